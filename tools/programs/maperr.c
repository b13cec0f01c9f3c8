/* maperr.c - the error of a lat-long map A against a reference B, relative to B's peak, as
 * docs/illumination-maps.md states Ramamoorthi & Hanrahan's claim: the mean over the sphere
 * (each texel weighted by its solid angle) and the max of |Y(A) - Y(B)| / max Y(B), Y the
 * luminance.  With a third argument it also writes that error as a grey map (the docs' error
 * pictures, tone mapped with a fixed exposure by docs/make-illumination-images.sh):
 *     build/tools/maperr sh9.exr exact.exr [err.exr]   ->  mean=0.0123 max=0.0456 peak=3.21 */
#include <math.h>
#include <stdio.h>

#include "envtex/io/imageio.h"
#include "envtex/envmaps/latlong.h"

int main(int argc, char **argv)
{
    error err = {0};
    image a = {0}, b = {0}, e = {0};
    int st = 1;
    if (argc != 3 && argc != 4) {
        fprintf(stderr, "usage: maperr A B [ERR.exr]\n");
        return 1;
    }
    if (imageio_read(argv[1], &a, NULL, &err) || imageio_read(argv[2], &b, NULL, &err)) goto done;
    if (a.w != b.w || a.h != b.h || b.w != 2 * b.h) {
        error_set(&err, argv[1], 0, "A (%d x %d) and B (%d x %d) must be lat-long maps of one size",
                  a.w, a.h, b.w, b.h);
        goto done;
    }
    double peak = 0, sum = 0, max = 0;
    for (int r = 0; r < b.h; r++)
        for (int c = 0; c < b.w; c++) peak = fmax(peak, rgb_luminance(image_get(&b, c, r)));
    if (!(peak > 0)) {
        error_set(&err, argv[2], 0, "the reference is black");
        goto done;
    }
    if (argc == 4 && image_alloc(&e, a.w, a.h, &err)) goto done;
    for (int r = 0; r < b.h; r++) {
        double om = latlong_texel_solid_angle(r, b.w, b.h);
        for (int c = 0; c < b.w; c++) {
            double d =
                fabs(rgb_luminance(image_get(&a, c, r)) - rgb_luminance(image_get(&b, c, r))) /
                peak;
            sum += d * om; /* the mean over the sphere: weighted by solid angle */
            max = fmax(max, d);
            if (e.px) image_set(&e, c, r, rgb_gray(d));
        }
    }
    if (e.px && imageio_write(argv[3], &e, NULL, &err)) goto done;
    printf("mean=%.4g max=%.4g peak=%.6g\n", sum / (4 * M_PI), max, peak);
    st = 0;
done:
    if (st) error_print(&err, stderr);
    image_free(&a);
    image_free(&b);
    image_free(&e);
    return st;
}
