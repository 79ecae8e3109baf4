/* stats: the JSON writer of a run. */
#include "stats.h"

#include <math.h>
#include <string.h>

#include "utf8.h"

void stats_json_string(FILE *f, const char *s)
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

/* The median of the n values v (sorted in place). */
static double median(double *v, uint32_t n)
{
    for (uint32_t i = 1; i < n; i++)
        for (uint32_t j = i; j > 0 && v[j] < v[j - 1]; j--) {
            double x = v[j];
            v[j] = v[j - 1];
            v[j - 1] = x;
        }
    return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

static const char *const phase_names[STATS_PHASES] = {"trace", "build", "precompute", "render", "total"};

/* The times of every repeat: cold (the first), median, and each repeat's. */
static void write_repeats(FILE *f, const stats_run *st)
{
    stats_repeats one;
    const stats_repeats *r = &st->repeats;
    if (r->n == 0) {
        one.n = 1;
        one.t[0][STATS_TRACE] = st->trace;
        one.t[0][STATS_BUILD] = st->build;
        one.t[0][STATS_PRECOMPUTE] = st->precompute;
        one.t[0][STATS_RENDER] = st->render;
        one.t[0][STATS_TOTAL] = st->total;
        r = &one;
    }
    fprintf(f, "  \"repeats\": %u,\n  \"time_s_cold\": {", r->n);
    for (int p = 0; p < STATS_PHASES; p++)
        fprintf(f, "%s\"%s\": %.6f", p ? ", " : "", phase_names[p], r->t[0][p]);
    fputs("},\n  \"time_s_median\": {", f);
    for (int p = 0; p < STATS_PHASES; p++) {
        double v[CONFIG_MAX_REPEATS];
        for (uint32_t i = 0; i < r->n; i++)
            v[i] = r->t[i][p];
        fprintf(f, "%s\"%s\": %.6f", p ? ", " : "", phase_names[p], median(v, r->n));
    }
    fputs("},\n  \"time_s_repeats\": {", f);
    for (int p = 0; p < STATS_PHASES; p++) {
        fprintf(f, "%s\"%s\": [", p ? ", " : "", phase_names[p]);
        for (uint32_t i = 0; i < r->n; i++)
            fprintf(f, "%s%.6f", i ? ", " : "", r->t[i][p]);
        fputc(']', f);
    }
    fputs("},\n", f);
    if (r != &st->repeats)
        return; /* no repeat loop: no fault counts */
    fputs("  \"minor_faults_repeats\": [", f);
    for (uint32_t i = 0; i < r->n; i++)
        fprintf(f, "%s%llu", i ? ", " : "", (unsigned long long)r->faults[i]);
    fputs("],\n", f);
}

/* The provenance object (threads: the render's). */
static void write_provenance(FILE *f, const provenance_info *p, unsigned threads)
{
    fputs("  \"provenance\": {\"commit\": ", f);
    stats_json_string(f, p->commit ? p->commit : "unknown");
    fputs(", \"tree\": ", f);
    stats_json_string(f, p->tree ? p->tree : "unknown");
    fputs(", \"compiler\": ", f);
    stats_json_string(f, p->compiler ? p->compiler : "unknown");
    fputs(", \"flags\": ", f);
    stats_json_string(f, p->flags ? p->flags : "unknown");
    fputs(", \"cpu\": ", f);
    stats_json_string(f, p->cpu[0] ? p->cpu : "unknown");
    fprintf(f, ", \"threads\": %u, \"loadavg\": [", threads);
    for (int i = 0; i < 3; i++) {
        if (p->commit && p->loadavg[i] >= 0.0)
            fprintf(f, "%.2f", p->loadavg[i]);
        else
            fputs("null", f);
        fputs(i < 2 ? ", " : "]},\n", f);
    }
}

pm_status stats_write_json(FILE *f, const char *scene_path, const config_render *cfg, unsigned threads,
                           const stats_run *st, const char *refused)
{
    fprintf(f, "{\n  \"status\": \"%s\",\n", refused ? "refused" : "ok");
    if (refused) {
        fputs("  \"reason\": ", f);
        stats_json_string(f, refused);
        fputs(",\n", f);
    }
    fputs("  \"scene\": ", f);
    stats_json_string(f, scene_path);
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
    fprintf(f, "  \"gather\": %u,\n", cfg->gather);
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
    write_repeats(f, st);
    fputs("  \"work\": ", f);
    work_write_json(f, &st->work);
    fputs(",\n", f);
    write_provenance(f, &st->provenance, threads);
    fprintf(f, "  \"samples\": %llu,\n", (unsigned long long)st->samples);
    fprintf(f, "  \"eye_depth_limit_hits\": %llu,\n", (unsigned long long)st->eye_depth_limit_hits);
    fprintf(f, "  \"empty_estimates\": %llu,\n", (unsigned long long)st->empty_estimates);
    fprintf(f, "  \"bytes_photon_map\": %llu,\n", (unsigned long long)st->bytes_photon_map);
    fprintf(f, "  \"bytes_representatives\": %llu,\n", (unsigned long long)st->bytes_representatives);
    fprintf(f, "  \"caustic_photons\": %llu,\n", (unsigned long long)st->caustic_photons);
    fprintf(f, "  \"bytes_caustic_map\": %llu,\n", (unsigned long long)st->bytes_caustic_map);
    fprintf(f,
            "  \"gather_work\": {\"rays\": %llu, \"specular\": %llu, \"lookups\": %llu, \"empty\": %llu, "
            "\"fallbacks\": %llu, \"missed\": %llu, \"depth_limit_hits\": %llu, \"caustic_lookups\": %llu, "
            "\"caustic_nodes\": %llu, \"caustic_points\": %llu},\n",
            (unsigned long long)st->gather_rays, (unsigned long long)st->gather_specular,
            (unsigned long long)st->gather_lookups, (unsigned long long)st->gather_empty,
            (unsigned long long)st->gather_fallbacks, (unsigned long long)st->gather_missed,
            (unsigned long long)st->gather_depth_limit_hits, (unsigned long long)st->caustic_lookups,
            (unsigned long long)st->caustic_nodes, (unsigned long long)st->caustic_points);
    fprintf(f, "  \"gather_time\": {\"gather_thread_s\": %.6f, \"render_thread_s\": %.6f, \"share\": ",
            st->gather_thread_s, st->render_thread_s);
    json_number(f, st->render_thread_s > 0.0 ? st->gather_thread_s / st->render_thread_s : 0.0);
    fputs("},\n", f);
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
