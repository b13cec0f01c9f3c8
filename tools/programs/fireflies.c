/* fireflies.c - how many pixels of a region stand out of it as fireflies: the share of its pixels
 * more than LEVELS 8-bit levels above the region's median.  The levels are what the course's PNG
 * holds: the linear render encoded as a scene's `gamma G`, c^(1/G), as envtex's PNG writer does
 * (G 0: the sRGB curve), a pixel's level the mean of its three channels.  The region is the
 * union of one or more rectangles, columns [X0, X1) and rows [Y0, Y1) each (they must not
 * overlap).
 *
 *     build/tools/fireflies render.exr 2.2 60  0 0 320 42  0 46 320 96
 *     -> pixels 28160 median 97 above 157: 211 (0.749%)
 *
 * tests/course/mis-fireflies measures the hw4 mis.test stand-in's back wall and floor with it. */
#include <stdio.h>
#include <stdlib.h>

#include "envtex/io/imageio.h"
#include "envtex/io/tonemap.h"

static int cmp_int(const void *a, const void *b) { return *(const int *)a - *(const int *)b; }

int main(int argc, char **argv)
{
    if (argc < 8 || (argc - 4) % 4 != 0) {
        fprintf(stderr, "usage: fireflies IMAGE GAMMA LEVELS X0 Y0 X1 Y1 [X0 Y0 X1 Y1 ...]\n");
        return 1;
    }
    error err = {0};
    image im = {0};
    if (imageio_read(argv[1], &im, NULL, &err)) {
        error_print(&err, stderr);
        return 1;
    }
    tonemap_params tm = tonemap_defaults();
    tm.gamma = atof(argv[2]);
    int levels = atoi(argv[3]), n_rect = (argc - 4) / 4, status = 1;
    long n = 0, k = 0, above = 0;
    int *lv = NULL;
    for (int i = 0; i < n_rect; i++) {
        int x0 = atoi(argv[4 + 4 * i]), y0 = atoi(argv[5 + 4 * i]);
        int x1 = atoi(argv[6 + 4 * i]), y1 = atoi(argv[7 + 4 * i]);
        if (x0 < 0 || y0 < 0 || x1 > im.w || y1 > im.h || x0 >= x1 || y0 >= y1) {
            fprintf(
                stderr,
                "fireflies: the rectangle [%d, %d) x [%d, %d) is not inside the %d x %d image\n",
                x0, x1, y0, y1, im.w, im.h);
            goto cleanup;
        }
        n += (long)(x1 - x0) * (y1 - y0);
    }
    if (!(lv = malloc((size_t)n * sizeof *lv))) {
        fprintf(stderr, "fireflies: out of memory\n");
        goto cleanup;
    }
    for (int i = 0; i < n_rect; i++)
        for (int y = atoi(argv[5 + 4 * i]); y < atoi(argv[7 + 4 * i]); y++)
            for (int x = atoi(argv[4 + 4 * i]); x < atoi(argv[6 + 4 * i]); x++) {
                uint8_t b[3];
                tonemap_pixel(&tm, image_get(&im, x, y), b);
                lv[k++] = (b[0] + b[1] + b[2] + 1) / 3; /* the mean level, rounded */
            }
    qsort(lv, (size_t)n, sizeof *lv, cmp_int); /* the order of the pixels does not matter */
    int median = lv[n / 2];
    for (long i = 0; i < n; i++) above += lv[i] > median + levels;
    printf("pixels %ld median %d above %d: %ld (%.3f%%)\n", n, median, median + levels, above,
           100.0 * above / n);
    status = 0;
cleanup:
    free(lv);
    image_free(&im);
    return status;
}
