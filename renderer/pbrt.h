/* pbrt: exporting a scene as a pbrt-v3 scene file that renders the same
 * radiance our renderer computes (reference/pbrt/README.md has the facts
 * behind the mapping). */
#ifndef PM_PBRT_H
#define PM_PBRT_H

#include <stddef.h>
#include <stdint.h>
#include <stdio.h>

#include "scene.h"
#include "status.h"

/* The pbrt integrator the scene asks for. */
typedef enum {
    PBRT_INTEGRATOR_BDPT = 0,          /* bidirectional path tracing */
    PBRT_INTEGRATOR_PATH = 1,          /* unidirectional path tracing (min_bounces needs the local change) */
    PBRT_INTEGRATOR_DIRECTLIGHTING = 2 /* direct light, specular chains traced: the --direct shadow-rays check */
} pbrt_integrator;

/* What export-pbrt writes. */
typedef struct {
    uint32_t width, height;     /* the film resolution */
    pbrt_integrator integrator;
    uint32_t bounces;           /* indirect bounces: pbrt's maxdepth is bounces + 1 (render --photon-depth B+1) */
    uint32_t min_bounces;       /* path only: keep paths with more than this many indirect bounces (pbrt
                                   mindepth = min_bounces + 1; 0 writes no mindepth, stock pbrt) */
    uint32_t spp;               /* samples per pixel (stratified: the nearest square at or above) */
    int fixed_subpixels;        /* 1: stratified without jitter at sqrt(spp) x sqrt(spp) fixed points, the
                                   renderer's --subpixels grid (directlighting check) */
} pbrt_options;

/* The default indirect bounces (pbrt maxdepth 64) and the largest accepted. */
#define PBRT_BOUNCES 63
#define PBRT_BOUNCES_MAX 1000
#define PBRT_SPP 64
#define PBRT_SPP_MAX 1048576

/* 1024x768, bdpt, 63 bounces, no minimum, 64 spp, jittered; never fails. */
pbrt_options pbrt_defaults(void);
/* "bdpt", "path" or "directlighting". */
const char *pbrt_integrator_name(pbrt_integrator i);
/* The integrators' names in the order of pbrt_integrator, NULL-terminated
 * (the option table's choices). */
extern const char *const pbrt_integrator_names[];

/* Checks that sc and o can be written as a pbrt scene with the same
 * radiance. Returns PM_ERR_INPUT with the cause in err for a glass
 * rectangle, the camera or the light inside a glass sphere
 * (renderer/README.md), or min_bounces with an integrator other than path
 * or not below bounces. */
pm_status pbrt_check(const scene *sc, const pbrt_options *o, char *err, size_t errlen);

/* Writes sc (already accepted by pbrt_check) as pbrt-v3 scene text to f;
 * scene_name goes into a comment. Returns PM_OK, or PM_ERR_IO if the stream
 * reports a write error. */
pm_status pbrt_write(FILE *f, const scene *sc, const char *scene_name, const pbrt_options *o);

#endif
