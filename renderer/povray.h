/* povray: exporting a scene as POV-Ray 3.7 SDL, radiometrically matched to
 * the renderer (see scenes/README.md and reference/README.md). */
#ifndef PM_POVRAY_H
#define PM_POVRAY_H

#include <stdint.h>
#include <stdio.h>

#include "scene.h"
#include "status.h"

/* POV-Ray's radiosity and photon settings. */
typedef enum { POVRAY_QUALITY_FAST = 0, POVRAY_QUALITY_REFERENCE = 1 } povray_quality;

/* What export-pov writes. */
typedef struct {
    uint32_t width, height;     /* the image size POV-Ray will be run at (sets the aspect ratio) */
    povray_quality quality;    /* radiosity and photon settings: fast or reference */
    int radiosity;          /* 0: no indirect diffuse light */
    int photons;            /* 0: no caustics (glass still shadows direct light) */
    int glass_caustics;     /* 0: glass is no photon target, so it casts no caustic, and its shadow-only
                               proxy is added so that it still blocks direct light; mirror caustics and
                               radiosity stay (the "glass caustic missing" negative control) */
    double rect_thickness;  /* a rectangle's box, as a fraction of the scene's diagonal */
    uint32_t bounces;       /* radiosity recursion_limit: indirect diffuse bounces */
} povray_options;

/* The default rect_thickness: 1e-3 of the diagonal (4.5 mm in the paper's
 * room); thin geometry (scenes/slabs.scene) needs thinner boxes. */
#define POVRAY_RECT_THICKNESS 1e-3
#define POVRAY_RECT_THICKNESS_MIN 1e-9
#define POVRAY_RECT_THICKNESS_MAX 1e-2
/* The default number of indirect bounces (radiosity recursion_limit), and
 * POV-Ray's largest. Measured: POV-Ray adds no light beyond about 8 bounces
 * (reference/README.md); `render --photon-depth B+1` is the same light path
 * length as `export-pov --bounces B`. */
#define POVRAY_BOUNCES 20
#define POVRAY_BOUNCES_MAX 20

/* 1024x768, fast, radiosity (20 bounces), photons and glass caustics on,
 * rectangles 1e-3 thick; never fails. */
povray_options povray_defaults(void);
/* "fast" or "reference". */
const char *povray_quality_name(povray_quality q);
/* The qualities' names in the order of povray_quality, NULL-terminated
 * (the option table's choices). */
extern const char *const povray_quality_names[];

/* Writes sc as POV-Ray 3.7 SDL to f; scene_name goes into a comment.
 * Returns PM_OK, or PM_ERR_IO if the stream reports a write error. */
pm_status povray_write(FILE *f, const scene *sc, const char *scene_name, const povray_options *o);

#endif
