/* info: the facts of a parsed scene as JSON (`photonmap info SCENE
 * --json`): the camera with the basis the eye pass uses for one image size,
 * the light, the materials, every shape with its scene file line, and the
 * bounds, so that tools read the scene through the renderer's own parser. */
#ifndef PM_INFO_H
#define PM_INFO_H

#include <stdint.h>
#include <stdio.h>

#include "scene.h"
#include "status.h"

/* Writes sc's facts as one JSON object to f; scene_path is the file it came
 * from, width x height the image size whose camera basis (camera_make) it
 * gives. Every number reads back to the same double. Returns PM_OK, or
 * PM_ERR_IO on a write error. */
pm_status info_write_json(FILE *f, const scene *sc, const char *scene_path, uint32_t width, uint32_t height);

#endif
