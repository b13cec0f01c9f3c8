/* exrattrs.c - the envtex attributes of an OpenEXR header (see include/envtex/io/exrattrs.h). */
#include "envtex/io/exrattrs.h"

#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* Set the envtex attributes of `at` that are known on part 0 (before the header is written). */
exr_result_t exrattrs_set(exr_context_t ctx, int part, const exrfile_attrs *at)
{
    exr_result_t r = EXR_ERR_SUCCESS;
    char text[EXRFILE_TEXT_MAX];
    if (!at) return r;
    if (at->spp > 0) r = exr_attr_set_int(ctx, part, "envtex:spp", at->spp);
    if (r == EXR_ERR_SUCCESS && at->has_seed) {
        snprintf(text, sizeof text, "%llu", (unsigned long long)at->seed);
        r = exr_attr_set_string(ctx, part, "envtex:seed", text);
    }
    if (r == EXR_ERR_SUCCESS && at->integrator[0]) {
        snprintf(text, sizeof text, "%s", at->integrator);
        r = exr_attr_set_string(ctx, part, "envtex:integrator", text);
    }
    if (r == EXR_ERR_SUCCESS && at->scene[0]) {
        snprintf(text, sizeof text, "%s", at->scene);
        r = exr_attr_set_string(ctx, part, "envtex:scene", text);
    }
    return r;
}

/* A string attribute `name` into out (cut to `size` - 1 bytes): 0 present, 1 absent, -1 error. */
static int get_text(exr_context_t ctx, const char *name, char *out, size_t size)
{
    int32_t len = 0;
    const char *str = NULL;
    exr_result_t r = exr_attr_get_string(ctx, 0, name, &len, &str);
    if (r == EXR_ERR_NO_ATTR_BY_NAME) return 1;
    if (r != EXR_ERR_SUCCESS || !str || len < 0) return -1;
    size_t n = (size_t)len < size - 1 ? (size_t)len : size - 1;
    memcpy(out, str, n);
    out[n] = '\0';
    return 0;
}

/* The attributes themselves, from a context open on the file (exrattrs.h). */
int exrattrs_get(exr_context_t ctx, exrfile_attrs *at, const char *path, error *err)
{
    int32_t spp = 0;
    exr_result_t r = exr_attr_get_int(ctx, 0, "envtex:spp", &spp);
    if (r == EXR_ERR_SUCCESS && spp < 1)
        return error_set(err, path, 0, "envtex:spp is %d, not a sample count >= 1", (int)spp);
    if (r != EXR_ERR_SUCCESS && r != EXR_ERR_NO_ATTR_BY_NAME)
        return error_set(err, path, 0, "envtex:spp is not an int attribute");
    at->spp = r == EXR_ERR_SUCCESS ? (int)spp : 0;
    char seed[32], *end = NULL;
    int got = get_text(ctx, "envtex:seed", seed, sizeof seed);
    if (got == 0) {
        errno = 0;
        unsigned long long v = strtoull(seed, &end, 10);
        if (errno || end == seed || *end || seed[0] == '-')
            return error_set(err, path, 0, "envtex:seed '%s' is not a whole number", seed);
        at->seed = (uint64_t)v;
        at->has_seed = 1;
    }
    if (got < 0 || get_text(ctx, "envtex:integrator", at->integrator, sizeof at->integrator) < 0 ||
        get_text(ctx, "envtex:scene", at->scene, sizeof at->scene) < 0)
        return error_set(err, path, 0, "an envtex attribute is not a string");
    return 0;
}
