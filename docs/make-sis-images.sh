#!/usr/bin/env bash
# docs/make-sis-images.sh HDRI_DIR: the strata pictures of docs/sis.md (`envtex strata`: each
# stratum outlined in magenta, each sample a green mark), 512 x 256 each:
#   docs/images/sis/sun_N.png        the sun map (envtex gen-env sun --width 512), N = 16, 64, 256
#   docs/images/sis/courtyard_N.png  the shipped courtyard (data/envmaps/courtyard.exr), N = 64, 256
#   docs/images/sis/sunrise_N.png    HDRI_DIR/sunrise.exr (../shared/hdri, not shipped: only these
#                                    PNGs made from it are) halved to 512 x 256, N = 64, 256
# and docs/images/sis/layers.txt, the `strata:` line of each (thresholds, regions, samples), and
#   docs/images/sis/envlight_8_sis.png  data/scenes/envlight_8_sis.test as it says (seed 1).
# Deterministic; seconds.
set -eu
export LC_ALL=C
cd "$(dirname "$0")/.."
hdri=${1:?usage: docs/make-sis-images.sh HDRI_DIR (holding sunrise.exr: ../shared/hdri)}
BUILD=${BUILD:-build}
ENVTEX=$(realpath "${ENVTEX:-$BUILD/envtex}")
out=docs/images/sis
tmp="$BUILD/sis-images"
mkdir -p "$out" "$tmp"
"$ENVTEX" gen-env sun "$tmp/sun.exr" --width 512 >/dev/null
"$ENVTEX" convert "$hdri/sunrise.exr" "$tmp/sunrise.exr" --to latlong --width 512 >/dev/null
: > "$out/layers.txt"
strata() { # NAME MAP N EXPOSURE
    echo "$1 N=$3: $("$ENVTEX" strata "$2" "$out/$1_$3.png" -n "$3" --exposure "$4")" >> "$out/layers.txt"
    echo "$out/$1_$3.png"
}
for n in 16 64 256; do strata sun "$tmp/sun.exr" "$n" -3; done
for n in 64 256; do strata courtyard data/envmaps/courtyard.exr "$n" 0; done
for n in 64 256; do strata sunrise "$tmp/sunrise.exr" "$n" -1; done
"$ENVTEX" render data/scenes/envlight_8_sis.test -o "$out/envlight_8_sis.png" --quiet --seed 1 >/dev/null
echo "$out/envlight_8_sis.png"
