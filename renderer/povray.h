/* povray: exporting a scene as POV-Ray 3.7 SDL, radiometrically matched to
 * the renderer (see scenes/README.md and reference/README.md). */
#ifndef PM_POVRAY_H
#define PM_POVRAY_H

#include <stdint.h>
#include <stdio.h>

#include "scene.h"

typedef enum { POVRAY_QUALITY_FAST = 0, POVRAY_QUALITY_REFERENCE = 1 } povray_quality;

typedef struct {
    uint32_t width, height;     /* the image size POV-Ray will be run at (sets the aspect ratio) */
    povray_quality quality;    /* radiosity and photon settings: fast or reference */
    int radiosity;          /* 0: no indirect diffuse light */
    int photons;            /* 0: no caustics (glass still shadows direct light) */
} povray_options;

/* 1024x768, fast, radiosity and photons on; never fails. */
povray_options povray_defaults(void);
/* "fast" or "reference". */
const char *povray_quality_name(povray_quality q);

/* Writes sc as POV-Ray 3.7 SDL to f; scene_name goes into a comment.
 * Returns 0, or -1 if the stream reports a write error. */
int povray_write(FILE *f, const scene *sc, const char *scene_name, const povray_options *o);

#endif
