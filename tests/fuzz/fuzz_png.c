/* fuzz_png.c - libFuzzer target for pngfile_read (include/envtex/pngfile.h); see tests/fuzz/README.md. */
#include "envtex/pngfile.h"
#include "fuzz_image.h"

FUZZ_IMAGE_TARGET(pngfile_read)
