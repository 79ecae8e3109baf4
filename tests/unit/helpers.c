/* helpers: scene-from-text and renders for the unit tests. */
#include "helpers.h"

#include "mem.h"
#include "render.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

scene *helper_scene(const char *text)
{
    char err[512];
    scene *s = NULL;
    if (scene_parse_buffer("test.scene", text, strlen(text), &s, err, sizeof err) != PM_OK) {
        fprintf(stderr, "test scene does not parse: %s\n", err);
        abort();
    }
    return s;
}

pm_status helper_render(const scene *sc, const config_render *cfg, unsigned threads, image *out, stats_run *st)
{
    char err[512];
    render_result res;
    pm_status rc = render_run(sc, cfg, threads, 0, &res, err, sizeof err);
    if (rc != PM_OK)
        fprintf(stderr, "  render_run: %s\n", err);
    *out = res.img;
    *st = res.st;
    reps_free(&res.reps);
    photons_map_free(&res.map);
    return rc;
}

pm_status helper_reps(const photons_map *m, const est_gather *g, config_rep_tree tree, unsigned threads,
                      reps_set *out)
{
    reps_params p = {.rep_every = 0, .rep_count = 0, .rep_tree = tree, .bias_correction = 0,
                     .normal_cos = CONFIG_DEFAULT_NORMAL_COS};
    pm_status rc;
    if ((rc = reps_collect(&p, m, NULL, out)) != PM_OK)
        return rc;
    if ((rc = reps_evaluate(out, m, g, threads, NULL)) != PM_OK)
        reps_free(out);
    return rc;
}

uint32_t helper_knn(const kd_tree *t, const float q[3], uint32_t k, float max_d2, uint32_t *idx, float *d2,
                    float *r2)
{
    kd_query s;
    memset(&s, 0, sizeof s);
    kd_query_simd(&s, KD_SIMD_AVX2); /* the best this CPU has */
    uint32_t n = kd_query_knn(t, &s, q, k, max_d2, idx, d2, r2);
    kd_query_free(&s);
    return n;
}

/* A photon map of `count` photons at pos[], each travelling along dir onto a
 * surface of normal `normal`, power `power` per channel, flags as given. */
void helper_map(photons_map *m, const float (*pos)[3], uint32_t count, vec3 dir, vec3 normal, float power,
                     unsigned flags)
{
    photons_list l;
    memset(&l, 0, sizeof l);
    l.count = count;
    l.pos = mem_alloc(sizeof(double) * 3 * (count ? count : 1));
    l.ph = mem_zalloc(sizeof(photons_record) * (count ? count : 1));
    if (!l.pos || !l.ph)
        abort();
    for (uint32_t i = 0; i < count; i++) {
        for (int a = 0; a < 3; a++)
            l.pos[3 * i + (uint32_t)a] = pos[i][a];
        for (int c = 0; c < 3; c++)
            l.ph[i].power[c] = power;
        photons_pack_dir(dir.x, dir.y, dir.z, l.ph[i].dir);
        photons_pack_dir(normal.x, normal.y, normal.z, l.ph[i].normal);
        l.ph[i].flags = (uint8_t)flags;
    }
    l.unit = vec_make(1, 1, 1);
    if (photons_build_map(&l, 0, 1, m, NULL) != PM_OK)
        abort();
}

int helper_trees_equal(const kd_tree *a, const kd_tree *b)
{
    if (a->n != b->n || a->nleaves != b->nleaves || a->scan_h != b->scan_h)
        return 0;
    if (memcmp(a->lo, b->lo, sizeof a->lo) || memcmp(a->hi, b->hi, sizeof a->hi))
        return 0;
    size_t inner = a->nleaves - 1, n = a->n;
    return !memcmp(a->split, b->split, inner * sizeof(float)) && !memcmp(a->axis, b->axis, inner) &&
           !memcmp(a->leaf_start, b->leaf_start, (a->nleaves + 1) * sizeof(uint32_t)) &&
           !memcmp(a->x, b->x, n * sizeof(float)) && !memcmp(a->y, b->y, n * sizeof(float)) &&
           !memcmp(a->z, b->z, n * sizeof(float));
}
