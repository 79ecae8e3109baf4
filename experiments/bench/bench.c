/* bench: the performance harness (not a test). Builds the real
 * photon maps of a scene, takes the eye pass's diffuse hit points as kNN
 * queries (16x16-tile order and shuffled), and times our kd-tree against
 * nanoflann side by side in one process; then the representative lookup,
 * the eye pass on 1 and 2 threads, and the memory per photon. Prints
 * Markdown on stdout. With --peers, the kNN against FLANN, scipy's
 * cKDTree and nanoflann instead (CSV).
 *
 *   bench [--scene F] [--reps R] [--qw W --qh H] [--icount] [--sizes a,b,c]
 *         [--ks a,b,c] [--knn-only] [--peers DIR [--python P]]
 *
 * --peers DIR: instead of the tables, the kNN against every peer on the
 * largest of --sizes, on two query streams: pixel centres in tile order
 * ("tiles") and the eye pass's own, four subpixel samples per pixel of a
 * quarter as many pixels ("subpixels"): ours (state carried from query to
 * query; also by packets of four consecutive queries, kd_query_knn_packet,
 * and stateless, each search from the cap), nanoflann, FLANN (flann.cpp: its
 * knnSearch and its radiusSearch) and scipy's cKDTree (ckdtree.py, a co-process run with interpreter P,
 * default /usr/bin/python3, talking through pipes; DIR holds the files it
 * reads and writes). Each rep times the five on the same queries one after
 * another; every peer's neighbour sets are checked against ours, and ours
 * against brute force on a sample (see check_sets for ties). Prints CSV
 * rows for report.py peers.
 *
 * --ks: the k of the kNN tables (default 1,10,20,50,100); --knn-only: the
 * kNN tables alone (no build, lookup or eye-pass timings), for a quick
 * side-by-side reading of one cell.
 * --icount: few queries per cell (ours, ours by packets of four, ours
 * stateless, nanoflann and FLANN's knnSearch; the orders tiles, shuffled and
 * the subpixel stream, whole pixels sampled),
 * each cell's loop bracketed by callgrind
 * client requests (run under valgrind --tool=callgrind --instr-atstart=no);
 * run.sh turns the dumps into instructions per query. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>
#include <sys/types.h>
#include <sys/wait.h>
#include <unistd.h>

#include <valgrind/callgrind.h>

#include "camera.h"
#include "clock.h"
#include "config.h"
#include "estimate.h"
#include "kdtree.h"
#include "material.h"
#include "parallel.h"
#include "photons.h"
#include "render.h"
#include "reps.h"
#include "rng.h"
#include "scene.h"
#include "stats.h"

void *nano_build(const float *pts, uint32_t n, uint32_t leaf);
void nano_free(void *h);
uint64_t nano_knn_batch(void *h, const float *q, uint32_t nq, uint32_t k, float max_d2, uint32_t *idx, float *d2,
                        double *r2sum);

uint64_t nano_knn_collect(void *h, const float *q, uint32_t nq, uint32_t k, float max_d2, uint32_t *out_idx);
void *flann_peer_build(const float *pts, uint32_t n, uint32_t leaf);
void flann_peer_free(void *h);
uint64_t flann_peer_knn_batch(void *h, const float *q, uint32_t nq, uint32_t k, float max_d2, int knn,
                              uint32_t *out_idx);

#define TILE 16u
#define MAXK 100u

typedef struct {
    uint32_t n;
    float *p;  /* xyz */
    float *nr; /* normal facing the viewer, xyz */
} qset;

static double now_s(void) { return (double)clock_now_ns() * 1e-9; }

/* A pure compute loop split over `threads` (64 items): the machine's own
 * 2-thread scaling at this moment, to read the eye pass's against. */
static void spin_item(uint64_t item, unsigned thread, void *ctx)
{
    (void)thread;
    volatile uint64_t *sink = ctx;
    uint64_t x = item;
    for (uint32_t i = 0; i < 2000000u; i++)
        x = x * 6364136223846793005ull + 1442695040888963407ull;
    *sink += x & 1;
}

static double spin_s(unsigned threads)
{
    static volatile uint64_t sink;
    double t0 = (double)clock_now_ns() * 1e-9;
    parallel_for(threads, 64, spin_item, (void *)&sink);
    return (double)clock_now_ns() * 1e-9 - t0;
}

/* CPU seconds of the whole process (all threads). */
static double cpu_s(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &ts);
    return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

static int cmp_double(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}

