// nano.cpp: the comparison side of the kNN benchmark, nanoflann's
// KDTreeSingleIndexAdaptor (L2_Simple, float, 3-d) behind a small C
// interface so the harness (bench.c) stays C. The radius cap is enforced by
// our own result set: it keeps the k nearest with d2 <= cap, and reports the
// cap as the pruning distance until it holds k points, so nanoflann prunes
// with the cap exactly as our tree does.
#include <cstdint>
#include <cstddef>
#include <cmath>
#include <vector>
#include <nanoflann.hpp>

namespace {

struct cloud {
    const float *p;
    size_t n;
    size_t kdtree_get_point_count() const { return n; }
    float kdtree_get_pt(size_t i, size_t d) const { return p[3 * i + d]; }
    template <class BBOX> bool kdtree_get_bbox(BBOX &) const { return false; }
};

typedef nanoflann::KDTreeSingleIndexAdaptor<nanoflann::L2_Simple_Adaptor<float, cloud>, cloud, 3, uint32_t> tree_t;

// k nearest within a squared-distance cap, ascending by insertion.
class capped_knn {
  public:
    typedef float DistanceType;
    typedef uint32_t IndexType;
    typedef size_t CountType;
    capped_knn(uint32_t k, float cap, uint32_t *idx, float *d2)
        : k_(k), n_(0), limit_(std::nextafter(cap, INFINITY)), idx_(idx), d2_(d2) {}
    size_t size() const { return n_; }
    bool full() const { return n_ == k_; }
    float worstDist() const { return n_ == k_ ? d2_[k_ - 1] : limit_; }
    bool addPoint(float d, uint32_t i) {
        if (!(d < worstDist()))
            return true;
        uint32_t j = n_ < k_ ? n_++ : k_ - 1;
        for (; j > 0 && d2_[j - 1] > d; j--) {
            d2_[j] = d2_[j - 1];
            idx_[j] = idx_[j - 1];
        }
        d2_[j] = d;
        idx_[j] = i;
        return true;
    }

  private:
    uint32_t k_, n_;
    float limit_;
    uint32_t *idx_;
    float *d2_;
};

struct handle {
    cloud c;
    tree_t *t;
};

} // namespace

extern "C" {

void *nano_build(const float *pts, uint32_t n, uint32_t leaf)
{
    handle *h = new handle;
    h->c.p = pts;
    h->c.n = n;
    h->t = new tree_t(3, h->c, nanoflann::KDTreeSingleIndexAdaptorParams(leaf));
    return h;
}

void nano_free(void *hp)
{
    handle *h = static_cast<handle *>(hp);
    delete h->t;
    delete h;
}

/* Answers nq queries (xyz triples); returns the total neighbours found and
 * adds the sum of every query's largest squared distance to *r2sum. */
uint64_t nano_knn_batch(void *hp, const float *q, uint32_t nq, uint32_t k, float max_d2, uint32_t *idx,
                        float *d2, double *r2sum)
{
    const handle *h = static_cast<const handle *>(hp);
    uint64_t total = 0;
    double s = 0.0;
    for (uint32_t i = 0; i < nq; i++) {
        capped_knn rs(k, max_d2, idx, d2);
        h->t->findNeighbors(rs, q + 3 * (size_t)i, nanoflann::SearchParams());
        total += rs.size();
        if (rs.size())
            s += d2[rs.size() - 1];
    }
    *r2sum += s;
    return total;
}

/* The same search, each query's neighbours (input indices, ascending
 * distance, UINT32_MAX after the last found) written to out_idx[nq * k]
 * for the neighbour-set check; returns the total found. */
uint64_t nano_knn_collect(void *hp, const float *q, uint32_t nq, uint32_t k, float max_d2, uint32_t *out_idx)
{
    const handle *h = static_cast<const handle *>(hp);
    uint64_t total = 0;
    std::vector<float> d2(k);
    for (uint32_t i = 0; i < nq; i++) {
        uint32_t *o = out_idx + (size_t)i * k;
        capped_knn rs(k, max_d2, o, d2.data());
        h->t->findNeighbors(rs, q + 3 * (size_t)i, nanoflann::SearchParams());
        for (size_t j = rs.size(); j < k; j++)
            o[j] = UINT32_MAX;
        total += rs.size();
    }
    return total;
}

}
