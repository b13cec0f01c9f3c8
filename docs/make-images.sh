#!/usr/bin/env bash
# make docs-images: render the scenes of data/scenes/ into the small PNGs the docs show
# (docs/images/).  Deterministic (fixed seed); the environment-lighting strategies are
# rendered at EQUAL TIME: each is timed at a few spp first, then given the spp that fits
# DOCS_SECONDS (default 2 s) on this machine.
set -eu
cd "$(dirname "$0")/.."
BUILD=${BUILD:-build}
ENVTEX=${ENVTEX:-$BUILD/envtex}
SECONDS_PER=${DOCS_SECONDS:-2}
out=docs/images
mkdir -p "$out"

done_list=" "
render() { # scene [options]: docs/images/<scene>.png
    local s=$1; shift
    "$ENVTEX" render "data/scenes/$s.test" -o "$out/$s.png" --quiet --seed 1 "$@" >/dev/null
    done_list="$done_list$s "
    echo "docs/images/$s.png"
}

for s in demo mirror_sphere glass_sphere mirrors_envmap mirrors_black hw1_spheres hw1_trinormal; do
    render "$s"
done

# equal time: spp = DOCS_SECONDS / (seconds per spp measured at 8 spp)
for s in envlight_1_hit envlight_2_uniform envlight_3_cdf envlight_4_mis envlight_5_mediancut; do
    line=$("$ENVTEX" render "data/scenes/$s.test" -o "$BUILD/calibrate.exr" --spp 8 --quiet)
    t=$(sed -n 's/.*time_s=\([^ ]*\).*/\1/p' <<<"$line")
    spp=$(awk -v t="$t" -v T="$SECONDS_PER" 'BEGIN { s = int(T / (t / 8) + 0.5); print (s < 1 ? 1 : s) }')
    render "$s" --spp "$spp"
    echo "  ($s: $spp spp in about ${SECONDS_PER} s)"
    echo "$s $spp" >> "$BUILD/docs-spp.txt.new"
done
mv "$BUILD/docs-spp.txt.new" docs/images/equal-time-spp.txt

# every other scene (added by later lecture steps) at its own settings
for f in data/scenes/*.test; do
    s=$(basename "$f" .test)
    case $done_list in *" $s "*) continue ;; esac
    render "$s"
done

# the courtyard in each representation (docs/envmap-representations.md)
while read -r kind width; do
    case $kind in ''|'#'*) continue ;; esac
    "$ENVTEX" convert data/envmaps/courtyard.exr "$BUILD/representation.exr" --to "$kind" --width "$width" >/dev/null
    "$ENVTEX" tonemap "$BUILD/representation.exr" "$out/representations/$kind.png"
    echo "docs/images/representations/$kind.png"
done < docs/images/representations/widths.txt
