/* test_kdtree_nearest: kd_nearest_if, the nearest point that passes a
 * predicate, against brute force, with and without a hint. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "check.h"
#include "helpers.h"
#include "rng.h"
#include "tests.h"

static float dist2(const float *p, const float q[3])
{
    float dx = p[0] - q[0], dy = p[1] - q[1], dz = p[2] - q[2];
    return dx * dx + dy * dy + dz * dz;
}

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

static int pred_even_orig(uint32_t i, const void *ctx)
{
    const uint32_t *perm = ctx;
    return perm[i] % 2 == 0;
}

void test_kdtree_nearest_if(void)
{
    uint32_t n = 2000;
    float *pts = random_points(n, 11, 0);
    uint32_t *perm = malloc(sizeof(uint32_t) * n);
    kd_tree t;
    CHECK(kd_build(&t, pts, n, KD_DEFAULT_LEAF, perm, 1) == PM_OK);
    rng_stream s = rng_make(5, 5);
    for (int qi = 0; qi < 200; qi++) {
        float q[3];
        for (int a = 0; a < 3; a++)
            q[a] = (float)(rng_next_double(&s) * 2.4 - 1.2);
        float cap = qi % 2 ? INFINITY : 0.01f;
        float best = INFINITY;
        uint32_t best_i = KD_NONE;
        for (uint32_t i = 0; i < n; i += 2) {
            float d = dist2(pts + 3 * i, q);
            if (d <= cap && d < best) {
                best = d;
                best_i = i;
            }
        }
        float d2;
        uint32_t got = kd_nearest_if(&t, q, cap, pred_even_orig, perm, KD_NONE, &d2);
        CHECK(got == KD_NONE ? best_i == KD_NONE : (perm[got] % 2 == 0 && d2 == best));
        /* without predicate: the plain nearest */
        uint32_t idx;
        float dd, r2;
        uint32_t k = helper_knn(&t, q, 1, cap, &idx, &dd, &r2);
        uint32_t g2 = kd_nearest_if(&t, q, cap, NULL, NULL, KD_NONE, &d2);
        CHECK(k == (g2 != KD_NONE) && (k == 0 || d2 == dd));
    }
    kd_free(&t);
    free(perm);
    free(pts);
}

/* kd_nearest_if's answer does not depend on its hint: the answer itself,
 * a point that qualifies elsewhere, one that does not qualify, one beyond
 * the cap, and the previous query's answer on a coherent walk (queries a
 * fraction of a leaf apart, and jumps) all give the hintless answer, over
 * trees of one leaf, odd counts and uneven leaves. */
void test_kdtree_nearest_if_hints(void)
{
    uint32_t sizes[] = {1, 7, 13, 100, 2001, 4096};
    for (size_t si = 0; si < sizeof sizes / sizeof sizes[0]; si++) {
        uint32_t n = sizes[si];
        float *pts = random_points(n, 17 + (uint64_t)si, 0);
        uint32_t *perm = malloc(sizeof(uint32_t) * n);
        kd_tree t;
        CHECK(kd_build(&t, pts, n, KD_DEFAULT_LEAF, perm, 1) == PM_OK);
        rng_stream s = rng_make(9, si);
        float q[3] = {0.0f, 0.0f, 0.0f};
        uint32_t prev = KD_NONE;
        int differ = 0;
        for (int qi = 0; qi < 400; qi++) {
            float step = qi % 50 == 0 ? 1.0f : 0.02f; /* mostly small steps, now and then a jump */
            for (int a = 0; a < 3; a++) {
                q[a] += (float)((rng_next_double(&s) * 2.0 - 1.0) * step);
                q[a] = q[a] > 1.3f ? 1.3f : (q[a] < -1.3f ? -1.3f : q[a]);
            }
            float cap = qi % 3 == 0 ? 0.05f : INFINITY;
            float want_d2;
            uint32_t want = kd_nearest_if(&t, q, cap, pred_even_orig, perm, KD_NONE, &want_d2);
            uint32_t hints[5] = {want, (uint32_t)(rng_next_u64(&s) % n), KD_NONE, KD_NONE, prev};
            for (uint32_t i = 0; i < n; i++) { /* a point that does not qualify */
                if (perm[i] % 2) {
                    hints[2] = i;
                    break;
                }
            }
            float far = -1.0f; /* the point farthest from q: beyond a small cap */
            for (uint32_t i = 0; i < n; i++) {
                float p[3], d;
                kd_point(&t, i, p);
                d = dist2(p, q);
                if (d > far) {
                    far = d;
                    hints[3] = i;
                }
            }
            for (int h = 0; h < 5; h++) {
                float d2;
                uint32_t got = kd_nearest_if(&t, q, cap, pred_even_orig, perm, hints[h], &d2);
                differ += got != want || (got != KD_NONE && d2 != want_d2);
            }
            float d2;
            prev = kd_nearest_if(&t, q, cap, NULL, NULL, prev, &d2);
        }
        CHECK_MSG(differ == 0, "n = %u: %d answers depend on the hint", n, differ);
        kd_free(&t);
        free(perm);
        free(pts);
    }
}
