/* test_photons: the photon pass and the map. Power is conserved in a closed
 * diffuse box (every emitted watt is stored or absorbed), whatever the
 * chunking; photons_build_map's map is the tree kd_build makes over the
 * map-frame points with each record at its point's leaf position (a
 * cross-check of the in-place path against the plain one); and
 * photons_peak_bytes follows the memory a trace and build really take (the
 * peak resident set, read from /proc), within 10%. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "check.h"
#include "helpers.h"
#include "mem.h"
#include "photons.h"
#include "rng.h"
#include "tests.h"

/* A closed diffuse box with the light inside. */
static const char *closed_box =
    "camera position 0 1 1.5 look_at 0 1 0 up 0 1 0 fov 60\n"
    "light point position 0.1 1.2 -0.3 power 3 2 1\n"
    "material w lambert rho 0.5 0.5 0.5\n"
    "rect corner -1 0 -2 edge1 0 0 4 edge2 0 2 0 material w\n"
    "rect corner 1 0 -2 edge1 0 2 0 edge2 0 0 4 material w\n"
    "rect corner -1 0 -2 edge1 2 0 0 edge2 0 2 0 material w\n"
    "rect corner -1 0 2 edge1 0 2 0 edge2 2 0 0 material w\n"
    "rect corner -1 0 -2 edge1 0 0 4 edge2 2 0 0 material w\n"
    "rect corner -1 2 -2 edge1 2 0 0 edge2 0 0 4 material w\n";

void test_photon_power_closed_box(void)
{
    scene *sc = helper_scene(closed_box);
    photons_params pp = {100003, 1, 64, 1}; /* P_e not a multiple of the chunk size */
    photons_list l;
    CHECK(photons_trace(sc, &pp, 2, NULL, &l) == 0);
    double sum[3] = {0, 0, 0};
    uint64_t first = 0;
    for (uint64_t i = 0; i < l.count; i++) {
        if (l.ph[i].flags & PHOTONS_FLAG_DIRECT) {
            first++;
            for (int c = 0; c < 3; c++)
                sum[c] += l.ph[i].power[c] * (c == 0 ? l.unit.x : c == 1 ? l.unit.y : l.unit.z);
        }
    }
    CHECK(first == pp.photons); /* every photon's first hit is diffuse and stored */
    CHECK(l.escaped == 0);
    CHECK_REL(sum[0], 3.0, 1e-6);
    CHECK_REL(sum[1], 2.0, 1e-6);
    CHECK_REL(sum[2], 1.0, 1e-6);
    /* albedo 0.5: on average 1/(1-0.5) = 2 stored photons per emitted one */
    CHECK_NEAR((double)l.count / pp.photons, 2.0, 0.02);
    photons_list_free(&l);
    /* shadow-ray mode stores no first hits */
    pp.store_first_hits = 0;
    CHECK(photons_trace(sc, &pp, 1, NULL, &l) == 0);
    uint64_t direct = 0;
    for (uint64_t i = 0; i < l.count; i++)
        direct += (l.ph[i].flags & PHOTONS_FLAG_DIRECT) != 0;
    CHECK(direct == 0 && l.count > 0);
    photons_list_free(&l);
    scene_free(sc);
}

/* A closed diffuse box with the light inside: about 2 photons stored per
 * emitted one, all of them in the map. */
static const char *box_scene =
    "camera position 0 1 1.5 look_at 0 1 0 up 0 1 0 fov 60\n"
    "light point position 0.1 1.2 -0.3 power 3 2 1\n"
    "material w lambert rho 0.5 0.5 0.5\n"
    "rect corner -1 0 -2 edge1 0 0 4 edge2 0 2 0 material w\n"
    "rect corner 1 0 -2 edge1 0 2 0 edge2 0 0 4 material w\n"
    "rect corner -1 0 -2 edge1 2 0 0 edge2 0 2 0 material w\n"
    "rect corner -1 0 2 edge1 0 2 0 edge2 2 0 0 material w\n"
    "rect corner -1 0 -2 edge1 0 0 4 edge2 2 0 0 material w\n"
    "rect corner -1 2 -2 edge1 2 0 0 edge2 0 0 4 material w\n";

/* A copy of a list (mem buffers, as the build frees them). */
static void copy_list(const photons_list *l, photons_list *out)
{
    *out = *l;
    out->pos = mem_alloc(sizeof(double) * 3 * (l->count ? l->count : 1));
    out->ph = mem_alloc(sizeof(photons_record) * (l->count ? l->count : 1));
    memcpy(out->pos, l->pos, sizeof(double) * 3 * l->count);
    memcpy(out->ph, l->ph, sizeof(photons_record) * l->count);
}

/* photons_build_map's map (1 and 2 threads, every 5th photon left out or
 * none) is kd_build's tree over the kept photons' map-frame points, each
 * record at its point's leaf position, and the left-out photons are the
 * flagged ones in trace order; as a negative control, a record moved is
 * seen. */
