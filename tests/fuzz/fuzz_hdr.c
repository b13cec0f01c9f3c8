/* fuzz_hdr.c - libFuzzer target for rgbe_read (include/envtex/io/rgbe.h); see tests/fuzz/README.md. */
#include "envtex/io/rgbe.h"
#include "fuzz_image.h"

FUZZ_IMAGE_TARGET(rgbe_read)
