/* povray: exporting a scene as POV-Ray 3.7 SDL, radiometrically matched to
 * the renderer (see scenes/README.md and reference/README.md). */
#ifndef PM_POVRAY_H
#define PM_POVRAY_H

#include <stdio.h>

#include "scene.h"

typedef enum { POV_QUALITY_FAST = 0, POV_QUALITY_REFERENCE = 1 } pov_quality;

typedef struct {
    unsigned width, height; /* the image size POV-Ray will be run at (sets the aspect ratio) */
    pov_quality quality;    /* radiosity and photon settings: fast or reference */
    int radiosity;          /* 0: no indirect diffuse light */
    int photons;            /* 0: no caustics (glass still shadows direct light) */
} pov_options;

/* 1024x768, fast, radiosity and photons on; never fails. */
pov_options pov_defaults(void);
/* "fast" or "reference". */
const char *pov_quality_name(pov_quality q);

/* Writes sc as POV-Ray 3.7 SDL to f; scene_name goes into a comment.
 * Returns 0, or -1 if the stream reports a write error. */
int pov_write(FILE *f, const scene *sc, const char *scene_name, const pov_options *o);

/* `photonmap export-pov SCENE [options]`: returns the process exit code
 * (0; 1 on I/O failure; 2 on a bad option or scene, with file:line:col). */
int povray_main(int argc, char **argv);

#endif
