/* gen_mesh - write a generated triangle mesh as a Wavefront OBJ, for the BVH benchmarks.
 *
 *     gen_mesh dragon OUT.obj          a stand-in for the course's dragon (about 100k triangles)
 *     gen_mesh sphere N OUT.obj        a unit UV sphere of about N triangles
 *     gen_mesh soup N OUT.obj          N random triangles in [-1, 1]^3 (a triangle soup)
 *
 * The dragon stand-in is a UV sphere of 158 x 316 quads (99,856 triangles) whose radius is
 * displaced by a sum of sines: ridges, folds and concavities, so that rays graze, miss and
 * re-enter as they do on a scanned model.  Deterministic: the same file every run.
 */
#include "envtex/core/vec.h" /* M_PI */

#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* the displaced radius at polar angle theta, azimuth phi */
static double dragon_radius(double theta, double phi)
{
    return 1 + 0.18 * sin(5 * phi) * sin(3 * theta) + 0.07 * sin(17 * phi + 4 * theta) +
           0.03 * sin(41 * theta) * cos(29 * phi);
}

static double unit_radius(double theta, double phi)
{
    (void)theta, (void)phi;
    return 1;
}

/* rows x cols quads of a sphere of radius rad(theta, phi), two triangles each (the poles' rows
 * are fans of slivers, as any UV sphere's) */
static void write_sphere(FILE *f, int rows, int cols, double (*rad)(double, double))
{
    for (int i = 0; i <= rows; i++) {
        double theta = M_PI * i / rows;
        for (int j = 0; j < cols; j++) {
            double phi = 2 * M_PI * j / cols, r = rad(theta, phi);
            fprintf(f, "v %.7f %.7f %.7f\n", r * sin(theta) * cos(phi), r * cos(theta),
                    r * sin(theta) * sin(phi));
        }
    }
    for (int i = 0; i < rows; i++)
        for (int j = 0; j < cols; j++) {
            long a = 1L + (long)i * cols + j, b = 1L + (long)i * cols + (j + 1) % cols;
            long c = a + cols, d = b + cols;
            fprintf(f, "f %ld %ld %ld\nf %ld %ld %ld\n", a, b, d, a, d, c);
        }
}

/* a 64-bit LCG's top 53 bits as a double in [0, 1) */
static double next_uniform(uint64_t *s)
{
    *s = *s * 6364136223846793005ULL + 1442695040888963407ULL;
    return (double)(*s >> 11) * 0x1p-53;
}

static void write_soup(FILE *f, long n)
{
    uint64_t s = 168;
    for (long i = 0; i < n; i++) {
        double c[3], size = 0.02 + 0.08 * next_uniform(&s);
        for (int k = 0; k < 3; k++) c[k] = 2 * next_uniform(&s) - 1;
        for (int v = 0; v < 3; v++)
            fprintf(f, "v %.7f %.7f %.7f\n", c[0] + size * (next_uniform(&s) - 0.5),
                    c[1] + size * (next_uniform(&s) - 0.5), c[2] + size * (next_uniform(&s) - 0.5));
        fprintf(f, "f %ld %ld %ld\n", 3 * i + 1, 3 * i + 2, 3 * i + 3);
    }
}

int main(int argc, char **argv)
{
    const char *kind = argc > 1 ? argv[1] : "";
    int is_dragon = strcmp(kind, "dragon") == 0;
    if (!(is_dragon ? argc == 3
                    : argc == 4 && (!strcmp(kind, "sphere") || !strcmp(kind, "soup")))) {
        fprintf(stderr, "usage: gen_mesh dragon OUT.obj | gen_mesh sphere|soup N OUT.obj\n");
        return 2;
    }
    long n = is_dragon ? 0 : atol(argv[2]);
    if (!is_dragon && n < 2) {
        fprintf(stderr, "gen_mesh: N must be at least 2, got '%s'\n", argv[2]);
        return 2;
    }
    const char *path = argv[argc - 1];
    FILE *f = fopen(path, "w");
    if (!f) {
        fprintf(stderr, "gen_mesh: cannot write %s\n", path);
        return 1;
    }
    if (is_dragon)
        write_sphere(f, 158, 316, dragon_radius);
    else if (!strcmp(kind, "sphere")) {
        int rows = (int)fmax(1, floor(sqrt(n / 4.0))); /* 2 rows x cols = n, cols = 2 rows */
        write_sphere(f, rows, 2 * rows, unit_radius);
    } else
        write_soup(f, n);
    if (fclose(f)) {
        fprintf(stderr, "gen_mesh: error writing %s\n", path);
        return 1;
    }
    return 0;
}
