/* fuzz_image.h - the body shared by the image-reader fuzz targets: write the input to an
 * in-memory file, read it with READER under a memory budget of FUZZ_MEMORY_BUDGET, check the
 * reader's contract (and that only the image stays charged), free.
 *
 *     #include "fuzz_image.h"
 *     FUZZ_IMAGE_TARGET(pfm_read)
 */
#ifndef ENVTEX_FUZZ_IMAGE_H
#define ENVTEX_FUZZ_IMAGE_H

#include "envtex/core/budget.h"
#include "envtex/core/image.h"
#include "fuzz.h"

/* On success: a non-empty image within the limits, every pixel readable.  On failure: -1, an
 * empty image and a message. */
static inline void fuzz_image_check(int rc, const image *im, const error *err)
{
    if (rc == 0) {
        fuzz_check(im->px && im->w >= 1 && im->h >= 1 && im->w <= IMAGE_MAX_SIDE &&
                       im->h <= IMAGE_MAX_SIDE && (long)im->w * im->h <= IMAGE_MAX_PIXELS,
                   "a successful read returns a non-empty image within the limits");
        volatile float sink = 0.0f; /* touch every sample: valgrind reports uninitialised ones */
        for (size_t i = 0; i < (size_t)im->w * (size_t)im->h * 3; i++)
            if (im->px[i] != im->px[i]) sink += 1.0f;
        (void)sink;
    } else {
        fuzz_check(rc == -1, "a failed read returns -1");
        fuzz_check(!im->px && im->w == 0 && im->h == 0, "a failed read leaves the image empty");
        fuzz_check(err->msg[0] != '\0', "a failed read says why");
    }
}

#define FUZZ_IMAGE_TARGET(READER)                                                                  \
    int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)                                   \
    {                                                                                              \
        const char *path = fuzz_tmpfile(data, size);                                               \
        if (!path) return 0;                                                                       \
        image im = {0};                                                                            \
        error err = {0};                                                                           \
        budget mem;                                                                                \
        budget_init(&mem, FUZZ_MEMORY_BUDGET);                                                     \
        int rc = READER(path, &im, &mem, &err);                                                    \
        fuzz_image_check(rc, &im, &err);                                                           \
        fuzz_check(rc || mem.used == (double)im.w * im.h * IMAGE_TEXEL_BYTES,                      \
                   "a read image stays charged, its scratch released");                            \
        image_free(&im);                                                                           \
        return 0;                                                                                  \
    }

#endif
