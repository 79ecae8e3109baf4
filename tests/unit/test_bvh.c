/* test_bvh: the BVH against the linear loop over the shapes (brute force):
 * the same shape index and bit-identical t for random rays against random
 * sphere/rectangle sets, rays starting on surfaces, rays parallel to
 * rectangles and to the axes, exact ties (duplicate shapes, shared edges);
 * degenerate sets; the scene-level switch; the parser staying linear. */
#include <assert.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "bvh.h"
#include "check.h"
#include "helpers.h"
#include "rng.h"
#include "scene.h"
#include "shapes.h"
#include "tests.h"

/* The linear loop of scene.c: first shape with the smallest t in (0, tmax). */
static int brute_intersect(const shape *s, size_t n, const shape_ray *r, double tmax, double *t)
{
    int best = -1;
    double tt;
    for (size_t i = 0; i < n; i++)
        if (shape_intersect(&s[i], r, 0.0, tmax, &tt)) {
            tmax = tt;
            best = (int)i;
        }
    if (best >= 0)
        *t = tmax;
    return best;
}

static int brute_occluded(const shape *s, size_t n, const shape_ray *r, double tmax)
{
    double tt;
    for (size_t i = 0; i < n; i++)
        if (shape_intersect(&s[i], r, 0.0, tmax, &tt))
            return 1;
    return 0;
}

static double uni(rng_stream *g, double lo, double hi)
{
    return lo + (hi - lo) * rng_next_double(g);
}

static vec3 random_dir(rng_stream *g)
{
    for (;;) {
        vec3 v = vec_make(uni(g, -1, 1), uni(g, -1, 1), uni(g, -1, 1));
        double l = vec_len(v);
        if (l > 0.1 && l <= 1.0)
            return vec_scale(v, 1.0 / l);
    }
}

/* One of the six axis directions. */
static vec3 axis_dir(rng_stream *g)
{
    int k = (int)(rng_next_double(g) * 6.0);
    double s = k & 1 ? -1.0 : 1.0;
    return k / 2 == 0 ? vec_make(s, 0, 0) : k / 2 == 1 ? vec_make(0, s, 0) : vec_make(0, 0, s);
}

/* A grid coordinate in [-2, 2] in steps of 0.25 (exact in binary). */
static double grid(rng_stream *g)
{
    return -2.0 + 0.25 * (int)(rng_next_double(g) * 17.0);
}

/* A random set of n shapes in [-2, 2]^3: spheres, axis-aligned rectangles on
 * grid coordinates (shared edges and planes), tilted rectangles, thin slabs,
 * and exact duplicates (ties broken by index). */
static void random_shapes(rng_stream *g, shape *s, size_t n)
{
    for (size_t i = 0; i < n; i++) {
        double u = rng_next_double(g);
        if (i > 0 && u < 0.08) { /* a duplicate of an earlier shape, possibly with its edges swapped */
            size_t j = (size_t)(rng_next_double(g) * (double)i);
            s[i] = s[j];
            if (s[j].kind == SHAPE_RECT && rng_next_double(g) < 0.5)
                s[i] = shape_rect(s[j].corner, s[j].edge2, s[j].edge1, s[j].material);
        } else if (u < 0.4) {
            s[i] = shape_sphere(vec_make(uni(g, -2, 2), uni(g, -2, 2), uni(g, -2, 2)), uni(g, 0.01, 0.6), 0);
        } else if (u < 0.75) { /* axis-aligned rectangle on the grid */
            vec3 c = vec_make(grid(g), grid(g), grid(g));
            double a = 0.25 * (1 + (int)(rng_next_double(g) * 6)), b = 0.25 * (1 + (int)(rng_next_double(g) * 6));
            int k = (int)(rng_next_double(g) * 3.0);
            vec3 e1 = k == 0 ? vec_make(0, a, 0) : k == 1 ? vec_make(0, 0, a) : vec_make(a, 0, 0);
            vec3 e2 = k == 0 ? vec_make(0, 0, b) : k == 1 ? vec_make(b, 0, 0) : vec_make(0, b, 0);
            s[i] = shape_rect(c, e1, e2, 0);
        } else if (u < 0.9) { /* tilted rectangle */
            vec3 e1 = vec_scale(random_dir(g), uni(g, 0.05, 1.5));
            vec3 e2 = vec_scale(vec_norm(vec_cross(e1, random_dir(g))), uni(g, 0.05, 1.5));
            s[i] = shape_rect(vec_make(uni(g, -2, 2), uni(g, -2, 2), uni(g, -2, 2)), e1, e2, 0);
        } else { /* the two faces of a thin slab, 1e-3 apart */
            vec3 c = vec_make(uni(g, -2, 2), uni(g, -2, 2), uni(g, -2, 2));
            s[i] = shape_rect(c, vec_make(0.7, 0, 0), vec_make(0, 0, 0.4), 0);
            if (i + 1 < n) {
                i++;
                s[i] = shape_rect(vec_add(c, vec_make(0, 1e-3, 0)), vec_make(0, 0, 0.4), vec_make(0.7, 0, 0), 0);
            }
        }
    }
}

