/* make_textures.c - the small PNG textures of data/textures/ and tests/golden/tex/, made
 * procedurally so that their provenance is this file (data/README.md):
 *     build/tools/make_textures data/textures
 * writes, into the folder given:
 *   checker.png   64 x 64, 8 x 8 black and white squares of 8 texels: the lecture's receding
 *                 checkerboard (hard edges alias as badly as possible)
 *   uvgrid.png    64 x 64, s as red, t as green, a dark line every 8 texels and a white dot
 *                 at (s, t) = (0, 1) ... a map whose orientation and seams are visible
 *   bumps.png     64 x 64 grey heights: 4 x 4 round bumps, h = cos^2 of the distance to the
 *                 bump centre (smooth, so the bump map's derivatives are well defined)
 *   lightmap.png  32 x 32, warm blobs on black: a light map baked as a texture
 *   roughness.png 32 x 32 grey: four horizontal bands, from 0.05 (shiny, top: t near 1) to 0.6
 *                 (rough, bottom), for roughnessmap (a sphere shows them as latitude bands)
 * Values are written as 8-bit sRGB (pngfile.h decodes them to linear when read). */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "envtex/io/pngfile.h"
#include "envtex/io/tonemap.h"

typedef void (*texel_fn)(int x, int y, int w, int h, double rgb_linear[3]);

static void checker(int x, int y, int w, int h, double c[3])
{
    (void)w;
    (void)h;
    double v = ((x / 8) + (y / 8)) % 2 ? 0.9 : 0.05;
    c[0] = c[1] = c[2] = v;
}

static void uvgrid(int x, int y, int w, int h, double c[3])
{
    double s = (x + 0.5) / w, t = 1.0 - (y + 0.5) / h; /* t up, row 0 at the top */
    c[0] = 0.1 + 0.8 * s;
    c[1] = 0.1 + 0.8 * t;
    c[2] = 0.25;
    if (x % 8 == 0 || y % 8 == 0) c[0] = c[1] = c[2] = 0.02;
    if (x < 4 && y < 4) c[0] = c[1] = c[2] = 1.0; /* marks (s, t) = (0, 1): top left */
}

static void bumps(int x, int y, int w, int h, double c[3])
{
    double cell = w / 4.0;
    double u = fmod(x + 0.5, cell) / cell - 0.5, v = fmod(y + 0.5, cell * h / w) / cell - 0.5;
    double r = sqrt(u * u + v * v) * 2; /* 0 at the centre, 1 at the cell's inscribed circle */
    double hgt = r < 1 ? cos(r * M_PI / 2) : 0;
    c[0] = c[1] = c[2] = hgt * hgt;
}

static void lightmap(int x, int y, int w, int h, double c[3])
{
    double s = (x + 0.5) / w, t = (y + 0.5) / h, sum = 0;
    const double blobs[3][2] = {{0.3, 0.3}, {0.7, 0.4}, {0.45, 0.75}};
    for (int k = 0; k < 3; k++) {
        double dx = s - blobs[k][0], dy = t - blobs[k][1];
        sum += exp(-(dx * dx + dy * dy) / (2 * 0.08 * 0.08));
    }
    if (sum > 1) sum = 1;
    c[0] = sum;
    c[1] = 0.6 * sum;
    c[2] = 0.25 * sum;
}

static void roughness(int x, int y, int w, int h, double c[3])
{
    (void)x;
    (void)w;
    int stripe = y * 4 / h; /* four bands down the image: row 0 is t = 1 */
    const double a[4] = {0.05, 0.15, 0.3, 0.6};
    c[0] = c[1] = c[2] = a[stripe];
}

static int write(const char *dir, const char *name, int w, int h, texel_fn f)
{
    char path[1024];
    snprintf(path, sizeof path, "%s/%s", dir, name);
    unsigned char *px = malloc((size_t)w * h * 3);
    if (!px) return -1;
    for (int y = 0; y < h; y++)
        for (int x = 0; x < w; x++) {
            double c[3];
            f(x, y, w, h, c);
            for (int k = 0; k < 3; k++) {
                double e = tonemap_srgb_encode(c[k] < 0 ? 0 : c[k] > 1 ? 1 : c[k]);
                px[3 * ((size_t)y * w + x) + k] = (unsigned char)lround(e * 255);
            }
        }
    error err = {0};
    int st = pngfile_write_rgb8(path, w, h, px, &err);
    free(px);
    if (st)
        error_print(&err, stderr);
    else
        printf("%s\n", path);
    return st;
}

int main(int argc, char **argv)
{
    if (argc != 2) {
        fprintf(stderr, "usage: make_textures FOLDER\n");
        return 1;
    }
    const char *d = argv[1];
    int bad = write(d, "checker.png", 64, 64, checker) | write(d, "uvgrid.png", 64, 64, uvgrid) |
              write(d, "bumps.png", 64, 64, bumps) | write(d, "lightmap.png", 32, 32, lightmap) |
              write(d, "roughness.png", 32, 32, roughness);
    return bad ? 1 : 0;
}
