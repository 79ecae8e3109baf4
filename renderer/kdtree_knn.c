/* kdtree_knn: the k-nearest search's entry points, query state, passes and
 * output, and the heap search used without a buffer (renderer/README.md). */
#include "kdtree_impl.h"

#include <assert.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#define KD_MAX_BUF_K (1u << 24) /* kd_query: larger k (16M) takes the heap in the output, no buffer */
#define KD_PACKET_SPREAD 4.0f   /* a packet's squared box diagonal at most this many squared start radii */

/* ---- k nearest: without a buffer ----
 * When no candidate buffer is at hand (k beyond KD_MAX_BUF_K, or no memory
 * for a state's), a max-heap of keys lives in idx/d2 themselves.
 * Slower, same result. */
static inline uint64_t heap_key(const uint32_t *hi, const float *hd, uint32_t j)
{
    return pack_key(hd[j], hi[j]);
}

static uint32_t knn_heap(const kd_tree *t, const float q[3], uint32_t k, float max_d2, uint32_t *hi, float *hd,
                         float *r2, kd_work *w)
{
    uint64_t nodes = 0, points = 0;
    uint32_t n = 0;
    float worst = max_d2, bound = prune_bound(worst);
    kd_frame stack[KD_STACK];
    int sp = 0;
    float off[3];
    float rd = root_offsets(t, q, off);
    uint32_t node = 0;
    if (rd <= bound) {
        do {
            nodes += descent_length(t, node) + 1;
            uint32_t leaf = descend(t, node, q, rd, off, bound, stack, &sp);
            uint32_t beg = t->leaf_start[leaf], end = t->leaf_start[leaf + 1];
            points += end - beg;
            for (uint32_t c = beg; c < end; c += KD_CHUNK) {
                float dd[KD_CHUNK];
                chunk_d2(t, c, q[0], q[1], q[2], dd);
                uint32_t m = end - c < KD_CHUNK ? end - c : KD_CHUNK;
                for (uint32_t j = 0; j < m; j++) {
                    float d = dd[j];
                    if (!(d <= worst))
                        continue;
                    uint64_t key = pack_key(d, c + j);
                    uint32_t at;
                    if (n < k) { /* sift up from the end */
                        at = n++;
                        while (at > 0 && heap_key(hi, hd, (at - 1) / 2) < key) {
                            uint32_t parent = (at - 1) / 2;
                            hd[at] = hd[parent];
                            hi[at] = hi[parent];
                            at = parent;
                        }
                    } else { /* replace the root, sift down */
                        if (key >= heap_key(hi, hd, 0))
                            continue;
                        at = 0;
                        for (;;) {
                            uint32_t ch = 2 * at + 1;
                            if (ch >= k)
                                break;
                            if (ch + 1 < k && heap_key(hi, hd, ch + 1) > heap_key(hi, hd, ch))
                                ch++;
                            if (heap_key(hi, hd, ch) <= key)
                                break;
                            hd[at] = hd[ch];
                            hi[at] = hi[ch];
                            at = ch;
                        }
                    }
                    hd[at] = d;
                    hi[at] = c + j;
                    if (n == k) {
                        worst = hd[0];
                        bound = prune_bound(worst);
                    }
                }
            }
        } while (pop(stack, &sp, bound, &node, &rd, off));
    }
    *r2 = n > 0 ? hd[0] : 0.0f;
    w->nodes += nodes;
    w->points += points;
    return n;
}

/* ---- k nearest: entry points ---- */

/* Candidate buffer entries for k (see kdtree_gather.inc: at least k + 2 chunks;
 * twice k so that a full buffer's selection is paid for by k appends). The
 * buffer is three regions of buf_entries(k) + KD_CHUNK keys: the gathered
 * candidates and kd_select_k's two scratch areas, each with slack for the
 * vector stores. */
static uint32_t buf_entries(uint32_t k)
{
    return 2 * k + 4 * KD_CHUNK;
}

static size_t buf_keys(uint32_t cap)
{
    return 3 * ((size_t)cap + KD_CHUNK);
}

/* How much wider than the last query's k-th radius (squared) to start: the
 * k-th distance of neighbouring queries varies about as 1/sqrt(k). */
static float start_slack(uint32_t k)
{
    return 1.0f + 2.5f / sqrtf((float)k);
}

/* The end of a search whose pass left n keys in buf (at least k, or all
 * within max_d2; distances up to r): the k smallest out, the hint kept.
 * The selection's scratch is s->buf's second and third regions. */
