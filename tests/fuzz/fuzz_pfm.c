/* fuzz_pfm.c - libFuzzer target for pfm_read (include/envtex/io/pfm.h); see tests/fuzz/README.md. */
#include "envtex/io/pfm.h"
#include "fuzz_image.h"

FUZZ_IMAGE_TARGET(pfm_read)
