/* test_image: OpenEXR round trip and atomic output files. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "check.h"
#include "image.h"
#include "tests.h"

void test_exr_round_trip(void)
{
    image im;
    CHECK(image_init(&im, 37, 21) == 0); /* odd sizes: partial last chunk */
    for (size_t i = 0; i < 37 * 21 * 3; i++)
        im.rgb[i] = (float)(i % 7) * 0.37f + (i % 3 == 0 ? 1e-30f : 0.0f) + (i == 5 ? 1e30f : 0.0f);
    char path[] = "/tmp/pm-test-exr-XXXXXX";
    int fd = mkstemp(path);
    CHECK(fd >= 0);
    close(fd);
    char err[512];
    CHECK_MSG(image_write_exr(&im, path, err, sizeof err) == 0, "%s", err);
    image back;
    CHECK_MSG(image_read_exr(&back, path, err, sizeof err) == 0, "%s", err);
    CHECK(back.width == 37 && back.height == 21);
    if (back.rgb)
        CHECK(memcmp(back.rgb, im.rgb, sizeof(float) * 37 * 21 * 3) == 0);
    image_free(&back);
    /* unwritable directory: an error naming the path, nothing left behind */
    CHECK(image_write_exr(&im, "/nonexistent-dir/x.exr", err, sizeof err) == PM_ERR_IO);
    CHECK(strstr(err, "/nonexistent-dir/x.exr") != NULL);
    CHECK(image_write_png(&im, "/nonexistent-dir/x.png", 1.0, err, sizeof err) == PM_ERR_IO);
    /* PNG: a real file with the PNG signature */
    char png[64];
    snprintf(png, sizeof png, "%s.png", path);
    CHECK_MSG(image_write_png(&im, png, 1.0, err, sizeof err) == 0, "%s", err);
    FILE *f = fopen(png, "rb");
    unsigned char sig[8] = {0};
    CHECK(f && fread(sig, 1, 8, f) == 8 && memcmp(sig, "\x89PNG\r\n\x1a\n", 8) == 0);
    if (f)
        fclose(f);
    unlink(png);
    unlink(path);
    image_free(&im);
}