static uint32_t knn_finish(kd_query *s, const kd_ops *ops, uint64_t *buf, uint32_t n, uint32_t k, float r,
                           float max_d2, uint32_t *idx, float *d2, float *r2)
{
    if (n > k) {
        size_t stride = (size_t)s->cap + KD_CHUNK;
        kd_select_k(buf, s->buf + stride, s->buf + 2 * stride, n, k, r, ops);
        n = k;
    }
    float top = ops->output(buf, n, idx, d2);
    *r2 = top;
    s->hint_k = k;
    s->hint_r2 = n == k ? top : max_d2;
    return n;
}

/* The radius the next search of k starts from: the last query's k-th,
 * scaled to k and widened, or max_d2 without a guess. */
static float start_radius(const kd_query *s, uint32_t k, float max_d2)
{
    float r = max_d2;
    if (s->hint_k) {
        float g = s->hint_r2 * ((float)k / (float)s->hint_k) * start_slack(k);
        r = g < r ? g : r;
    }
    return r;
}

static const kd_ops *ops_of(const kd_query *s)
{
#if KD_HAVE_AVX2
    if (s->simd == KD_SIMD_AVX2)
        return &kd_ops_avx2;
#endif
    (void)s;
    return &kd_ops_base;
}

/* The search with a buffer of s->cap >= buf_entries(k) entries; k <= t->n. */
static uint32_t knn_run(const kd_tree *t, kd_query *s, const float q[3], uint32_t k, float max_d2, uint32_t *idx,
                        float *d2, float *r2)
{
    assert(k >= 1 && k <= t->n && s->cap >= buf_entries(k));
    float r = start_radius(s, k, max_d2);
    const kd_ops *ops = ops_of(s);
    uint64_t *buf = s->buf;
    uint32_t n;
    int small = k <= KD_SMALL_K;
    for (int pass = 0;; pass++) {
        float used = r;
#if KD_HAVE_AVX2
        if (s->simd == KD_SIMD_AVX2)
            n = small ? kd_gather_small_avx2(t, q, k, buf, s->cap, &r, &s->work)
                      : kd_gather_avx2(t, q, k, buf, s->cap, &r, &s->work);
        else
#endif
            n = small ? kd_gather_small_base(t, q, k, buf, s->cap, &r, &s->work)
                      : kd_gather_base(t, q, k, buf, s->cap, &r, &s->work);
        s->passes++;
        if (n >= k || !(used < max_d2))
            break;
        /* too few within r: widen (2-d density: count ~ r2), at most 3 times before the cap */
        float g = n > 0 ? used * 1.5f * (float)k / (float)n : used * 4.0f;
        r = (pass < 3 && g > used && g < max_d2) ? g : max_d2;
    }
    s->queries++;
    return knn_finish(s, ops, buf, n, k, r, max_d2, idx, d2, r2);
}

pm_status kd_query_init(kd_query *s, uint32_t k_max)
{
    memset(s, 0, sizeof *s);
    s->simd = kd_simd_best();
    uint32_t cap = buf_entries(k_max == 0 ? 1 : (k_max < KD_MAX_BUF_K ? k_max : KD_MAX_BUF_K));
    s->buf = malloc(sizeof(uint64_t) * buf_keys(cap));
    if (!s->buf)
        return PM_ERR_NOMEM;
    s->cap = cap;
    return PM_OK;
}

void kd_query_free(kd_query *s)
{
    free(s->buf);
    free(s->pbuf);
    memset(s, 0, sizeof *s);
}

void kd_query_forget(kd_query *s)
{
    s->hint_k = 0;
    s->hint_r2 = 0.0f;
}

kd_simd kd_query_simd(kd_query *s, kd_simd want)
{
    kd_simd best = kd_simd_best();
    s->simd = want < best ? KD_SIMD_BASE : best;
    return s->simd;
}

uint32_t kd_query_knn(const kd_tree *t, kd_query *s, const float q[3], uint32_t k, float max_d2, uint32_t *idx,
                      float *d2, float *r2)
{
    *r2 = 0.0f;
    if (k == 0 || t->n == 0 || !(max_d2 >= 0.0f))
        return 0;
    k = k < t->n ? k : t->n;
    if (k > KD_MAX_BUF_K) {
        s->queries++;
        return knn_heap(t, q, k, max_d2, idx, d2, r2, &s->work);
    }
    if (s->cap < buf_entries(k)) {
        uint64_t *b = realloc(s->buf, sizeof(uint64_t) * buf_keys(buf_entries(k)));
        if (!b) {
            s->queries++;
            return knn_heap(t, q, k, max_d2, idx, d2, r2, &s->work);
        }
        s->buf = b;
        s->cap = buf_entries(k);
    }
    return knn_run(t, s, q, k, max_d2, idx, d2, r2);
}

