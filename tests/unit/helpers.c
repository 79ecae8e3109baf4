/* helpers: scene-from-text and renders for the unit tests. */
#include "helpers.h"

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

int helper_render(const scene *sc, const config_render *cfg, unsigned threads, image *out, stats_run *st)
{
    char err[512];
    render_result res;
    int rc = render_run(sc, cfg, threads, 0, &res, err, sizeof err);
    if (rc != PM_OK)
        fprintf(stderr, "  render_run: %s\n", err);
    *out = res.img;
    *st = res.st;
    reps_free(&res.reps);
    photons_map_free(&res.map);
    return rc;
}

int helper_reps(const photons_map *m, const est_gather *g, config_rep_tree tree, unsigned threads, reps_set *out)
{
    reps_params p = {0, 0, tree, 0};
    if (reps_collect(&p, m, NULL, out))
        return -1;
    if (reps_evaluate(out, m, g, threads, NULL)) {
        reps_free(out);
        return -1;
    }
    return 0;
}
