/* fuzz_exr.c - libFuzzer target for exrfile_read (include/envtex/exrfile.h); see tests/fuzz/README.md. */
#include "envtex/exrfile.h"
#include "fuzz_image.h"

FUZZ_IMAGE_TARGET(exrfile_read)
