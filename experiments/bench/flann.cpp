// flann.cpp: a comparison side of the kNN benchmark, FLANN's
// KDTreeSingleIndex (L2_Simple: squared distances, float, 3-d) behind a
// small C interface so the harness (bench.c) stays C. Written from FLANN's
// public API (flann/algorithms/kdtree_single_index.h, nn_index.h): the
// index is built over the points in place, and each batch is one call of
// the documented radiusSearch with SearchParams::max_neighbors = k, which
// is FLANN's "k nearest within a radius" (sorted by distance), or of the
// documented knnSearch with the neighbours beyond the cap dropped after.
// The radius test is strict, so the cap is passed as the next float above
// it to keep every point with d2 <= cap, as our tree does. Compiled
// without OpenMP, so FLANN searches on the calling thread only.
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <vector>

#include <flann/algorithms/dist.h>
#include <flann/algorithms/kdtree_single_index.h>

namespace {

typedef flann::KDTreeSingleIndex<flann::L2_Simple<float>> index_t;

struct handle {
    flann::Matrix<float> data;
    index_t *index;
    std::vector<size_t> idx;  // nq x k, reused across batches
    std::vector<float> dists; // nq x k
};

} // namespace

extern "C" {

void *flann_peer_build(const float *pts, uint32_t n, uint32_t leaf)
{
    handle *h = new handle;
    h->data = flann::Matrix<float>(const_cast<float *>(pts), n, 3);
    h->index = new index_t(h->data, flann::KDTreeSingleIndexParams((int)leaf, true));
    h->index->buildIndex();
    return h;
}

void flann_peer_free(void *hp)
{
    handle *h = static_cast<handle *>(hp);
    delete h->index;
    delete h;
}

/* Answers nq queries (xyz triples) in one FLANN call: radiusSearch with
 * max_neighbors = k (knn == 0), or knnSearch (knn != 0: FLANN's plain k
 * nearest, no cap, its default result set for this k) followed by dropping
 * the neighbours beyond the cap, which leaves the k nearest within it.
 * Writes each query's neighbours (input indices, ascending distance,
 * UINT32_MAX after the last found) to out_idx[nq * k] when it is not NULL;
 * returns the total found within the cap. */
uint64_t flann_peer_knn_batch(void *hp, const float *q, uint32_t nq, uint32_t k, float max_d2, int knn,
                              uint32_t *out_idx)
{
    handle *h = static_cast<handle *>(hp);
    h->idx.resize((size_t)nq * k);
    h->dists.resize((size_t)nq * k);
    flann::Matrix<float> queries(const_cast<float *>(q), nq, 3);
    flann::Matrix<size_t> indices(h->idx.data(), nq, k);
    flann::Matrix<float> dists(h->dists.data(), nq, k);
    flann::SearchParams sp(flann::FLANN_CHECKS_UNLIMITED, 0.0f, true);
    sp.cores = 1;
    if (knn) {
        h->index->knnSearch(queries, indices, dists, k, sp);
    } else {
        sp.max_neighbors = (int)k;
        h->index->radiusSearch(queries, indices, dists, std::nextafter(max_d2, INFINITY), sp);
    }
    // a row ends at its first entry beyond the cap: radiusSearch marks the
    // entry after its last with an infinite distance (the rest of the row is
    // left as it was), knnSearch fills the row in ascending distance
    uint64_t found = 0;
    for (size_t row = 0; row < nq; row++) {
        const float *d = &h->dists[row * k];
        size_t n = 0;
        while (n < k && d[n] <= max_d2)
            n++;
        found += n;
        if (out_idx)
            for (size_t j = 0; j < k; j++)
                out_idx[row * k + j] = j < n ? (uint32_t)h->idx[row * k + j] : UINT32_MAX;
    }
    return found;
}

}
