/* fuzz_obj.c - libFuzzer target for the Wavefront OBJ reader (obj_load_string; see
 * tests/fuzz/README.md).  The bytes are the text of an OBJ file. */
#include <stdlib.h>
#include <string.h>

#include "envtex/io/obj.h"
#include "fuzz.h"

/* Each record kind capped lower than OBJ_MAX_ELEMS so a long input cannot eat memory. */
#define FUZZ_OBJ_MAX_ELEMS 100000L

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    char *text = malloc(size + 1);
    if (!text) return 0;
    memcpy(text, data, size);
    text[size] = '\0';
    obj_mesh m;
    error err = {0};
    budget mem;
    budget_init(&mem, FUZZ_MEMORY_BUDGET);
    int rc = obj_load_string(text, "fuzz.obj", FUZZ_OBJ_MAX_ELEMS, &m, &mem, &err);
    if (rc == 0) {
        fuzz_check(m.n_v <= FUZZ_OBJ_MAX_ELEMS && m.n_vt <= FUZZ_OBJ_MAX_ELEMS &&
                       m.n_vn <= FUZZ_OBJ_MAX_ELEMS && m.n_tris <= FUZZ_OBJ_MAX_ELEMS,
                   "record counts within the limit");
        for (long i = 0; i < m.n_tris; i++)
            for (int k = 0; k < 3; k++) {
                const obj_triangle *t = &m.tris[i];
                fuzz_check(t->v[k] >= 0 && t->v[k] < m.n_v, "position index in range");
                fuzz_check(t->vt[k] >= -1 && t->vt[k] < m.n_vt, "uv index in range or -1");
                fuzz_check(t->vn[k] >= -1 && t->vn[k] < m.n_vn, "normal index in range or -1");
            }
        fuzz_check(mem.used == m.bytes, "the mesh's arrays are what is charged");
        obj_free(&m);
    } else {
        fuzz_check(rc == -1 && err.msg[0] != '\0', "a failed load returns -1 and says why");
        fuzz_check(mem.used == 0, "a failed load leaves nothing charged");
    }
    free(text);
    return 0;
}