/* ---- packets ---- */

/* Makes s ready for a packet of k: a buffer of at least buf_entries(k) and
 * KD_PACKET candidate regions as long as its cap. Returns 0 when memory
 * runs out (the queries then go one by one). */
static int packet_ready(kd_query *s, uint32_t k)
{
    if (k > KD_MAX_BUF_K)
        return 0;
    if (s->cap < buf_entries(k)) {
        uint64_t *b = realloc(s->buf, sizeof(uint64_t) * buf_keys(buf_entries(k)));
        if (!b)
            return 0;
        s->buf = b;
        s->cap = buf_entries(k);
    }
    if (!s->pbuf || s->pcap != s->cap) {
        free(s->pbuf);
        s->pbuf = malloc(sizeof(uint64_t) * KD_PACKET * ((size_t)s->cap + KD_CHUNK));
        s->pcap = s->pbuf ? s->cap : 0;
    }
    return s->pbuf != NULL;
}

void kd_query_knn_packet(const kd_tree *t, kd_query *s, const float (*q)[3], uint32_t m, uint32_t k, float max_d2,
                         uint32_t *const *idx, float *const *d2, uint32_t *found, float *r2)
{
    assert(m <= KD_PACKET);
    int alone = m < 2 || k == 0 || t->n == 0 || !(max_d2 >= 0.0f);
    for (uint32_t j = 0; j < m && !alone; j++) /* a NaN query would spoil the packet's box */
        alone = !(q[j][0] == q[j][0] && q[j][1] == q[j][1] && q[j][2] == q[j][2]);
    uint32_t kk = k < t->n ? k : t->n;
    if (alone || !packet_ready(s, kk)) {
        for (uint32_t j = 0; j < m; j++)
            found[j] = kd_query_knn(t, s, q[j], k, max_d2, idx[j], d2[j], &r2[j]);
        return;
    }
    float start = start_radius(s, kk, max_d2);
    /* queries spread wider than the search radius share little of the walk
     * and widen it for all: those go one by one */
    float w2 = 0.0f;
    for (int a = 0; a < 3; a++) {
        float lo = q[0][a], hi = q[0][a];
        for (uint32_t j = 1; j < m; j++) {
            lo = q[j][a] < lo ? q[j][a] : lo;
            hi = q[j][a] > hi ? q[j][a] : hi;
        }
        w2 += (hi - lo) * (hi - lo);
    }
    if (!(w2 <= KD_PACKET_SPREAD * start)) {
        for (uint32_t j = 0; j < m; j++)
            found[j] = kd_query_knn(t, s, q[j], k, max_d2, idx[j], d2[j], &r2[j]);
        return;
    }
    const kd_ops *ops = ops_of(s);
    uint64_t *bufs[KD_PACKET];
    float r[KD_PACKET];
    uint32_t n[KD_PACKET];
    for (uint32_t j = 0; j < m; j++) {
        bufs[j] = s->pbuf + j * ((size_t)s->cap + KD_CHUNK);
        r[j] = start;
    }
    int small = kk <= KD_SMALL_K;
#if KD_HAVE_AVX2
    if (s->simd == KD_SIMD_AVX2)
        (small ? kd_packet_small_avx2 : kd_packet_avx2)(t, q, m, kk, bufs, s->cap, r, n, &s->work);
    else
#endif
        (small ? kd_packet_small_base : kd_packet_base)(t, q, m, kk, bufs, s->cap, r, n, &s->work);
    s->passes++;
    for (uint32_t j = 0; j < m; j++) {
        if (n[j] >= kk || !(start < max_d2)) {
            s->queries++;
            found[j] = knn_finish(s, ops, bufs[j], n[j], kk, r[j], max_d2, idx[j], d2[j], &r2[j]);
        } else { /* too few within the packet's radius: this one alone, widening */
            found[j] = kd_query_knn(t, s, q[j], k, max_d2, idx[j], d2[j], &r2[j]);
        }
    }
}
