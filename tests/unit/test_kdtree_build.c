/* test_kdtree_build: kd_build and kd_build_items. The build's peak memory
 * is what kd_build_peak_bytes says; the tree is the same for any thread
 * count; kd_build_items (in place, on the map's 32-byte items) builds
 * kd_build's tree and leaves each payload with its point. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "check.h"
#include "helpers.h"
#include "mem.h"
#include "rng.h"
#include "tests.h"

static float *random_points(uint32_t n, uint64_t seed, int clustered)
{
    float *p = malloc(sizeof(float) * 3 * (n + 1));
    rng_stream s = rng_make(seed, 0);
    for (uint32_t i = 0; i < 3 * n; i++) {
        double u = rng_next_double(&s);
        p[i] = clustered ? (float)floor(u * 4.0) * 0.25f : (float)(u * 2.0 - 1.0);
    }
    return p;
}

/* kd_build_peak_bytes is what the build holds at its peak: the tree's
 * arrays (kd_bytes once built) and its working copy of 16 bytes a point;
 * kd_point reads back the points in leaf order. */
void test_kdtree_build_memory(void)
{
    const uint32_t sizes[] = {0, 1, 12, 13, 1000, 4099};
    const uint32_t leaves[] = {0, 1, 3, KD_DEFAULT_LEAF, 1000};
    for (size_t si = 0; si < sizeof sizes / sizeof sizes[0]; si++)
        for (size_t li = 0; li < sizeof leaves / sizeof leaves[0]; li++) {
            uint32_t n = sizes[si];
            float *pts = random_points(n, 31 + n, 0);
            uint32_t *perm = malloc(sizeof(uint32_t) * (n + 1));
            kd_tree t;
            CHECK(kd_build(&t, pts, n, leaves[li], perm, 1) == PM_OK);
            double want = (double)kd_bytes(&t) + 16.0 * (n > 0 ? n : 1);
            CHECK(kd_tree_bytes(n, leaves[li]) == (double)kd_bytes(&t));
            CHECK_MSG(kd_build_peak_bytes(n, leaves[li]) == want, "n=%u leaf=%u: %.0f bytes, want %.0f", n,
                      leaves[li], kd_build_peak_bytes(n, leaves[li]), want);
            int same = 1;
            for (uint32_t i = 0; i < n; i++) {
                float p[3];
                kd_point(&t, i, p);
                same &= memcmp(p, pts + 3 * (size_t)perm[i], sizeof p) == 0;
            }
            CHECK_MSG(same, "n=%u: kd_point differs from the input point", n);
            kd_free(&t);
            free(perm);
            free(pts);
        }
    /* beyond what a tree holds: still a number, growing with n */
    CHECK(kd_build_peak_bytes(1e12, KD_DEFAULT_LEAF) > 16e12);
}

/* 1 when a and b are the same tree to the bit (every array, the points'
 * padding included) and their permutations agree; else 0. */
static int same_tree(const kd_tree *a, const uint32_t *pa, const kd_tree *b, const uint32_t *pb)
{
    if (a->n != b->n || a->nleaves != b->nleaves || a->scan_h != b->scan_h)
        return 0;
    if (memcmp(a->lo, b->lo, sizeof a->lo) || memcmp(a->hi, b->hi, sizeof a->hi))
        return 0;
    size_t inner = a->nleaves - 1, pts = (size_t)a->n + 8; /* KD_CHUNK floats of padding */
    return !memcmp(a->split, b->split, inner * sizeof(float)) && !memcmp(a->axis, b->axis, inner) &&
           !memcmp(a->leaf_start, b->leaf_start, (a->nleaves + 1) * sizeof(uint32_t)) &&
           !memcmp(a->x, b->x, pts * sizeof(float)) && !memcmp(a->y, b->y, pts * sizeof(float)) &&
           !memcmp(a->z, b->z, pts * sizeof(float)) && !memcmp(pa, pb, a->n * sizeof(uint32_t));
}

/* The build on 2 and 3 threads gives the 1-thread tree to the bit, over
 * points with many equal coordinates (ties in every selection) and sizes
 * spanning several copy blocks; as negative controls, the same points with
 * two of them swapped in the input, or one split value changed, do not
 * compare equal. */
