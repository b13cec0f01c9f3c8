/* fuzz_scene.c - libFuzzer target for the scene parser (scene_load_string, images not loaded;
 * see tests/fuzz/README.md).  The bytes are the text of a scene file. */
#include <stdlib.h>
#include <string.h>

#include "envtex/scene/scene.h"
#include "envtex/scene/scene_load.h"
#include "fuzz.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    char *text = malloc(size + 1);
    if (!text) return 0;
    memcpy(text, data, size);
    text[size] = '\0';
    scene_load_opts o = scene_load_defaults();
    o.load_images = 0;
    o.max_prims = 100000; /* the parser's own limit, lowered so a long input cannot eat memory */
    budget mem;
    budget_init(&mem, FUZZ_MEMORY_BUDGET);
    o.mem = &mem;
    scene sc;
    error err = {0};
    int rc = scene_load_string(text, NULL, &o, &sc, &err);
    if (rc == 0) {
        fuzz_check(sc.width >= 1 && sc.height >= 1 && sc.width <= SCENE_MAX_SIZE &&
                       sc.height <= SCENE_MAX_SIZE &&
                       (long)sc.width * sc.height <= SCENE_MAX_PIXELS,
                   "a loaded scene has a size within the limits");
        fuzz_check(sc.spp >= 1 && sc.spp <= SCENE_MAX_SPP, "spp within the limits");
        fuzz_check(sc.maxdepth >= -1 && sc.maxdepth <= SCENE_MAX_DEPTH,
                   "maxdepth within the limits");
        fuzz_check(sc.n_spheres + sc.n_triangles <= 2 * o.max_prims, "primitives within the limit");
        for (long i = 0; i < sc.n_triangles; i++)
            fuzz_check(sc.triangles[i].material >= 0 && sc.triangles[i].material < sc.n_materials,
                       "triangle material index in range");
        for (long i = 0; i < sc.n_spheres; i++)
            fuzz_check(sc.spheres[i].material >= 0 && sc.spheres[i].material < sc.n_materials,
                       "sphere material index in range");
        scene_free(&sc);
    } else {
        fuzz_check(rc == -1 && err.msg[0] != '\0', "a failed load returns -1 and says why");
    }
    free(text);
    return 0;
}