void test_photons_map_matches_plain_build(void)
{
    scene *sc = helper_scene(box_scene);
    photons_params pp = {150001, 3, 64, 1};
    photons_list l;
    CHECK(photons_trace(sc, &pp, 2, NULL, &l) == 0);
    for (uint64_t i = 0; i < l.count; i += 5)
        l.ph[i].flags |= PHOTONS_FLAG_REP;
    for (int mask = 0; mask <= 1; mask++)
        for (unsigned th = 1; th <= 2; th++) {
            uint8_t leave = mask ? PHOTONS_FLAG_REP : 0;
            photons_list copy, left;
            copy_list(&l, &copy);
            photons_map m;
            CHECK(photons_build_map(&copy, leave, th, &m, &left) == 0);
            CHECK(m.stored == l.count);
            float *pts = malloc(sizeof(float) * 3 * (l.count ? l.count : 1));
            uint32_t *src = malloc(sizeof(uint32_t) * (l.count ? l.count : 1));
            uint32_t n = 0, nl = 0;
            int left_ok = 1;
            for (uint32_t i = 0; i < l.count; i++) {
                if (l.ph[i].flags & leave) {
                    left_ok &= nl < left.count && !memcmp(&left.ph[nl], &l.ph[i], sizeof l.ph[i]) &&
                               !memcmp(left.pos + 3 * (size_t)nl, l.pos + 3 * (size_t)i, 3 * sizeof(double));
                    nl++;
                    continue;
                }
                photons_map_point(&m, vec_make(l.pos[3 * i], l.pos[3 * i + 1], l.pos[3 * i + 2]), pts + 3 * n);
                src[n++] = i;
            }
            CHECK_MSG(left_ok && nl == left.count, "mask %d: the left-out list is not the flagged photons", mask);
            CHECK(m.count == n);
            uint32_t *perm = malloc(sizeof(uint32_t) * (n + 1));
            kd_tree ref;
            CHECK(kd_build(&ref, pts, n, KD_DEFAULT_LEAF, perm, 1) == PM_OK);
            CHECK_MSG(helper_trees_equal(&ref, &m.tree), "mask %d, %u threads: another tree", mask, th);
            int ok = 1;
            for (uint32_t i = 0; i < n; i++)
                ok &= !memcmp(&m.ph[i], &l.ph[src[perm[i]]], sizeof m.ph[i]);
            CHECK_MSG(ok, "mask %d, %u threads: a record is not at its point's leaf position", mask, th);
            /* negative control: a swapped pair of records is seen */
            if (n > 2 && memcmp(&m.ph[0], &m.ph[1], sizeof m.ph[0])) {
                photons_record r = m.ph[0];
                m.ph[0] = m.ph[1];
                m.ph[1] = r;
                CHECK(memcmp(&m.ph[0], &l.ph[src[perm[0]]], sizeof r) != 0);
            }
            kd_free(&ref);
            free(perm);
            free(pts);
            free(src);
            photons_map_free(&m);
            photons_list_free(&left);
        }
    photons_list_free(&l);
    scene_free(sc);
}

#if defined(__SANITIZE_ADDRESS__)
#define SCALE_SANITIZED 1
#elif defined(__has_feature)
#if __has_feature(address_sanitizer)
#define SCALE_SANITIZED 1
#endif
#endif

#ifndef SCALE_SANITIZED
/* This process's resident set (VmRSS) or its peak (VmHWM) in bytes, 0 when
 * /proc says nothing. */
static double proc_status_bytes(const char *key)
{
    FILE *f = fopen("/proc/self/status", "r");
    if (!f)
        return 0.0;
    char line[256];
    double kb = 0.0;
    size_t len = strlen(key);
    while (fgets(line, sizeof line, f))
        if (!strncmp(line, key, len) && line[len] == ':')
            kb = atof(line + len + 1);
    fclose(f);
    return kb * 1024.0;
}

/* Resets the peak resident set to the current one; 0 on success. */
static int reset_peak(void)
{
    FILE *f = fopen("/proc/self/clear_refs", "w");
    if (!f)
        return -1;
    int rc = fputs("5", f) < 0;
    return fclose(f) != 0 || rc ? -1 : 0;
}

#endif

/* The peak resident set of a trace and build of about 1.2M stored photons
 * (on two threads) is photons_peak_bytes of the count within 10%, and
 * below 48 bytes a stored photon (beyond the in-flight chunks' four huge
 * pages); as a negative control, the check would refuse an estimate 25%
 * too high or too low (an estimate twice this one among them). Skipped where /proc cannot reset the peak
 * and under the address sanitizer (its shadow memory counts). */
void test_photons_peak_memory(void)
{
#ifdef SCALE_SANITIZED
    CHECK_SKIP("the address sanitizer's shadow memory counts in the resident set");
    return;
#else
    scene *sc = helper_scene(box_scene);
    photons_params pp = {600000, 5, 64, 1};
    double before = proc_status_bytes("VmRSS");
    if (reset_peak() || before <= 0.0 || proc_status_bytes("VmHWM") <= 0.0) {
        scene_free(sc);
        CHECK_SKIP("/proc/self/clear_refs cannot reset the peak resident set here");
        return;
    }
    photons_list l;
    photons_map m;
    CHECK(photons_trace(sc, &pp, 2, NULL, &l) == 0);
    double stored = (double)l.count;
    CHECK(photons_build_map(&l, 0, 2, &m, NULL) == 0);
    double peak = proc_status_bytes("VmHWM") - before, est = photons_peak_bytes(stored);
    fprintf(stderr, "  %.0f stored: peak %.1f MB (%.1f B each), estimate %.1f MB (%.1f B each)\n", stored,
            peak / 1e6, peak / stored, est / 1e6, est / stored);
    CHECK(stored > 1e6);
    CHECK_MSG(fabs(est / peak - 1.0) <= 0.10, "estimate %.0f vs peak %.0f bytes", est, peak);
    /* the chunks in flight hold up to 4 huge pages whatever the count */
    CHECK_MSG(peak - 4.0 * (double)MEM_HUGE_MIN <= 48.0 * stored, "%.1f bytes a stored photon", peak / stored);
    /* negative controls: estimates 25% off, and twice it, fail the check */
    CHECK(!(fabs(1.25 * est / peak - 1.0) <= 0.10));
    CHECK(!(fabs(0.75 * est / peak - 1.0) <= 0.10));
    CHECK(!(fabs(2.0 * est / peak - 1.0) <= 0.10));
    photons_map_free(&m);
    scene_free(sc);
#endif
}