void test_kdtree_build_threads(void)
{
    const uint32_t sizes[] = {0, 5, 1000, 70001, 200003};
    const uint32_t leaves[] = {KD_DEFAULT_LEAF, 1};
    for (size_t si = 0; si < sizeof sizes / sizeof sizes[0]; si++)
        for (size_t li = 0; li < sizeof leaves / sizeof leaves[0]; li++) {
            uint32_t n = sizes[si];
            float *pts = malloc(sizeof(float) * 3 * (n ? n : 1));
            rng_stream s = rng_make(77, n);
            for (uint32_t i = 0; i < 3 * n; i++) {
                double u = rng_next_double(&s);
                /* a third of the coordinates on a coarse grid of 9 values */
                pts[i] = i % 3 == 1 ? (float)(floor(u * 9.0) / 8.0 - 0.5) : (float)(u - 0.5);
            }
            uint32_t *p1 = malloc(sizeof(uint32_t) * (n + 1)), *pn = malloc(sizeof(uint32_t) * (n + 1));
            kd_tree t1, tn;
            CHECK(kd_build(&t1, pts, n, leaves[li], p1, 1) == PM_OK);
            for (unsigned th = 2; th <= 3; th++) {
                CHECK(kd_build(&tn, pts, n, leaves[li], pn, th) == PM_OK);
                CHECK_MSG(same_tree(&t1, p1, &tn, pn), "n=%u leaf=%u: %u threads build another tree", n,
                          leaves[li], th);
                kd_free(&tn);
            }
            if (n >= 1000) {
                /* negative controls */
                float keep[3];
                memcpy(keep, pts, sizeof keep);
                memcpy(pts, pts + 3 * (n / 2), sizeof keep);
                memcpy(pts + 3 * (n / 2), keep, sizeof keep);
                CHECK(kd_build(&tn, pts, n, leaves[li], pn, 2) == PM_OK);
                CHECK_MSG(!same_tree(&t1, p1, &tn, pn), "n=%u: swapped input compares equal", n);
                kd_free(&tn);
                t1.split[t1.nleaves / 2] = nextafterf(t1.split[t1.nleaves / 2], INFINITY);
                memcpy(pts + 3 * (n / 2), pts, sizeof keep);
                memcpy(pts, keep, sizeof keep);
                CHECK(kd_build(&tn, pts, n, leaves[li], pn, 2) == PM_OK);
                CHECK_MSG(!same_tree(&t1, p1, &tn, pn), "n=%u: a changed split compares equal", n);
                kd_free(&tn);
            }
            kd_free(&t1);
            free(p1);
            free(pn);
            free(pts);
        }
}

/* n points with a third of the coordinates on a coarse grid (ties in every
 * selection). */
static float *tie_points(uint32_t n, uint64_t seed)
{
    float *pts = malloc(sizeof(float) * 3 * (n ? n : 1));
    rng_stream s = rng_make(seed, n);
    for (uint32_t i = 0; i < 3 * n; i++) {
        double u = rng_next_double(&s);
        pts[i] = i % 3 == 1 ? (float)(floor(u * 9.0) / 8.0 - 0.5) : (float)(u - 0.5);
    }
    return pts;
}

/* The items of pts, each payload its input index and a pattern. */
static kd_build_item *items_of(const float *pts, uint32_t n)
{
    kd_build_item *it = mem_alloc(sizeof(kd_build_item) * (n ? n : 1));
    for (uint32_t i = 0; i < n; i++) {
        memcpy(it[i].p, pts + 3 * (size_t)i, sizeof it[i].p);
        for (size_t b = 0; b < sizeof it[i].payload; b++)
            it[i].payload[b] = (unsigned char)(i * 7u + b);
        memcpy(it[i].payload, &i, sizeof i);
    }
    return it;
}

/* kd_build_items on 1, 2 and 3 threads gives kd_build's tree, and item i
 * ends holding leaf point i with the payload of input perm[i]; as negative
 * controls, two input points swapped give another tree, and a payload
 * moved out of step is seen. */
void test_kdtree_build_items(void)
{
    const uint32_t sizes[] = {0, 1, 5, 1000, 70001, 200003};
    for (size_t si = 0; si < sizeof sizes / sizeof sizes[0]; si++) {
        uint32_t n = sizes[si];
        float *pts = tie_points(n, 91);
        uint32_t *perm = malloc(sizeof(uint32_t) * (n + 1));
        kd_tree ref;
        CHECK(kd_build(&ref, pts, n, KD_DEFAULT_LEAF, perm, 1) == PM_OK);
        for (unsigned th = 1; th <= 3; th++) {
            kd_build_item *it = items_of(pts, n);
            kd_tree t;
            CHECK(kd_build_items(&t, it, n, KD_DEFAULT_LEAF, th) == PM_OK);
            CHECK_MSG(helper_trees_equal(&ref, &t), "n=%u, %u threads: another tree than kd_build's", n, th);
            int ok = 1;
            for (uint32_t i = 0; i < n; i++) {
                uint32_t id;
                memcpy(&id, it[i].payload, sizeof id);
                ok &= id == perm[i] && it[i].payload[4] == (unsigned char)(id * 7u + 4u) &&
                      memcmp(it[i].p, pts + 3 * (size_t)id, sizeof it[i].p) == 0 && it[i].p[0] == t.x[i];
            }
            CHECK_MSG(ok, "n=%u, %u threads: an item's payload is not its point's", n, th);
            if (n >= 1000 && th == 2) {
                /* negative control: the check sees a payload out of step */
                unsigned char keep = it[n / 3].payload[0];
                it[n / 3].payload[0] ^= 1u;
                uint32_t id;
                memcpy(&id, it[n / 3].payload, sizeof id);
                CHECK(id != perm[n / 3]);
                it[n / 3].payload[0] = keep;
            }
            kd_free(&t);
            mem_free(it);
        }
        if (n >= 1000) {
            /* negative control: swapped inputs build another tree */
            float keep[3];
            memcpy(keep, pts, sizeof keep);
            memcpy(pts, pts + 3 * (n / 2), sizeof keep);
            memcpy(pts + 3 * (n / 2), keep, sizeof keep);
            kd_build_item *it = items_of(pts, n);
            kd_tree t;
            CHECK(kd_build_items(&t, it, n, KD_DEFAULT_LEAF, 2) == PM_OK);
            CHECK_MSG(!helper_trees_equal(&ref, &t), "n=%u: swapped input compares equal", n);
            kd_free(&t);
            mem_free(it);
        }
        kd_free(&ref);
        free(perm);
        free(pts);
    }
}
