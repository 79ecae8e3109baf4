/* bench: the performance harness of issue 7 (not a test). Builds the real
 * photon maps of a scene, takes the eye pass's diffuse hit points as kNN
 * queries (16x16-tile order and shuffled), and times our kd-tree against
 * nanoflann side by side in one process; then the representative lookup,
 * the eye pass on 1 and 2 threads, and the memory per photon. Prints
 * Markdown on stdout.
 *
 *   bench [--scene F] [--reps R] [--qw W --qh H] [--icount] [--sizes a,b,c]
 *         [--ks a,b,c] [--knn-only]
 *
 * --ks: the k of the kNN tables (default 1,10,20,50,100); --knn-only: the
 * kNN tables alone (no build, lookup or eye-pass timings), for a quick
 * side-by-side reading of one cell.
 * --icount: few queries per cell, each cell's loop bracketed by callgrind
 * client requests (run under valgrind --tool=callgrind --instr-atstart=no);
 * run.sh turns the dumps into instructions per query. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include <valgrind/callgrind.h>

#include "camera.h"
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

#define TILE 16u
#define MAXK 100u

typedef struct {
    uint32_t n;
    float *p;  /* xyz */
    float *nr; /* normal facing the viewer, xyz */
} qset;

static double now_s(void) { return (double)stats_now_ns() * 1e-9; }

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
    double t0 = (double)stats_now_ns() * 1e-9;
    parallel_for(threads, 64, spin_item, (void *)&sink);
    return (double)stats_now_ns() * 1e-9 - t0;
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

/* The first diffuse hit of the camera ray through each pixel centre of a WxH
 * image, pixels visited tile by tile as the eye pass does. Mirrors reflect;
 * glass refracts (reflects on total internal reflection). */
static qset eye_points(const scene *sc, uint32_t w, uint32_t h)
{
    qset q = {0, malloc(sizeof(float) * 3 * w * h), malloc(sizeof(float) * 3 * w * h)};
    double aspect = (double)h / w;
    for (uint32_t ty = 0; ty < (h + TILE - 1) / TILE; ty++)
        for (uint32_t tx = 0; tx < (w + TILE - 1) / TILE; tx++)
            for (uint32_t y = ty * TILE; y < h && y < ty * TILE + TILE; y++)
                for (uint32_t x = tx * TILE; x < w && x < tx * TILE + TILE; x++) {
                    shape_ray r = camera_ray(sc, aspect, (x + 0.5) / w, (y + 0.5) / h);
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
 * one needed; the results do not depend on it). */
static uint64_t ours_knn_batch(const kd_tree *t, const float *q, uint32_t nq, uint32_t k, float max_d2,
                               uint32_t *idx, float *d2, double *r2sum)
{
    kd_query st;
    if (kd_query_init(&st, k)) {
        fprintf(stderr, "bench: out of memory\n");
        exit(1);
    }
    uint64_t total = 0;
    double s = 0.0;
    for (uint32_t i = 0; i < nq; i++) {
        float r2;
        total += kd_query_knn(t, &st, q + 3 * (size_t)i, k, max_d2, idx, d2, &r2);
        s += r2;
    }
    kd_query_free(&st);
    *r2sum += s;
    return total;
}

static uint64_t lookup_batch(const reps_set *r, const photons_map *m, const qset *q, uint32_t nq, double cos_min,
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
        vec3 e = reps_lookup(r, m, vec_make(p[0], p[1], p[2]), vec_make(n[0], n[1], n[2]), cos_min, g, scratch, &f);
        found += (uint64_t)f;
        s += e.x;
    }
    est_scratch_delete(scratch, 1);
    *esum += s;
    return found;
}

