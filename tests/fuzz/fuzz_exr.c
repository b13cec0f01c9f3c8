/* fuzz_exr.c - libFuzzer target for exrfile_read (include/envtex/io/exrfile.h); see tests/fuzz/README.md. */
#include "envtex/io/exrfile.h"
#include "fuzz_image.h"

FUZZ_IMAGE_TARGET(exrfile_read)