/* Compares the tree with brute force for ray r; returns 1 when they agree. */
static int agree(const bvh *b, const shape *s, size_t n, const shape_ray *r, double tmax, long *hits)
{
    double tb = -1.0, tl = -1.0;
    int ib = bvh_intersect(b, s, r, tmax, &tb);
    int il = brute_intersect(s, n, r, tmax, &tl);
    int ok = ib == il && (il < 0 || tb == tl);
    if (!ok)
        fprintf(stderr, "  ray (%.17g %.17g %.17g) dir (%.17g %.17g %.17g): bvh shape %d t %.17g, linear shape %d t %.17g\n",
                r->origin.x, r->origin.y, r->origin.z, r->dir.x, r->dir.y, r->dir.z, ib, tb, il, tl);
    if (il >= 0) {
        (*hits)++;
        /* shadow queries just short of, at and beyond the nearest hit */
        double lims[3] = {tl, nextafter(tl, INFINITY), tl * 0.5};
        for (int k = 0; k < 3; k++)
            ok &= bvh_occluded(b, s, r, lims[k]) == brute_occluded(s, n, r, lims[k]);
    }
    ok &= bvh_occluded(b, s, r, tmax) == brute_occluded(s, n, r, tmax);
    return ok;
}

void test_bvh_matches_brute_force(void)
{
    static const size_t sizes[] = {1, 2, 3, 5, 17, 64, 300, 1000};
    rng_stream g = rng_make(42, 7);
    long rays = 0, hits = 0, bad = 0;
    for (size_t si = 0; si < sizeof sizes / sizeof sizes[0]; si++) {
        for (int set = 0; set < 4; set++) {
            size_t n = sizes[si];
            shape *s = malloc(n * sizeof *s);
            assert(s);
            random_shapes(&g, s, n);
            bvh *b = bvh_build(s, n, 4.0);
            CHECK(b != NULL);
            if (!b) {
                free(s);
                continue;
            }
            bvh_info info = bvh_describe(b);
            CHECK(info.shapes == n && info.nodes <= 2 * n - 1 && info.leaves >= 1 && info.depth <= BVH_MAX_DEPTH);
            for (int k = 0; k < 3000; k++) {
                shape_ray r;
                double tmax = INFINITY;
                int kind = k % 6;
                if (kind == 0) { /* anywhere, any direction */
                    r.origin = vec_make(uni(&g, -3, 3), uni(&g, -3, 3), uni(&g, -3, 3));
                    r.dir = random_dir(&g);
                } else if (kind == 1) { /* from a grid point along an axis: exact edge hits and ties */
                    r.origin = vec_make(grid(&g), grid(&g), grid(&g));
                    r.dir = axis_dir(&g);
                } else if (kind == 2) { /* parallel to the axis-aligned rectangles' planes, in a grid plane */
                    r.origin = vec_make(grid(&g), grid(&g), grid(&g));
                    double a = uni(&g, 0, 2 * VEC_PI);
                    int ax = (int)(rng_next_double(&g) * 3.0);
                    vec3 d = ax == 0 ? vec_make(0, cos(a), sin(a)) : ax == 1 ? vec_make(cos(a), 0, sin(a))
                                                                             : vec_make(cos(a), sin(a), 0);
                    r.dir = d;
                } else { /* from a point on a surface: the hit point of a previous ray */
                    shape_ray q = {vec_make(uni(&g, -3, 3), uni(&g, -3, 3), uni(&g, -3, 3)), random_dir(&g)};
                    double t;
                    int i = brute_intersect(s, n, &q, INFINITY, &t);
                    if (i < 0)
                        continue;
                    /* as computed along the ray, or moved onto the surface
                     * (scene_intersect), or pushed off it as scene_spawn does */
                    r.origin = kind == 3 ? vec_madd(q.origin, q.dir, t) : shape_hit_point(&s[i], &q, t);
                    if (kind == 5)
                        r.origin = vec_madd(r.origin, shape_normal(&s[i], r.origin), rng_next_double(&g) < 0.5 ? 1e-12 : -1e-12);
                    r.dir = rng_next_double(&g) < 0.2 ? q.dir : random_dir(&g);
                    if (rng_next_double(&g) < 0.3)
                        tmax = uni(&g, 0.0, 3.0);
                }
                rays++;
                if (!agree(b, s, n, &r, tmax, &hits))
                    bad++;
            }
            bvh_free(b);
            free(s);
        }
    }
    CHECK_MSG(bad == 0, "%ld of %ld rays disagree", bad, rays);
    CHECK_MSG(hits > rays / 5, "only %ld of %ld rays hit: the test would prove little", hits, rays);
}