int main(int argc, char **argv)
{
    const char *scene_path = "scenes/cornell.scene";
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
    if (scene_set_accel(sc, SCENE_ACCEL_AUTO)) { /* as the render pipeline does first */
        fprintf(stderr, "bench: out of memory\n");
        return 1;
    }
    config_render cfg = config_defaults();
    qset tiles = eye_points(sc, qw, qh);
    qset shuf = shuffled(&tiles, 1);
    if (icount) { /* every m-th query of each order, so the sample covers the whole view */
        uint32_t m = tiles.n / 8000 ? tiles.n / 8000 : 1, j = 0;
        for (uint32_t i = 0; i < tiles.n; i += m, j++) {
            memmove(tiles.p + 3 * j, tiles.p + 3 * i, 3 * sizeof(float));
            memmove(shuf.p + 3 * j, shuf.p + 3 * i, 3 * sizeof(float));
        }
        tiles.n = shuf.n = j;
    }
    const qset *orders[2] = {&tiles, &shuf};
    const char *order_name[2] = {"tiles", "shuffled"};
    uint32_t nq = tiles.n;
    uint32_t idx[MAXK];
    float d2[MAXK];

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
        reps_params rps = {.every = cfg.rep_every, .count = 0, .tree = CONFIG_REP_TREE_SEPARATE, .leave_out = 0};
        photons_list list;
        photons_map map;
        if (photons_trace(sc, &pp, 1, NULL, &list)) {
            fprintf(stderr, "bench: out of memory\n");
            return 1;
        }
        reps_choose(&rps, &list);
        uint32_t stored = (uint32_t)list.count;
        if (photons_build_map(&list, 0, &map, NULL)) {
            fprintf(stderr, "bench: out of memory\n");
            return 1;
        }
        /* both trees hold the map's points (its frame); the queries and the
         * radius cap move into that frame too */
        float *pos = malloc(sizeof(float) * 3 * stored);
        for (uint32_t i = 0; i < stored; i++) {
            pos[3 * (size_t)i] = map.tree.x[i];
            pos[3 * (size_t)i + 1] = map.tree.y[i];
            pos[3 * (size_t)i + 2] = map.tree.z[i];
        }
        double max_r = render_max_radius(sc, &cfg, &map);
        est_gather gather = est_gather_make(&map, cfg.nn, max_r, 0);
        float max_d2 = (float)gather.max_r2;
        qset mq[2];
        for (int o = 0; o < 2; o++) {
            mq[o].n = orders[o]->n;
            mq[o].p = malloc(sizeof(float) * 3 * mq[o].n);
            mq[o].nr = NULL;
            for (uint32_t i = 0; i < mq[o].n; i++) {
                const float *w = orders[o]->p + 3 * (size_t)i;
                photons_map_point(&map, vec_make(w[0], w[1], w[2]), mq[o].p + 3 * (size_t)i);
            }
        }
        void *nano = nano_build(pos, stored, KD_DEFAULT_LEAF);
        if (icount)
            CALLGRIND_START_INSTRUMENTATION;
        for (int ki = 0; ki < nks; ki++) {
            uint32_t k = ks[ki];
            for (int o = 0; o < 2; o++) {
                const float *q = mq[o].p;
                if (icount) {
                    char label[96];
                    double s = 0;
                    CALLGRIND_ZERO_STATS;
                    ours_knn_batch(&map.tree, q, nq, k, max_d2, idx, d2, &s);
                    snprintf(label, sizeof label, "ours %u %u %s %u", sizes[si], k, order_name[o], nq);
                    CALLGRIND_DUMP_STATS_AT(label);
                    nano_knn_batch(nano, q, nq, k, max_d2, idx, d2, &s);
                    snprintf(label, sizeof label, "nano %u %u %s %u", sizes[si], k, order_name[o], nq);
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
        if (!icount && !knn_only) {
            /* the trees' build over the same points, interleaved */
            double tb[64], tn[64];
            for (int r = 0; r < reps && r < 64; r++) {
                kd_tree bt;
                double t0 = now_s();
                if (kd_build(&bt, pos, stored, KD_DEFAULT_LEAF, NULL)) {
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

        if (!icount && !knn_only) {
            /* representatives: precompute with the defaults, then the lookup */
            reps_set rp;
            if (reps_collect(&rps, &map, NULL, &rp) || reps_evaluate(&rp, &map, &gather, 1, NULL)) {
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
                    f = lookup_batch(&rp, &map, orders[o], nq, cfg.normal_cos, &gather, &es);
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
                    if (render_run(sc, &tiny, th, 0, &res, err, sizeof err)) {
                        fprintf(stderr, "bench: out of memory\n");
                        return 1;
                    }
                    st0 = res.st;
                    render_result_free(&res);
                    double c1 = cpu_s();
                    if (render_run(sc, &c, th, 0, &res, err, sizeof err)) {
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
    free(tiles.p), free(tiles.nr), free(shuf.p), free(shuf.nr);
    scene_free(sc);
    return 0;
}
