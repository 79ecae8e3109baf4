/* helpers: scene-from-text for the unit tests. */
#include "helpers.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

scene *helper_scene(const char *text)
{
    char err[512];
    scene *s = NULL;
    if (scene_parse_buffer("test.scene", text, strlen(text), &s, err, sizeof err) != SCENE_OK) {
        fprintf(stderr, "test scene does not parse: %s\n", err);
        abort();
    }
    return s;
}