void test_bvh_degenerate_sets(void)
{
    rng_stream g = rng_make(43, 1);
    long hits = 0, bad = 0;
    /* 2000 copies of one sphere: no split exists; the lowest index wins */
    enum { N = 2000 };
    shape *s = malloc(N * sizeof *s);
    assert(s);
    for (size_t i = 0; i < N; i++)
        s[i] = shape_sphere(vec_make(0.5, 0.5, 0.5), 0.25, 0);
    bvh *b = bvh_build(s, N, 1.0);
    CHECK(b != NULL);
    if (b) {
        bvh_info info = bvh_describe(b);
        CHECK(info.depth <= BVH_MAX_DEPTH);
        shape_ray r = {vec_make(0.5, 0.5, -2), vec_make(0, 0, 1)};
        double t = 0;
        CHECK(bvh_intersect(b, s, &r, INFINITY, &t) == 0 && t == 2.25);
        for (int k = 0; k < 500; k++) {
            shape_ray q = {vec_make(uni(&g, -1, 2), uni(&g, -1, 2), uni(&g, -1, 2)), random_dir(&g)};
            bad += !agree(b, s, N, &q, INFINITY, &hits);
        }
        bvh_free(b);
    }
    /* coplanar unit rectangles tiling a plane, and a stack of identical ones */
    for (size_t i = 0; i < N; i++) {
        if (i < N / 2)
            s[i] = shape_rect(vec_make((double)(i % 40) * 0.05, 0, (double)(i / 40) * 0.05), vec_make(0, 0, 0.05),
                              vec_make(0.05, 0, 0), 0);
        else
            s[i] = shape_rect(vec_make(0, 1, 0), vec_make(1, 0, 0), vec_make(0, 0, 1), 0);
    }
    b = bvh_build(s, N, 3.0);
    CHECK(b != NULL);
    if (b) {
        for (int k = 0; k < 3000; k++) {
            shape_ray q;
            if (k % 2) { /* down onto tile edges and corners on the 0.05 grid */
                q.origin = vec_make(0.05 * (int)(rng_next_double(&g) * 41), 2, 0.05 * (int)(rng_next_double(&g) * 26));
                q.dir = vec_make(0, -1, 0);
            } else {
                q.origin = vec_make(uni(&g, -1, 3), uni(&g, -1, 3), uni(&g, -1, 3));
                q.dir = random_dir(&g);
            }
            bad += !agree(b, s, N, &q, INFINITY, &hits);
        }
        /* the stack: the first of the identical rectangles wins */
        shape_ray up = {vec_make(0.5, 0.5, 0.5), vec_make(0, 1, 0)};
        double t = 0;
        CHECK(bvh_intersect(b, s, &up, INFINITY, &t) == N / 2 && t == 0.5);
        bvh_free(b);
    }
    /* one shape */
    shape one = shape_sphere(vec_make(0, 0, 0), 1, 0);
    b = bvh_build(&one, 1, 1.0);
    CHECK(b != NULL && bvh_describe(b).nodes == 1);
    if (b) {
        shape_ray in = {vec_make(0, 0, 0), vec_make(1, 0, 0)};
        double t = 0, tl = 0;
        CHECK(bvh_intersect(b, &one, &in, INFINITY, &t) == 0 && t == 1.0);
        CHECK(bvh_intersect(b, &one, &in, 1.0, &t) == -1); /* t must be < tmax */
        CHECK(bvh_occluded(b, &one, &in, nextafter(1.0, 2.0)) && !bvh_occluded(b, &one, &in, 1.0));
        /* an origin far beyond the reach takes the linear loop: same answer */
        shape_ray far = {vec_make(-1e12, 0, 0), vec_make(1, 0, 0)};
        CHECK(bvh_intersect(b, &one, &far, INFINITY, &t) == 0 && brute_intersect(&one, 1, &far, INFINITY, &tl) == 0 &&
              t == tl);
        bvh_free(b);
    }
    free(s);
    CHECK_MSG(bad == 0, "%ld rays disagree", bad);
    CHECK(hits > 1000);
}

