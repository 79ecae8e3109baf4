/* imgmetrics: error of one linear RGB EXR against a reference EXR.
 *
 *   build/imgmetrics TEST.exr REF.exr [--mask MASK.exr] [--peak 1|max] [--csv|--header]
 *
 * Over every pixel (or only the pixels where the mask has a non-zero channel)
 * and every RGB channel (x = test, r = reference):
 *   relMSE = mean((x - r)^2 / (r^2 + 0.01))
 *   RMSE   = sqrt(mean((x - r)^2))
 *   PSNR   = 10 log10(peak^2 / MSE) dB, peak = 1 (default: linear radiance
 *            1.0 = display white at exposure 1) or, with --peak max, the
 *            reference's largest channel value over the compared pixels.
 * Output: one key=value line (default), e.g.
 *   relmse=0.00123 rmse=0.0102 psnr=39.8 pixels=786432 peak=1
 * or, with --csv, the values alone in that order (relmse,rmse,psnr,pixels,peak);
 * --header prints the CSV header line first. PSNR is "inf" when the images are
 * equal. Exit 0; 2 on usage errors, unreadable files or size mismatch.
 * Reads RGB(A) EXR, half or float, through renderer/image.c (libOpenEXRCore). */
#include "image.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static void usage(void)
{
    fprintf(stderr, "usage: imgmetrics TEST.exr REF.exr [--mask MASK.exr] [--peak 1|max] [--csv] [--header]\n");
}

static void fmt(char *buf, size_t n, double v)
{
    if (isinf(v))
        snprintf(buf, n, "inf");
    else
        snprintf(buf, n, "%.6g", v);
}

int main(int argc, char **argv)
{
    const char *files[2] = {NULL, NULL}, *mask_path = NULL;
    int nfiles = 0, csv = 0, header = 0, peak_max = 0;
    for (int i = 1; i < argc; i++) {
        if (!strcmp(argv[i], "--mask") && i + 1 < argc)
            mask_path = argv[++i];
        else if (!strcmp(argv[i], "--peak") && i + 1 < argc) {
            i++;
            if (!strcmp(argv[i], "max"))
                peak_max = 1;
            else if (!strcmp(argv[i], "1"))
                peak_max = 0;
            else {
                usage();
                return 2;
            }
        } else if (!strcmp(argv[i], "--csv"))
            csv = 1;
        else if (!strcmp(argv[i], "--header"))
            header = csv = 1;
        else if (!strcmp(argv[i], "-h") || !strcmp(argv[i], "--help")) {
            usage();
            return 0;
        } else if (argv[i][0] == '-' && argv[i][1] == '-') {
            usage();
            return 2;
        } else if (nfiles < 2)
            files[nfiles++] = argv[i];
        else {
            usage();
            return 2;
        }
    }
    if (nfiles != 2) {
        usage();
        return 2;
    }
    char err[512];
    image a, b, m = {0, 0, NULL};
    if (image_read_exr(&a, files[0], err, sizeof err)) {
        fprintf(stderr, "imgmetrics: %s\n", err);
        return 2;
    }
    if (image_read_exr(&b, files[1], err, sizeof err)) {
        fprintf(stderr, "imgmetrics: %s\n", err);
        image_free(&a);
        return 2;
    }
    int rc = 2;
    if (mask_path && image_read_exr(&m, mask_path, err, sizeof err)) {
        fprintf(stderr, "imgmetrics: %s\n", err);
        goto out;
    }
    if (a.width != b.width || a.height != b.height || (mask_path && (m.width != a.width || m.height != a.height))) {
        fprintf(stderr, "imgmetrics: size mismatch: %s %ux%u, %s %ux%u%s\n", files[0], a.width, a.height, files[1],
                b.width, b.height, mask_path ? " (or mask)" : "");
        goto out;
    }
    size_t np = (size_t)a.width * a.height, used = 0;
    double sum_rel = 0, sum_sq = 0, rmax = 0;
    for (size_t p = 0; p < np; p++) {
        if (mask_path && m.rgb[3 * p] == 0 && m.rgb[3 * p + 1] == 0 && m.rgb[3 * p + 2] == 0)
            continue;
        used++;
        for (int c = 0; c < 3; c++) {
            double x = a.rgb[3 * p + c], r = b.rgb[3 * p + c], d = x - r;
            sum_rel += d * d / (r * r + 0.01);
            sum_sq += d * d;
            if (r > rmax)
                rmax = r;
        }
    }
    if (used == 0) {
        fprintf(stderr, "imgmetrics: the mask selects no pixel\n");
        goto out;
    }
    double n = 3.0 * (double)used, mse = sum_sq / n, peak = peak_max ? rmax : 1.0;
    double psnr = mse > 0 ? 10.0 * log10(peak * peak / mse) : INFINITY;
    char s_rel[32], s_rmse[32], s_psnr[32], s_peak[32];
    fmt(s_rel, sizeof s_rel, sum_rel / n);
    fmt(s_rmse, sizeof s_rmse, sqrt(mse));
    fmt(s_psnr, sizeof s_psnr, psnr);
    fmt(s_peak, sizeof s_peak, peak);
    if (header)
        printf("relmse,rmse,psnr,pixels,peak\n");
    if (csv)
        printf("%s,%s,%s,%zu,%s\n", s_rel, s_rmse, s_psnr, used, s_peak);
    else
        printf("relmse=%s rmse=%s psnr=%s pixels=%zu peak=%s\n", s_rel, s_rmse, s_psnr, used, s_peak);
    rc = 0;
out:
    image_free(&a);
    image_free(&b);
    image_free(&m);
    return rc;
}
