/* stats: the JSON writer of a run. */
#include "stats.h"

#include <math.h>
#include <string.h>

#include "utf8.h"

/* Writes s as a JSON string: valid UTF-8 as is, control characters
 * escaped, and each byte that is not valid UTF-8 (a path may hold any bytes)
 * as U+FFFD, so the file always parses. */
static void json_string(FILE *f, const char *s)
{
    const unsigned char *p = (const unsigned char *)s;
    size_t n = strlen(s);
    fputc('"', f);
    while (n > 0) {
        unsigned char c = *p;
        size_t l = utf8_sequence_len(p, n);
        if (l == 0) {
            fputs("\\ufffd", f);
            l = 1;
        } else if (c == '"' || c == '\\') {
            fprintf(f, "\\%c", c);
        } else if (c < 0x20) {
            fprintf(f, "\\u%04x", c);
        } else {
            fwrite(p, 1, l, f);
        }
        p += l;
        n -= l;
    }
    fputc('"', f);
}

/* Writes x as a JSON number, or null when it is not finite (JSON has no
 * Inf or NaN). */
static void json_number(FILE *f, double x)
{
    if (isfinite(x))
        fprintf(f, "%.9g", x);
    else
        fputs("null", f);
}

pm_status stats_write_json(FILE *f, const char *scene_path, const config_render *cfg, unsigned threads,
                           const stats_run *st, const char *refused)
{
    fprintf(f, "{\n  \"status\": \"%s\",\n", refused ? "refused" : "ok");
    if (refused) {
        fputs("  \"reason\": ", f);
        json_string(f, refused);
        fputs(",\n", f);
    }
    fputs("  \"scene\": ", f);
    json_string(f, scene_path);
    fprintf(f, ",\n  \"method\": \"%s\",\n", config_method_name(cfg->method));
    fprintf(f, "  \"direct\": \"%s\",\n", config_direct_name(cfg->direct));
    fprintf(f, "  \"estimate\": \"%s\",\n", cfg->bias_correction ? "corrected" : "paper");
    fprintf(f, "  \"photons_emitted\": %llu,\n", (unsigned long long)st->photons_emitted);
    fprintf(f, "  \"photons_stored\": %llu,\n", (unsigned long long)st->photons_stored);
    fprintf(f, "  \"photon_paths_truncated\": %llu,\n", (unsigned long long)st->photon_paths_truncated);
    fprintf(f, "  \"photons_escaped\": %llu,\n", (unsigned long long)st->photons_escaped);
    fprintf(f, "  \"representatives\": %llu,\n", (unsigned long long)st->representatives);
    fprintf(f, "  \"rep_every\": %u,\n", cfg->rep_every);
    fprintf(f, "  \"rep_count\": %llu,\n", (unsigned long long)cfg->rep_count);
    fprintf(f, "  \"normal_cos\": %.17g,\n", cfg->normal_cos);
    fprintf(f, "  \"rep_tree\": \"%s\",\n", config_rep_tree_name(cfg->rep_tree));
    fprintf(f, "  \"rep_eval\": \"%s\",\n", config_rep_eval_name(cfg->rep_eval));
    fprintf(f, "  \"rep_gate\": \"%s\",\n", config_rep_gate_name(cfg->rep_gate));
    fprintf(f, "  \"rep_gate_tau\": %.17g,\n", cfg->rep_gate_tau);
    fprintf(f, "  \"reps_evaluated\": %llu,\n", (unsigned long long)st->reps_evaluated);
    fprintf(f, "  \"rep_fallbacks\": %llu,\n", (unsigned long long)st->rep_fallbacks);
    fprintf(f, "  \"nn\": %u,\n", cfg->nn);
    fprintf(f, "  \"max_radius\": %.17g,\n", st->max_radius);
    fprintf(f, "  \"width\": %u,\n  \"height\": %u,\n", cfg->width, cfg->height);
    fprintf(f, "  \"samples_per_pixel\": %u,\n", cfg->subpixels * cfg->subpixels);
    fprintf(f, "  \"threads\": %u,\n", threads);
    fprintf(f, "  \"accel\": \"%s\",\n", config_accel_name(cfg->accel));
    fprintf(f, "  \"seed\": %llu,\n", (unsigned long long)cfg->seed);
    fprintf(f, "  \"photon_depth\": %u,\n", cfg->photon_depth);
    fprintf(f, "  \"eye_depth\": %u,\n", cfg->eye_depth);
    fprintf(f, "  \"time_s\": {\"trace\": %.6f, \"build\": %.6f, \"precompute\": %.6f, \"render\": %.6f, "
               "\"total\": %.6f},\n",
            st->trace, st->build, st->precompute, st->render, st->total);
    fprintf(f, "  \"samples\": %llu,\n", (unsigned long long)st->samples);
    fprintf(f, "  \"eye_depth_limit_hits\": %llu,\n", (unsigned long long)st->eye_depth_limit_hits);
    fprintf(f, "  \"empty_estimates\": %llu,\n", (unsigned long long)st->empty_estimates);
    fprintf(f, "  \"bytes_photon_map\": %llu,\n", (unsigned long long)st->bytes_photon_map);
    fprintf(f, "  \"bytes_representatives\": %llu,\n", (unsigned long long)st->bytes_representatives);
    fprintf(f, "  \"mean_radiance\": [");
    for (int c = 0; c < 3; c++) {
        json_number(f, st->mean_radiance[c]);
        fputs(c < 2 ? ", " : "],\n", f);
    }
    fprintf(f, "  \"underflow_pixels\": %llu,\n", (unsigned long long)st->underflow_pixels);
    fprintf(f, "  \"flushed_values\": %llu,\n", (unsigned long long)st->flushed_values);
    fprintf(f, "  \"nonfinite_pixels\": %llu\n}\n", (unsigned long long)st->nonfinite_pixels);
    return ferror(f) ? PM_ERR_IO : PM_OK;
}