/* A scene of n small boxes (six rectangles each) on a grid in a closed room. */
static char *boxes_scene(size_t nboxes)
{
    size_t cap = 4096 + nboxes * 6 * 120;
    char *t = malloc(cap);
    assert(t);
    size_t len = (size_t)snprintf(t, cap,
                                  "camera position 0 1 2.4 look_at 0 1 0 up 0 1 0 fov 65\n"
                                  "light point position 0 1.75 0 power 12.566371 12.566371 12.566371\n"
                                  "material w lambert rho 0.75 0.75 0.75\nmaterial g glass ior 1.5\n"
                                  "rect corner -1 0 -1 edge1 0 0 3.5 edge2 0 2 0 material w\n"
                                  "rect corner 1 0 -1 edge1 0 2 0 edge2 0 0 3.5 material w\n"
                                  "rect corner -1 0 -1 edge1 2 0 0 edge2 0 2 0 material w\n"
                                  "rect corner -1 0 -1 edge1 0 0 3.5 edge2 2 0 0 material w\n"
                                  "rect corner -1 2 -1 edge1 2 0 0 edge2 0 0 3.5 material w\n"
                                  "rect corner -1 0 2.5 edge1 0 2 0 edge2 2 0 0 material w\n"
                                  "sphere center 0 1 0.5 radius 0.2 material g\n");
    for (size_t i = 0; i < nboxes; i++) {
        double x = -0.9 + 0.1 * (double)(i % 18), z = -0.9 + 0.1 * (double)((i / 18) % 18);
        double y = 0.05 + 0.1 * (double)(i / 324), a = 0.05;
        const char *f[6] = {"%g %g %g edge1 %g 0 0 edge2 0 %g 0", "%g %g %g edge1 0 %g 0 edge2 %g 0 0",
                            "%g %g %g edge1 0 0 %g edge2 0 %g 0", "%g %g %g edge1 0 %g 0 edge2 0 0 %g",
                            "%g %g %g edge1 0 0 %g edge2 %g 0 0", "%g %g %g edge1 %g 0 0 edge2 0 0 %g"};
        double c[6][3] = {{x, y, z}, {x, y, z + a}, {x, y, z}, {x + a, y, z}, {x, y, z}, {x, y + a, z}};
        for (int k = 0; k < 6; k++) {
            len += (size_t)snprintf(t + len, cap - len, "rect corner ");
            len += (size_t)snprintf(t + len, cap - len, f[k], c[k][0], c[k][1], c[k][2], a, a);
            len += (size_t)snprintf(t + len, cap - len, " material w\n");
            assert(len < cap);
        }
    }
    return t;
}

