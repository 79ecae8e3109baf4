/* image: the linear RGB framebuffer and its files: OpenEXR (32-bit float,
 * through OpenEXR's C API, libOpenEXRCore) and an sRGB 8-bit PNG preview
 * (libpng). Files are written through outfile, so they appear whole or not
 * at all. */
#ifndef PM_IMAGE_H
#define PM_IMAGE_H

#include <stddef.h>
#include <stdint.h>

#include "status.h"

/* A linear RGB float framebuffer. */
typedef struct {
    uint32_t width, height;
    float *rgb; /* width*height*3, row 0 at the top */
} image;

/* Allocates a black image. Returns PM_OK, or PM_ERR_NOMEM when memory runs
 * out. */
pm_status image_init(image *im, uint32_t width, uint32_t height);
/* Frees the pixels; the struct is left empty. A zeroed image is fine. */
void image_free(image *im);
/* Pixels with a non-finite channel. */
uint64_t image_count_nonfinite(const image *im);
/* The mean of each channel over all pixels (accumulated in double). */
void image_mean(const image *im, double mean[3]);

/* Writes a linear float RGB OpenEXR (ZIP compressed) to `path` by way of a
 * temporary file. Returns PM_OK, or PM_ERR_IO (PM_ERR_NOMEM when memory
 * runs out) with "path: reason" in err. */
pm_status image_write_exr(const image *im, const char *path, char *err, size_t errlen);
/* Reads an RGB(A) OpenEXR into im (for tests and tools). Returns PM_OK, or
 * PM_ERR_IO (PM_ERR_NOMEM when memory runs out) with "path: reason" in err
 * (im is then empty). */
pm_status image_read_exr(image *im, const char *path, char *err, size_t errlen);
/* Writes an 8-bit sRGB PNG of im * exposure (clamped) to `path` by way of a
 * temporary file. Returns PM_OK, or PM_ERR_IO (PM_ERR_NOMEM when memory
 * runs out) with "path: reason" in err. */
pm_status image_write_png(const image *im, const char *path, double exposure, char *err, size_t errlen);

#endif
