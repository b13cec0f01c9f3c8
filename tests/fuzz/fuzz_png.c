/* fuzz_png.c - libFuzzer target for pngfile_read (include/envtex/io/pngfile.h); see tests/fuzz/README.md. */
#include "envtex/io/pngfile.h"
#include "fuzz_image.h"

FUZZ_IMAGE_TARGET(pngfile_read)