void test_bvh_scene_switch(void)
{
    char *text = boxes_scene(400); /* 2407 shapes */
    scene *sc = helper_scene(text), *lin = helper_scene(text);
    free(text);
    CHECK(sc->nshapes == 2407 && sc->accel == NULL); /* the parser builds none */
    CHECK(scene_set_accel(sc, SCENE_ACCEL_AUTO) == 0 && sc->accel != NULL); /* auto: a BVH */
    CHECK(strtol(SCENE_BVH_MIN_SHAPES_TEXT, NULL, 10) == SCENE_BVH_MIN_SHAPES);
    CHECK(scene_set_accel(lin, SCENE_ACCEL_LINEAR) == 0 && lin->accel == NULL);
    rng_stream g = rng_make(44, 2);
    long bad = 0, hits = 0;
    for (int k = 0; k < 20000; k++) {
        shape_ray r = {vec_make(uni(&g, -0.99, 0.99), uni(&g, 0.01, 1.99), uni(&g, -0.99, 2.49)), random_dir(&g)};
        if (k % 4 == 0) /* along an axis */
            r.dir = axis_dir(&g);
        scene_hit hb, hl;
        int ab = scene_intersect(sc, &r, INFINITY, &hb);
        int ob = scene_occluded(sc, &r, 1.0);
        int al = scene_intersect(lin, &r, INFINITY, &hl);
        int ol = scene_occluded(lin, &r, 1.0);
        hits += al;
        if (ab != al || ob != ol ||
            (al && (hb.shape != hl.shape || hb.t != hl.t || memcmp(&hb.p, &hl.p, sizeof hb.p) ||
                    memcmp(&hb.n, &hl.n, sizeof hb.n) || hb.front != hl.front || hb.eps != hl.eps)))
            bad++;
    }
    CHECK_MSG(bad == 0, "%ld rays differ between the BVH and the linear loop", bad);
    CHECK(hits == 20000); /* a closed room */
    scene_free(lin);
    /* switching: linear drops the tree, auto builds it again */
    CHECK(scene_set_accel(sc, SCENE_ACCEL_LINEAR) == 0 && sc->accel == NULL);
    CHECK(scene_set_accel(sc, SCENE_ACCEL_AUTO) == 0 && sc->accel);
    scene_free(sc);

    /* few shapes: auto keeps the linear loop */
    sc = helper_scene("camera position 0 1 2 look_at 0 1 0 up 0 1 0 fov 60\nlight point position 0 1 0 power 1 1 1\n"
                      "material w lambert rho 1 1 1\nsphere center 0 0 0 radius 1 material w\n");
    CHECK(sc->accel == NULL);
    CHECK(scene_set_accel(sc, SCENE_ACCEL_BVH) == 0 && sc->accel != NULL);
    scene_free(sc);
}

/* CPU seconds to parse a scene of nboxes boxes and build its BVH (auto, as
 * the render pipeline does): the best of three. */
static double parse_seconds(size_t nboxes, size_t *nshapes)
{
    char *text = boxes_scene(nboxes);
    double best = INFINITY;
    for (int rep = 0; rep < 3; rep++) {
        char err[256];
        scene *sc = NULL;
        clock_t c0 = clock();
        int rc = scene_parse_buffer("boxes.scene", text, strlen(text), &sc, err, sizeof err);
        if (sc)
            CHECK(scene_set_accel(sc, SCENE_ACCEL_AUTO) == 0 && sc->accel);
        double dt = (double)(clock() - c0) / CLOCKS_PER_SEC;
        CHECK_MSG(rc == PM_OK, "%s", err);
        if (sc)
            *nshapes = sc->nshapes;
        scene_free(sc);
        best = fmin(best, dt);
    }
    free(text);
    return best;
}

void test_bvh_parser_stays_linear(void)
{
    /* the documented limit: 100,000 shapes (16,665 boxes + 7 shapes = 99,997) */
    size_t n_small = 0, n_big = 0;
    double t_small = parse_seconds(4166, &n_small), t_big = parse_seconds(16665, &n_big);
    CHECK(n_small == 25003 && n_big == 99997);
    /* 4x the shapes: linear (or n log n) gives about 4-5x the time, a
     * quadratic step 16x; allow 8x (CPU time, best of three) */
    CHECK_MSG(t_big <= 8.0 * t_small + 0.05, "25k shapes %.3f s, 100k shapes %.3f s", t_small, t_big);
    printf("  parse + BVH: %zu shapes %.3f s, %zu shapes %.3f s (CPU)\n", n_small, t_small, n_big, t_big);
}
