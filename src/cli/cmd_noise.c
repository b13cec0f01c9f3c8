/* cmd_noise.c - `envtex noise X Y Z`: Perlin's improved noise at a point (perlin.h). */
#include <stdio.h>

#include "envtex/cli/cli.h"
#include "envtex/textures/perlin.h"

int cmd_noise(int argc, char **argv)
{
    double v[3];
    if (argc != 3) return cli_usage_error("%s", "noise needs three numbers X Y Z");
    for (int k = 0; k < 3; k++)
        if (cli_parse_double(argv[k], &v[k]))
            return cli_usage_error("noise needs finite numbers, got '%s'", argv[k]);
    printf("%.9g\n", perlin_noise(v[0], v[1], v[2]));
    return 0;
}