static double median(double *v, int n)
{
    qsort(v, (size_t)n, sizeof(double), cmp_double);
    return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

/* The first diffuse hit of the camera ray through each of the SxS subpixel
 * centres of each pixel of a WxH image (S = 1: the pixel centre), pixels
 * visited tile by tile and subpixels row by row, as the eye pass does.
 * Mirrors reflect; glass refracts (reflects on total internal reflection). */
static qset eye_points(const scene *sc, uint32_t w, uint32_t h, uint32_t S)
{
    size_t cap = (size_t)w * h * S * S;
    qset q = {0, malloc(sizeof(float) * 3 * cap), malloc(sizeof(float) * 3 * cap)};
    double aspect = (double)h / w;
    for (uint32_t ty = 0; ty < (h + TILE - 1) / TILE; ty++)
        for (uint32_t tx = 0; tx < (w + TILE - 1) / TILE; tx++)
            for (uint32_t y = ty * TILE; y < h && y < ty * TILE + TILE; y++)
                for (uint32_t x = tx * TILE; x < w && x < tx * TILE + TILE; x++)
                for (uint32_t sub = 0; sub < S * S; sub++) {
                    uint32_t sy = sub / S, sx = sub % S;
                    shape_ray r = camera_ray(sc, aspect, (x + (sx + 0.5) / S) / w, (y + (sy + 0.5) / S) / h);
                    for (int depth = 0; depth < 16; depth++) {
                        scene_hit hit;
                        if (!scene_intersect(sc, &r, INFINITY, &hit))
                            break;
                        const material *m = &sc->materials[sc->shapes[hit.shape].material];
                        if (m->kind == MATERIAL_LAMBERT) {
                            float *o = q.p + 3 * q.n, *on = q.nr + 3 * q.n;
                            o[0] = (float)hit.p.x, o[1] = (float)hit.p.y, o[2] = (float)hit.p.z;
                            on[0] = (float)hit.n.x, on[1] = (float)hit.n.y, on[2] = (float)hit.n.z;
                            q.n++;
                            break;
                        }
                        vec3 d;
                        if (m->kind == MATERIAL_GLASS &&
                            material_refract(r.dir, hit.n, hit.front ? 1.0 / m->ior : m->ior, &d))
                            r = scene_spawn(&hit, d, 0);
                        else
                            r = scene_spawn(&hit, material_reflect(r.dir, hit.n), 1);
                    }
                }
    return q;
}

static qset shuffled(const qset *a, uint64_t seed)
{
    qset q = {a->n, malloc(sizeof(float) * 3 * a->n), malloc(sizeof(float) * 3 * a->n)};
    memcpy(q.p, a->p, sizeof(float) * 3 * a->n);
    memcpy(q.nr, a->nr, sizeof(float) * 3 * a->n);
    rng_stream s = rng_make(seed, 7);
    for (uint32_t i = a->n; i > 1; i--) {
        uint32_t j = (uint32_t)(rng_next_u64(&s) % i);
        for (int c = 0; c < 3; c++) {
            float t = q.p[3 * (i - 1) + c]; q.p[3 * (i - 1) + c] = q.p[3 * j + c]; q.p[3 * j + c] = t;
            t = q.nr[3 * (i - 1) + c]; q.nr[3 * (i - 1) + c] = q.nr[3 * j + c]; q.nr[3 * j + c] = t;
        }
    }
    return q;
}

/* Our side: one kd_query state carried from query to query, as an eye-pass
 * thread carries its own (each query starts from the radius the previous
 * one needed; the results do not depend on it); STATELESS: the state is
 * forgotten before each query instead. */
static uint64_t ours_knn_run(const kd_tree *t, const float *q, uint32_t nq, uint32_t k, float max_d2,
                             uint32_t *idx, float *d2, double *r2sum, int stateless)
{
    kd_query st;
    if (kd_query_init(&st, k) != PM_OK) {
        fprintf(stderr, "bench: out of memory\n");
        exit(1);
    }
    uint64_t total = 0;
    double s = 0.0;
    for (uint32_t i = 0; i < nq; i++) {
        float r2;
        if (stateless)
            kd_query_forget(&st);
        total += kd_query_knn(t, &st, q + 3 * (size_t)i, k, max_d2, idx, d2, &r2);
        s += r2;
    }
    kd_query_free(&st);
    *r2sum += s;
    return total;
}

static uint64_t ours_knn_batch(const kd_tree *t, const float *q, uint32_t nq, uint32_t k, float max_d2,
                               uint32_t *idx, float *d2, double *r2sum)
{
    return ours_knn_run(t, q, nq, k, max_d2, idx, d2, r2sum, 0);
}

/* ours_knn_batch by packets of KD_PACKET consecutive queries
 * (kd_query_knn_packet), the state carried from packet to packet; the
 * answers of the last packet to idx/d2 (KD_PACKET x MAXK). */
static uint64_t ours_knn_packets(const kd_tree *t, const float *q, uint32_t nq, uint32_t k, float max_d2,
                                 uint32_t *idx, float *d2, double *r2sum)
{
    kd_query st;
    if (kd_query_init(&st, k) != PM_OK) {
        fprintf(stderr, "bench: out of memory\n");
        exit(1);
    }
    uint32_t *ip[KD_PACKET];
    float *dp[KD_PACKET];
    for (uint32_t j = 0; j < KD_PACKET; j++) {
        ip[j] = idx + j * (size_t)MAXK;
        dp[j] = d2 + j * (size_t)MAXK;
    }
    uint64_t total = 0;
    double s = 0.0;
    for (uint32_t i = 0; i < nq; i += KD_PACKET) {
        uint32_t m = nq - i < KD_PACKET ? nq - i : KD_PACKET, f[KD_PACKET];
        float r2[KD_PACKET];
        kd_query_knn_packet(t, &st, (const float(*)[3])(q + 3 * (size_t)i), m, k, max_d2, ip, dp, f, r2);
        for (uint32_t j = 0; j < m; j++) {
            total += f[j];
            s += r2[j];
        }
    }
    kd_query_free(&st);
    *r2sum += s;
    return total;
}

/* ours_knn_batch with no state between queries: each starts from the cap,
 * as a peer's single query does. */
static uint64_t ours_knn_stateless(const kd_tree *t, const float *q, uint32_t nq, uint32_t k, float max_d2,
                                   uint32_t *idx, float *d2, double *r2sum)
{
    return ours_knn_run(t, q, nq, k, max_d2, idx, d2, r2sum, 1);
}

static uint64_t lookup_batch(const reps_set *r, const photons_map *m, const qset *q, uint32_t nq,
                             const est_gather *g, double *esum)
{
    uint64_t found = 0;
    double s = 0.0;
    est_scratch *scratch = est_scratch_new(1, 1); /* the last answer starts the next search, as in the eye pass */
    if (!scratch)
        return 0;
    for (uint32_t i = 0; i < nq; i++) {
        const float *p = q->p + 3 * (size_t)i, *n = q->nr + 3 * (size_t)i;
        int f;
        vec3 e = reps_lookup(r, m, vec_make(p[0], p[1], p[2]), vec_make(n[0], n[1], n[2]), g, scratch, &f);
        found += (uint64_t)f;
        s += e.x;
    }
    est_scratch_delete(scratch, 1);
    *esum += s;
    return found;
}

/* ---- the kNN against the peers (--peers) ---- */

/* Our neighbours of each query as input indices (perm: leaf order ->
 * input), UINT32_MAX after the last found, the state carried from query to
 * query as in ours_knn_batch (or dropped before each, `stateless`); returns
 * the total. */
static uint64_t ours_collect(const kd_tree *t, const uint32_t *perm, const float *q, uint32_t nq, uint32_t k,
                             float max_d2, int stateless, uint32_t *out)
{
    kd_query st;
    if (kd_query_init(&st, k) != PM_OK) {
        fprintf(stderr, "bench: out of memory\n");
        exit(1);
    }
    uint64_t total = 0;
    float d2[MAXK];
    for (uint32_t i = 0; i < nq; i++) {
        float r2;
        uint32_t *o = out + (size_t)i * k;
        if (stateless)
            kd_query_forget(&st);
        uint32_t f = kd_query_knn(t, &st, q + 3 * (size_t)i, k, max_d2, o, d2, &r2);
        for (uint32_t j = 0; j < k; j++)
            o[j] = j < f ? perm[o[j]] : UINT32_MAX;
        total += f;
    }
    kd_query_free(&st);
    return total;
}

/* ours_collect by packets of KD_PACKET consecutive queries. */
static uint64_t ours_collect_packets(const kd_tree *t, const uint32_t *perm, const float *q, uint32_t nq, uint32_t k,
                                     float max_d2, uint32_t *out)
{
    kd_query st;
    if (kd_query_init(&st, k) != PM_OK) {
        fprintf(stderr, "bench: out of memory\n");
        exit(1);
    }
    static float d2s[KD_PACKET][MAXK];
    uint64_t total = 0;
    for (uint32_t i = 0; i < nq; i += KD_PACKET) {
        uint32_t m = nq - i < KD_PACKET ? nq - i : KD_PACKET, f[KD_PACKET];
        uint32_t *ip[KD_PACKET];
        float *dp[KD_PACKET], r2[KD_PACKET];
        for (uint32_t j = 0; j < KD_PACKET; j++) {
            ip[j] = out + (size_t)(i + (j < m ? j : 0)) * k;
            dp[j] = d2s[j];
        }
        kd_query_knn_packet(t, &st, (const float(*)[3])(q + 3 * (size_t)i), m, k, max_d2, ip, dp, f, r2);
        for (uint32_t j = 0; j < m; j++) {
            for (uint32_t c = 0; c < k; c++)
                ip[j][c] = c < f[j] ? perm[ip[j][c]] : UINT32_MAX;
            total += f[j];
        }
    }
    kd_query_free(&st);
    return total;
}

typedef struct {
    double d2;
    uint32_t id;
} neighbour;

static int cmp_neighbour_id(const void *a, const void *b)
{
    uint32_t x = ((const neighbour *)a)->id, y = ((const neighbour *)b)->id;
    return (x > y) - (x < y);
}

static double dist2(const float *p, const float *q)
{
    double dx = (double)p[0] - q[0], dy = (double)p[1] - q[1], dz = (double)p[2] - q[2];
    return dx * dx + dy * dy + dz * dz;
}

/* One query's answer as (squared distance in double, index) pairs sorted by
 * index; returns how many were found. */
static uint32_t load_set(const float *pts, const float *q, const uint32_t *ids, uint32_t k, neighbour *o,
                         double *max_d2)
{
    uint32_t n = 0;
    *max_d2 = 0.0;
    while (n < k && ids[n] != UINT32_MAX) {
        o[n].id = ids[n];
        o[n].d2 = dist2(pts + 3 * (size_t)ids[n], q);
        *max_d2 = o[n].d2 > *max_d2 ? o[n].d2 : *max_d2;
        n++;
    }
    qsort(o, n, sizeof *o, cmp_neighbour_id);
    return n;
}

#define TIE_REL 1e-6 /* distances this close (relative) count as equal */

static int near_boundary(double d2, double boundary)
{
    return fabs(d2 - boundary) <= TIE_REL * boundary;
}

/* The neighbour-set check of one query: 0 when the two answers hold the
 * same indices; 1 when they differ only by ties: every index that one
 * answer has and the other lacks lies (within TIE_REL, distances taken in
 * double from the same float coordinates) at the other answer's boundary,
 * its k-th distance when it found k, else the cap; 2 otherwise. */
static int check_one(const float *pts, const float *q, const uint32_t *a, const uint32_t *b, uint32_t k, double cap)
{
    neighbour sa[MAXK], sb[MAXK];
    double ma, mb;
    uint32_t na = load_set(pts, q, a, k, sa, &ma), nb = load_set(pts, q, b, k, sb, &mb);
    double ba = na == k ? ma : cap, bb = nb == k ? mb : cap; /* each answer's boundary */
    int differ = 0;
    uint32_t i = 0, j = 0;
    while (i < na || j < nb) {
        if (j == nb || (i < na && sa[i].id < sb[j].id)) { /* in a only */
            if (!near_boundary(sa[i].d2, bb))
                return 2;
            differ = 1, i++;
        } else if (i == na || sb[j].id < sa[i].id) { /* in b only */
            if (!near_boundary(sb[j].d2, ba))
                return 2;
            differ = 1, j++;
        } else {
            i++, j++;
        }
    }
    return differ;
}

/* Checks nq answers of `got` against `ref` (k per query); adds to
 * counts[0..2] the queries that match exactly, by ties only, and not, and
 * reports the first few mismatches on stderr. */
static void check_sets(const char *who, const float *pts, const float *q, uint32_t nq, uint32_t k, float cap,
                       const uint32_t *ref, const uint32_t *got, uint64_t counts[3])
{
    for (uint32_t i = 0; i < nq; i++) {
        int c = check_one(pts, q + 3 * (size_t)i, ref + (size_t)i * k, got + (size_t)i * k, k, cap);
        if (c == 2 && counts[2] < 5)
            fprintf(stderr, "bench: MISMATCH %s k=%u query %u\n", who, k, i);
        counts[c]++;
    }
}

/* Brute force: the k nearest of all n points to q with squared distance (in
 * double) at most cap, by (distance, index); UINT32_MAX after the last. */
static void brute_knn(const float *pts, uint32_t n, const float *q, uint32_t k, double cap, uint32_t *out)
{
    neighbour best[MAXK];
    uint32_t m = 0;
    for (uint32_t i = 0; i < n; i++) {
        double d = dist2(pts + 3 * (size_t)i, q);
        if (d > cap || (m == k && !(d < best[k - 1].d2)))
            continue;
        uint32_t j = m < k ? m++ : k - 1;
        for (; j > 0 && best[j - 1].d2 > d; j--)
            best[j] = best[j - 1];
        best[j].d2 = d;
        best[j].id = i;
    }
    for (uint32_t j = 0; j < k; j++)
        out[j] = j < m ? best[j].id : UINT32_MAX;
}

/* The cKDTree co-process: its stdin and stdout. */
typedef struct {
    FILE *to, *from;
    pid_t pid;
} coproc;

/* Starts `python script dir leaf` with pipes on its stdin and stdout and
 * waits for its "ready" line; returns its build seconds, or -1 when it
 * cannot start (c is then empty). */
static double coproc_start(coproc *c, const char *python, const char *script, const char *dir, uint32_t leaf)
{
    int in[2], out[2];
    memset(c, 0, sizeof *c);
    if (pipe(in) || pipe(out))
        return -1;
    fflush(stdout);
    pid_t pid = fork();
    if (pid < 0)
        return -1;
    if (pid == 0) {
        char leafs[16];
        snprintf(leafs, sizeof leafs, "%u", leaf);
        dup2(in[0], 0);
        dup2(out[1], 1);
        close(in[0]), close(in[1]), close(out[0]), close(out[1]);
        execl(python, python, script, dir, leafs, (char *)NULL);
        _exit(127);
    }
    close(in[0]), close(out[1]);
    c->pid = pid;
    c->to = fdopen(in[1], "w");
    c->from = fdopen(out[0], "r");
    double build;
    if (!c->to || !c->from || fscanf(c->from, " ready %lf", &build) != 1)
        return -1;
    return build;
}

/* One batch in the co-process: returns its own timing of the query call
 * (seconds) and sets *found, or -1 when it failed. */
static double coproc_batch(coproc *c, uint32_t k, float cap, int write, uint64_t *found)
{
    unsigned long long f;
    double t;
    fprintf(c->to, "%u %a %d\n", k, (double)cap, write);
    fflush(c->to);
    if (fscanf(c->from, " %lf %llu", &t, &f) != 2)
        return -1;
    *found = f;
    return t;
}

static void coproc_stop(coproc *c)
{
    if (c->to) {
        fprintf(c->to, "quit\n");
        fclose(c->to);
    }
    if (c->from)
        fclose(c->from);
    if (c->pid > 0)
        waitpid(c->pid, NULL, 0);
}

static int write_f32(const char *dir, const char *name, const float *v, size_t count)
{
    char path[1024];
    snprintf(path, sizeof path, "%s/%s", dir, name);
    FILE *f = fopen(path, "wb");
    int ok = f && fwrite(v, sizeof(float), count, f) == count;
    if (f && fclose(f))
        ok = 0;
    return ok ? 0 : -1;
}

static int read_u32(const char *dir, const char *name, uint32_t *v, size_t count)
{
    char path[1024];
    snprintf(path, sizeof path, "%s/%s", dir, name);
    FILE *f = fopen(path, "rb");
    int ok = f && fread(v, sizeof(uint32_t), count, f) == count;
    if (f)
        fclose(f);
    return ok ? 0 : -1;
}

/* The check's negative control on query 0's answer `ans` (k per query):
 * the answer with its farthest neighbour replaced by a point outside it
 * that is not at the same distance must fail; the answer itself must
 * pass. Returns 0 when both hold (or query 0 has no neighbour), else -1. */
static int negative_control(const float *pts, uint32_t n, const float *q, uint32_t k, double cap,
                            const uint32_t *ans)
{
    uint32_t bad[MAXK], m = 0;
    while (m < k && ans[m] != UINT32_MAX)
        m++;
    if (m == 0)
        return 0;
    memcpy(bad, ans, sizeof(uint32_t) * k);
    uint32_t far = 0; /* farthest of the answer: the one to replace */
    for (uint32_t j = 1; j < m; j++)
        far = dist2(pts + 3 * (size_t)bad[j], q) > dist2(pts + 3 * (size_t)bad[far], q) ? j : far;
    double df = dist2(pts + 3 * (size_t)bad[far], q);
    for (uint32_t i = 0; i < n; i++) {
        int in = 0;
        for (uint32_t j = 0; j < m; j++)
            in |= ans[j] == i;
        if (!in && !near_boundary(dist2(pts + 3 * (size_t)i, q), df)) {
            bad[far] = i;
            return check_one(pts, q, ans, ans, k, cap) == 0 && check_one(pts, q, ans, bad, k, cap) == 2 ? 0 : -1;
        }
    }
    return 0;
}

#define BRUTE_EVERY 509u /* ours is checked against brute force on every this-th query */
#define NWHO 7             /* ours, the peers, ours by packets and ours without state */

/* The peers comparison on the map's points `pos` and the queries q (map
 * frame) of the stream named `order`: CSV rows on stdout (see report.py peers). Returns
 * 0, or 1 when a peer could not run or an answer did not check. */
static int run_peers(const char *dir, const char *python, const char *order, uint32_t pe, const float *pos, uint32_t n,
                     const float *q, uint32_t nq, float cap, const uint32_t *ks, int nks, int reps)
{
    if (write_f32(dir, "points.f32", pos, 3 * (size_t)n) || write_f32(dir, "queries.f32", q, 3 * (size_t)nq)) {
        fprintf(stderr, "bench: --peers: cannot write to %s\n", dir);
        return 1;
    }
    coproc ckd;
    double tb = coproc_start(&ckd, python, "experiments/bench/ckdtree.py", dir, KD_DEFAULT_LEAF);
    if (tb < 0) {
        fprintf(stderr, "bench: --peers: cannot start %s experiments/bench/ckdtree.py\n", python);
        coproc_stop(&ckd);
        return 1;
    }
    printf("%u,%u,%u,0,%s,ckdtree,build,%.6f,0,0,0,0\n", pe, n, nq, order, tb);
    double t0 = now_s();
    kd_tree ours;
    uint32_t *perm = malloc(sizeof(uint32_t) * (n ? n : 1));
    if (!perm || kd_build(&ours, pos, n, KD_DEFAULT_LEAF, perm, 1) != PM_OK) {
        fprintf(stderr, "bench: out of memory\n");
        exit(1);
    }
    double t1 = now_s();
    void *nano = nano_build(pos, n, KD_DEFAULT_LEAF);
    double t2 = now_s();
    void *fl = flann_peer_build(pos, n, KD_DEFAULT_LEAF);
    double t3 = now_s();
    printf("%u,%u,%u,0,%s,ours,build,%.6f,0,0,0,0\n%u,%u,%u,0,%s,nanoflann,build,%.6f,0,0,0,0\n"
           "%u,%u,%u,0,%s,flann-knn,build,%.6f,0,0,0,0\n%u,%u,%u,0,%s,flann-radius,build,%.6f,0,0,0,0\n",
           pe, n, nq, order, t1 - t0, pe, n, nq, order, t2 - t1, pe, n, nq, order, t3 - t2, pe, n, nq, order,
           t3 - t2);
    uint32_t *ref = malloc(sizeof(uint32_t) * (size_t)nq * MAXK), *got = malloc(sizeof(uint32_t) * (size_t)nq * MAXK);
    if (!ref || !got) {
        fprintf(stderr, "bench: out of memory\n");
        exit(1);
    }
    int bad = 0;
    const char *who[NWHO] = {"ours", "nanoflann", "flann-knn", "flann-radius", "ckdtree", "ours-packets", "ours-stateless"};
    static uint32_t idx[KD_PACKET * MAXK];
    static float d2[KD_PACKET * MAXK];
    for (int ki = 0; ki < nks; ki++) {
        uint32_t k = ks[ki];
        /* the answers, untimed, each checked: ours against brute force on a
         * sample, every peer against ours on all queries */
        uint64_t found[NWHO] = {0}, cnt[NWHO][3] = {{0}};
        found[0] = ours_collect(&ours, perm, q, nq, k, cap, 0, ref);
        if (ki == 0 && negative_control(pos, n, q, k, (double)cap, ref)) {
            fprintf(stderr, "bench: --peers: the neighbour-set check let a wrong answer through\n");
            exit(1);
        }
        uint32_t nb = 0;
        for (uint32_t i = 0; i < nq; i += BRUTE_EVERY, nb++) {
            uint32_t bf[MAXK];
            brute_knn(pos, n, q + 3 * (size_t)i, k, (double)cap, bf);
            int c = check_one(pos, q + 3 * (size_t)i, bf, ref + (size_t)i * k, k, (double)cap);
            if (c == 2 && cnt[0][2] < 5)
                fprintf(stderr, "bench: MISMATCH ours vs brute force k=%u query %u\n", k, i);
            cnt[0][c]++;
        }
        found[1] = nano_knn_collect(nano, q, nq, k, cap, got);
        check_sets("nanoflann", pos, q, nq, k, cap, ref, got, cnt[1]);
        found[2] = flann_peer_knn_batch(fl, q, nq, k, cap, 1, got);
        check_sets("flann-knn", pos, q, nq, k, cap, ref, got, cnt[2]);
        found[3] = flann_peer_knn_batch(fl, q, nq, k, cap, 0, got);
        check_sets("flann-radius", pos, q, nq, k, cap, ref, got, cnt[3]);
        if (coproc_batch(&ckd, k, cap, 1, &found[4]) < 0 || read_u32(dir, "ckdtree.u32", got, (size_t)nq * k)) {
            fprintf(stderr, "bench: --peers: cKDTree failed at k=%u\n", k);
            bad = 1;
            break;
        }
        check_sets("ckdtree", pos, q, nq, k, cap, ref, got, cnt[4]);
        found[5] = ours_collect_packets(&ours, perm, q, nq, k, cap, got);
        check_sets("ours-packets", pos, q, nq, k, cap, ref, got, cnt[5]);
        found[6] = ours_collect(&ours, perm, q, nq, k, cap, 1, got);
        check_sets("ours-stateless", pos, q, nq, k, cap, ref, got, cnt[6]);
        for (int w = 0; w < NWHO; w++) {
            printf("%u,%u,%u,%u,%s,%s,check,0,%llu,%llu,%llu,%llu\n", pe, n, w ? nq : nb, k, order, who[w],
                   (unsigned long long)found[w], (unsigned long long)cnt[w][0], (unsigned long long)cnt[w][1],
                   (unsigned long long)cnt[w][2]);
            bad |= cnt[w][2] != 0;
        }
        /* the timed runs: all five one after another in each rep, the four
         * in this process in an order that rotates from rep to rep */
        for (int r = 0; r < reps; r++) {
            double s[NWHO];
            uint64_t f[NWHO];
            static const int inproc[6] = {0, 1, 2, 3, 5, 6};
            for (int j = 0; j < 6; j++) {
                int w = inproc[(j + r) % 6];
                double r2 = 0, t0 = now_s();
                if (w == 0)
                    f[0] = ours_knn_batch(&ours, q, nq, k, cap, idx, d2, &r2);
                else if (w == 5)
                    f[5] = ours_knn_packets(&ours, q, nq, k, cap, idx, d2, &r2);
                else if (w == 6)
                    f[6] = ours_knn_stateless(&ours, q, nq, k, cap, idx, d2, &r2);
                else if (w == 1)
                    f[1] = nano_knn_batch(nano, q, nq, k, cap, idx, d2, &r2);
                else
                    f[w] = flann_peer_knn_batch(fl, q, nq, k, cap, w == 2, NULL);
                s[w] = now_s() - t0;
            }
            s[4] = coproc_batch(&ckd, k, cap, 0, &f[4]);
            for (int w = 0; w < NWHO; w++) {
                bad |= s[w] < 0 || f[w] != found[w];
                printf("%u,%u,%u,%u,%s,%s,%d,%.6f,%llu,,,\n", pe, n, nq, k, order, who[w], r, s[w],
                       (unsigned long long)f[w]);
            }
            fflush(stdout);
        }
    }
    coproc_stop(&ckd);
    flann_peer_free(fl);
    nano_free(nano);
    kd_free(&ours);
    free(perm);
    free(ref);
    free(got);
    return bad;
}

int main(int argc, char **argv)
{
    const char *scene_path = "scenes/cornell.scene";
    const char *peers_dir = NULL, *python = "/usr/bin/python3";
    int reps = 5, icount = 0, knn_only = 0;
    uint32_t ks[8] = {1, 10, 20, 50, 100};
    int nks = 5;
    uint32_t qw = 320, qh = 240;
    uint32_t sizes[8] = {50000, 100000, 500000};
    int nsizes = 3;
    for (int i = 1; i < argc; i++) {
        if (!strcmp(argv[i], "--scene") && i + 1 < argc)
            scene_path = argv[++i];
        else if (!strcmp(argv[i], "--reps") && i + 1 < argc)
            reps = atoi(argv[++i]);
        else if (!strcmp(argv[i], "--qw") && i + 1 < argc)
            qw = (uint32_t)atoi(argv[++i]);
        else if (!strcmp(argv[i], "--qh") && i + 1 < argc)
            qh = (uint32_t)atoi(argv[++i]);
        else if (!strcmp(argv[i], "--icount"))
            icount = 1;
        else if (!strcmp(argv[i], "--knn-only"))
            knn_only = 1;
        else if (!strcmp(argv[i], "--peers") && i + 1 < argc)
            peers_dir = argv[++i];
        else if (!strcmp(argv[i], "--python") && i + 1 < argc)
            python = argv[++i];
        else if (!strcmp(argv[i], "--ks") && i + 1 < argc) {
            nks = 0;
            for (char *s = strtok(argv[++i], ","); s && nks < 8; s = strtok(NULL, ","))
                ks[nks++] = (uint32_t)atoi(s);
            for (int j = 0; j < nks; j++)
                if (ks[j] < 1 || ks[j] > MAXK) {
                    fprintf(stderr, "bench: --ks: each k must be in 1..%u\n", MAXK);
                    return 2;
                }
        }
        else if (!strcmp(argv[i], "--sizes") && i + 1 < argc) {
            nsizes = 0;
            for (char *s = strtok(argv[++i], ","); s && nsizes < 8; s = strtok(NULL, ","))
                sizes[nsizes++] = (uint32_t)atoi(s);
        } else {
            fprintf(stderr, "bench: unknown argument %s\n", argv[i]);
            return 2;
        }
    }
    if (reps < 1)
        reps = 1;
    char err[256];
    scene *sc;
    if (scene_load(scene_path, &sc, err, sizeof err) != PM_OK) {
        fprintf(stderr, "bench: %s\n", err);
        return 1;
    }
    if (scene_set_accel(sc, SCENE_ACCEL_AUTO) != PM_OK) { /* as the render pipeline does first */
        fprintf(stderr, "bench: out of memory\n");
        return 1;
    }
    config_render cfg = config_defaults();
    qset tiles = eye_points(sc, qw, qh, 1);
    qset shuf = shuffled(&tiles, 1);
    if (icount) { /* every m-th query of each order, so the sample covers the whole view */
        uint32_t m = tiles.n / 8000 ? tiles.n / 8000 : 1, j = 0;
        for (uint32_t i = 0; i < tiles.n; i += m, j++) {
            memmove(tiles.p + 3 * j, tiles.p + 3 * i, 3 * sizeof(float));
            memmove(shuf.p + 3 * j, shuf.p + 3 * i, 3 * sizeof(float));
        }
        tiles.n = shuf.n = j;
    }
    if (peers_dir) {
        uint32_t pe = sizes[nsizes - 1];
        photons_params pp = {pe, cfg.seed, cfg.photon_depth, 1};
        photons_list list;
        photons_map map;
        if (photons_trace(sc, &pp, 1, NULL, &list) != PM_OK || photons_build_map(&list, 0, 1, &map, NULL) != PM_OK) {
            fprintf(stderr, "bench: out of memory\n");
            return 1;
        }
        /* the renderer's own stream: the eye pass's four subpixel samples per
         * pixel (a quarter of the pixels, so about as many queries) */
        qset sub = eye_points(sc, qw / 2, qh / 2, 2);
        float *pos = malloc(sizeof(float) * 3 * map.count), *q = malloc(sizeof(float) * 3 * tiles.n);
        float *qs = malloc(sizeof(float) * 3 * sub.n);
        if (!pos || !q || !qs) {
            fprintf(stderr, "bench: out of memory\n");
            return 1;
        }
        for (uint32_t i = 0; i < map.count; i++)
            kd_point(&map.tree, i, pos + 3 * (size_t)i);
        for (uint32_t i = 0; i < tiles.n; i++) {
            const float *w = tiles.p + 3 * (size_t)i;
            photons_map_point(&map, vec_make(w[0], w[1], w[2]), q + 3 * (size_t)i);
        }
        for (uint32_t i = 0; i < sub.n; i++) {
            const float *w = sub.p + 3 * (size_t)i;
            photons_map_point(&map, vec_make(w[0], w[1], w[2]), qs + 3 * (size_t)i);
        }
        est_gather gather = est_gather_make(&map, cfg.nn, render_max_radius(sc, &cfg, &map), 0);
        printf("pe,stored,queries,k,order,who,rep,seconds,found,exact,ties,mismatches\n");
        int rc = run_peers(peers_dir, python, "tiles", pe, pos, map.count, q, tiles.n, (float)gather.max_r2, ks, nks,
                           reps);
        if (rc == 0)
            rc = run_peers(peers_dir, python, "subpixels", pe, pos, map.count, qs, sub.n, (float)gather.max_r2, ks,
                           nks, reps);
        free(pos), free(q), free(qs), free(sub.p), free(sub.nr);
        photons_map_free(&map);
        free(tiles.p), free(tiles.nr), free(shuf.p), free(shuf.nr);
        scene_free(sc);
        return rc;
    }
    /* --icount also counts the eye pass's own stream: four subpixel samples
     * per pixel of a quarter as many pixels, sampled in runs of 256
     * consecutive queries (a packet and the state need neighbours in the
     * stream; the tiles and shuffled samples take every m-th query) */
    qset subq = {0, NULL, NULL};
    if (icount) {
        subq = eye_points(sc, qw / 2, qh / 2, 2);
        uint32_t runs = subq.n / 256, m = runs / 32 ? runs / 32 : 1, j = 0;
        for (uint32_t g = 0; g < runs; g += m)
            for (uint32_t e = 0; e < 256; e++, j++)
                memmove(subq.p + 3 * j, subq.p + 3 * ((size_t)256 * g + e), 3 * sizeof(float));
        subq.n = j;
    }
    const int nord = icount ? 3 : 2;
    const qset *orders[3] = {&tiles, &shuf, &subq};
    const char *order_name[3] = {"tiles", "shuffled", "subpixels"};
    uint32_t nq = tiles.n;
    uint32_t idx[MAXK];
    float d2[MAXK];
    static uint32_t pidx[KD_PACKET * MAXK];
    static float pd2[KD_PACKET * MAXK];

    if (!icount) {
        printf("## kNN queries per second, one thread\n\n");
        printf("Queries: the first diffuse hit of the ray through each pixel centre of a %ux%u view "
               "(%u points), in 16x16-tile order and shuffled. Radius cap 0.05 x the photons' bounding-box diagonal. "
               "Leaf size %u for both trees. Median of %d interleaved runs; `ratio` = ours / nanoflann "
               "(queries/s). `found` = mean neighbours per query (identical for both; checked).\n\n",
               qw, qh, tiles.n, KD_DEFAULT_LEAF, reps);
        printf("| P_e | stored | k | order | ours (Mq/s) | nanoflann (Mq/s) | ratio | found |\n");
        printf("|---:|---:|---:|---|---:|---:|---:|---:|\n");
    }
    for (int si = 0; si < nsizes; si++) {
        photons_params pp = {sizes[si], cfg.seed, cfg.photon_depth, 1};
        reps_params rps = {.rep_every = cfg.rep_every, .rep_count = 0, .rep_tree = CONFIG_REP_TREE_SEPARATE,
                           .bias_correction = 0, .normal_cos = cfg.normal_cos};
        photons_list list;
        photons_map map;
        if (photons_trace(sc, &pp, 1, NULL, &list) != PM_OK) {
            fprintf(stderr, "bench: out of memory\n");
            return 1;
        }
        reps_choose(&rps, &list);
        uint32_t stored = (uint32_t)list.count;
        if (photons_build_map(&list, 0, 1, &map, NULL) != PM_OK) {
            fprintf(stderr, "bench: out of memory\n");
            return 1;
        }
        /* both trees hold the map's points (its frame); the queries and the
         * radius cap move into that frame too */
        float *pos = malloc(sizeof(float) * 3 * stored);
        for (uint32_t i = 0; i < stored; i++)
            kd_point(&map.tree, i, pos + 3 * (size_t)i);
        double max_r = render_max_radius(sc, &cfg, &map);
        est_gather gather = est_gather_make(&map, cfg.nn, max_r, 0);
        float max_d2 = (float)gather.max_r2;
        qset mq[3];
        for (int o = 0; o < nord; o++) {
            mq[o].n = orders[o]->n;
            mq[o].p = malloc(sizeof(float) * 3 * mq[o].n);
            mq[o].nr = NULL;
            for (uint32_t i = 0; i < mq[o].n; i++) {
                const float *w = orders[o]->p + 3 * (size_t)i;
                photons_map_point(&map, vec_make(w[0], w[1], w[2]), mq[o].p + 3 * (size_t)i);
            }
        }
        void *nano = nano_build(pos, stored, KD_DEFAULT_LEAF);
        void *fl = icount ? flann_peer_build(pos, stored, KD_DEFAULT_LEAF) : NULL;
        if (icount)
            CALLGRIND_START_INSTRUMENTATION;
        for (int ki = 0; ki < nks; ki++) {
            uint32_t k = ks[ki];
            for (int o = 0; o < nord; o++) {
                const float *q = mq[o].p;
                if (icount) {
                    nq = mq[o].n;
                    char label[96];
                    double s = 0;
                    CALLGRIND_ZERO_STATS;
                    ours_knn_batch(&map.tree, q, nq, k, max_d2, idx, d2, &s);
                    snprintf(label, sizeof label, "ours %u %u %s %u", sizes[si], k, order_name[o], nq);
                    CALLGRIND_DUMP_STATS_AT(label);
                    if (o == 2) { /* packets only where the stream is contiguous */
                        ours_knn_packets(&map.tree, q, nq, k, max_d2, pidx, pd2, &s);
                        snprintf(label, sizeof label, "ourspacket %u %u %s %u", sizes[si], k, order_name[o], nq);
                        CALLGRIND_DUMP_STATS_AT(label);
                    }
                    ours_knn_stateless(&map.tree, q, nq, k, max_d2, idx, d2, &s);
                    snprintf(label, sizeof label, "oursstateless %u %u %s %u", sizes[si], k, order_name[o], nq);
                    CALLGRIND_DUMP_STATS_AT(label);
                    nano_knn_batch(nano, q, nq, k, max_d2, idx, d2, &s);
                    snprintf(label, sizeof label, "nano %u %u %s %u", sizes[si], k, order_name[o], nq);
                    CALLGRIND_DUMP_STATS_AT(label);
                    flann_peer_knn_batch(fl, q, nq, k, max_d2, 1, NULL);
                    snprintf(label, sizeof label, "flann %u %u %s %u", sizes[si], k, order_name[o], nq);
                    CALLGRIND_DUMP_STATS_AT(label);
                    continue;
                }
                double t_ours[64], t_nano[64], s_ours = 0, s_nano = 0;
                uint64_t f_ours = 0, f_nano = 0;
                for (int r = 0; r < reps && r < 64; r++) {
                    double t0 = now_s();
                    f_ours = ours_knn_batch(&map.tree, q, nq, k, max_d2, idx, d2, &s_ours);
                    double t1 = now_s();
                    f_nano = nano_knn_batch(nano, q, nq, k, max_d2, idx, d2, &s_nano);
                    double t2 = now_s();
                    t_ours[r] = t1 - t0;
                    t_nano[r] = t2 - t1;
                }
                if (f_ours != f_nano || fabs(s_ours - s_nano) > 1e-6 * fabs(s_nano) + 1e-12)
                    fprintf(stderr, "bench: MISMATCH P_e=%u k=%u: found %llu vs %llu, r2 sums %.9g vs %.9g\n",
                            sizes[si], k, (unsigned long long)f_ours, (unsigned long long)f_nano, s_ours, s_nano);
                double mo = median(t_ours, reps), mn = median(t_nano, reps);
                printf("| %u | %u | %u | %s | %.3f | %.3f | %.2f | %.1f |\n", sizes[si], stored, k, order_name[o],
                       nq / mo * 1e-6, nq / mn * 1e-6, mn / mo, (double)f_ours / nq);
                fflush(stdout);
            }
        }
        if (icount)
            CALLGRIND_STOP_INSTRUMENTATION;
        nano_free(nano);
        if (fl)
            flann_peer_free(fl);
        if (!icount && !knn_only) {
            /* the trees' build over the same points, interleaved */
            double tb[64], tn[64];
            for (int r = 0; r < reps && r < 64; r++) {
                kd_tree bt;
                double t0 = now_s();
                if (kd_build(&bt, pos, stored, KD_DEFAULT_LEAF, NULL, 1) != PM_OK) {
                    fprintf(stderr, "bench: out of memory\n");
                    return 1;
                }
                double t1 = now_s();
                kd_free(&bt);
                double t2 = now_s();
                void *nb = nano_build(pos, stored, KD_DEFAULT_LEAF);
                double t3 = now_s();
                nano_free(nb);
                tb[r] = t1 - t0;
                tn[r] = t3 - t2;
            }
            printf("\nTree build over the %u stored points, one thread, median of %d: kd_build %.3f s, "
                   "nanoflann %.3f s.\n",
                   stored, reps, median(tb, reps), median(tn, reps));
        }
        free(pos);
        free(mq[0].p);
        free(mq[1].p);
        if (nord > 2)
            free(mq[2].p);

        if (!icount && !knn_only) {
            /* representatives: precompute with the defaults, then the lookup */
            reps_set rp;
            if (reps_collect(&rps, &map, NULL, &rp) != PM_OK || reps_evaluate(&rp, &map, &gather, 1, NULL) != PM_OK) {
                fprintf(stderr, "bench: out of memory\n");
                return 1;
            }
            printf("\n### Representative lookup at P_e = %u (nearest representative with normal cosine > %.2f, "
                   "reps_lookup, own tree), one thread\n\n",
                   sizes[si], cfg.normal_cos);
            printf("| P_e | representatives | order | lookups/s (M) | found | bytes/photon (map) | "
                   "bytes/representative |\n|---:|---:|---|---:|---:|---:|---:|\n");
            for (int o = 0; o < 2; o++) {
                double t[64], es = 0;
                uint64_t f = 0;
                for (int r = 0; r < reps && r < 64; r++) {
                    double t0 = now_s();
                    f = lookup_batch(&rp, &map, orders[o], nq, &gather, &es);
                    t[r] = now_s() - t0;
                }
                printf("| %u | %u | %s | %.3f | %.3f | %.2f | %.2f |\n", sizes[si], rp.count, order_name[o],
                       nq / median(t, reps) * 1e-6, (double)f / nq,
                       (double)(kd_bytes(&map.tree) + (size_t)map.count * sizeof(photons_record)) / map.count,
                       (double)reps_bytes(&rp, &map) / rp.count);
            }
            reps_free(&rp);
            if (si + 1 < nsizes)
                printf("\n| P_e | stored | k | order | ours (Mq/s) | nanoflann (Mq/s) | ratio | found |\n"
                       "|---:|---:|---:|---|---:|---:|---:|---:|\n");
        }
        photons_map_free(&map);
    }

    if (!icount && !knn_only) {
        uint32_t ew = 256, eh = 192;
        double load[3] = {0, 0, 0};
        FILE *lf = fopen("/proc/loadavg", "r");
        if (lf) {
            if (fscanf(lf, "%lf %lf %lf", &load[0], &load[1], &load[2]) != 3)
                load[0] = load[1] = load[2] = 0;
            fclose(lf);
        }
        printf("\n## Eye pass, samples per second (render_run, %ux%u, S=%u, P_e=%u, n=%u)\n\n", ew, eh,
               cfg.subpixels, (unsigned)cfg.photons, cfg.nn);
        printf("Wall: eye-pass samples per second from render_run's own eye-pass timer, median of %d runs. "
               "CPU: process CPU seconds of the eye pass (a render minus the same render at 16x16) per "
               "sample; `CPU ratio` = CPU per sample on 1 thread / on 2 threads, 1.00 when the second "
               "thread does its share with no overhead (false sharing, contention), so that 2 free cores "
               "would give 2 x CPU ratio. Load average when this ran: %.1f %.1f %.1f (other jobs share "
               "the 2 cores, so wall scaling here understates what the code does; `compute-loop scaling` is what a "
               "pure integer loop split over 2 threads got in the same minutes, the most the machine gave).\n\n",
               reps, load[0], load[1], load[2]);
        printf("| method | 1 thread (Msamples/s) | 2 threads (Msamples/s) | wall scaling | compute-loop scaling "
               "| CPU us/sample 1 thr | CPU us/sample 2 thr | CPU ratio |\n|---|---:|---:|---:|---:|---:|---:|---:|\n");
        for (int m = 0; m < 2; m++) {
            config_render c = cfg;
            c.width = ew;
            c.height = eh;
            c.method = m ? CONFIG_METHOD_PRECOMPUTED : CONFIG_METHOD_CONVENTIONAL;
            config_render tiny = c;
            tiny.width = tiny.height = 16;
            double rate[2], cpu[2], spin[2][64];
            for (unsigned th = 1; th <= 2; th++) {
                double t[64], cs[64];
                uint64_t samples = 0;
                for (int r = 0; r < reps && r < 64; r++) {
                    render_result res;
                    stats_run st, st0;
                    double c0 = cpu_s();
                    if (render_run(sc, &tiny, th, 0, &res, err, sizeof err) != PM_OK) {
                        fprintf(stderr, "bench: out of memory\n");
                        return 1;
                    }
                    st0 = res.st;
                    render_result_free(&res);
                    double c1 = cpu_s();
                    if (render_run(sc, &c, th, 0, &res, err, sizeof err) != PM_OK) {
                        fprintf(stderr, "bench: out of memory\n");
                        return 1;
                    }
                    st = res.st;
                    render_result_free(&res);
                    double c2 = cpu_s();
                    t[r] = st.render;
                    samples = st.samples - st0.samples;
                    cs[r] = ((c2 - c1) - (c1 - c0)) / (double)samples;
                    samples = st.samples;
                    spin[th - 1][r] = spin_s(th);
                }
                rate[th - 1] = samples / median(t, reps);
                cpu[th - 1] = median(cs, reps);
            }
            double spin_scaling = median(spin[0], reps) / median(spin[1], reps);
            printf("| %s | %.3f | %.3f | %.2fx | %.2fx | %.3f | %.3f | %.2f |\n", config_method_name(c.method),
                   rate[0] * 1e-6, rate[1] * 1e-6, rate[1] / rate[0], spin_scaling, cpu[0] * 1e6, cpu[1] * 1e6,
                   cpu[0] / cpu[1]);
        }
        printf("\nPHOTON_BYTES_PER_STORED = %zu (payload %zu + position %zu); the tree adds %.2f bytes/photon "
               "of inner nodes and leaf offsets (see the table above).\n",
               (size_t)PHOTONS_BYTES_PER_STORED, sizeof(photons_record), 3 * sizeof(float),
               0.0 + (double)(sizeof(float) + 1 + sizeof(uint32_t)) / KD_DEFAULT_LEAF);
    }
    free(tiles.p), free(tiles.nr), free(shuf.p), free(shuf.nr), free(subq.p), free(subq.nr);
    scene_free(sc);
    return 0;
}
