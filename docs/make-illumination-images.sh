#!/usr/bin/env bash
# docs/make-illumination-images.sh HDRI_DIR: the pictures and the two tables of
# docs/illumination-maps.md.  HDRI_DIR holds the five real maps (courtyard, forest, studio,
# sunrise, sunset .exr; ../shared/hdri, not shipped: only small PNGs made from them are); the
# sun map is made here (envtex gen-env sun --width 1024) and the shipped courtyard (512 x 256)
# is data/envmaps/courtyard.exr.
#
#   docs/images/illumination/NAME.png             the map (256 x 128, tone mapped)
#   docs/images/illumination/NAME_irradiance.png  its exact E / pi map (256 x 128, same tone map)
#   docs/images/illumination/NAME_error.png       |E_sh9 - E_exact| / max E_exact, white = 5%
#   the table between the "sh9 table" markers     mean and max of that error (64 x 32 maps),
#                                                 the CPU time of each method
#   docs/images/illumination/spheres_MAP_KIND_*.png  a lone diffuse and a lone glossy sphere
#                                                 by prefiltered exact, sh9 (16 spp), the path
#                                                 tracer at 16 spp and the reference
#   the table between the "speed table" markers   prefiltered (exact, sh9) against the path
#                                                 tracer at several spp: CPU time, relMSE
#
# Deterministic but for the times.  Takes a few minutes (the references: REF_SPP, default 8192).
set -eu
export LC_ALL=C
cd "$(dirname "$0")/.."
hdri=${1:?usage: docs/make-illumination-images.sh HDRI_DIR (the five maps of ../shared/hdri)}
hdri=$(cd "$hdri" && pwd)
BUILD=${BUILD:-build}
ENVTEX=$(realpath "${ENVTEX:-$BUILD/envtex}")
MAPERR=$(realpath "$BUILD/tools/maperr")
REF_SPP=${REF_SPP:-8192}
out=docs/images/illumination
page=docs/illumination-maps.md
mkdir -p "$out"
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT

# cpu COMMAND...: run it, its stdout to $work/stdout; print its CPU time (user + system), seconds
cpu() {
    /usr/bin/time -f '%U %S' -o "$work/time" "$@" >"$work/stdout"
    awk '{ printf "%.2f", $1 + $2 }' "$work/time"
}

# replace the lines between <!-- NAME: begin --> and <!-- NAME: end --> of the page by FILE
splice() {
    awk -v name="$1" -v file="$2" '
        $0 == "<!-- " name ": begin -->" { print; while ((getline l < file) > 0) print l; skip = 1; next }
        $0 == "<!-- " name ": end -->" { skip = 0 }
        !skip { print }' "$page" > "$work/page" && cp "$work/page" "$page"
}

"$ENVTEX" gen-env sun "$work/sun.exr" --width 1024 >/dev/null
cat > "$work/maps" <<EOF
courtyard|$hdri/courtyard.exr
forest|$hdri/forest.exr
studio|$hdri/studio.exr
sunrise|$hdri/sunrise.exr
sunset|$hdri/sunset.exr
sun|$work/sun.exr
courtyard (512)|$PWD/data/envmaps/courtyard.exr
EOF

# ---- the maps, their irradiance, the SH9 error ----
{
    echo "| map | mean error | max error | R&H's claim: mean <= 1.5%, max < 5%? | peak E / pi | exact: CPU s | sh9: CPU s |"
    echo "|---|---|---|---|---|---|---|"
} > "$work/sh9-table"
while IFS='|' read -r name map; do
    [ -n "$name" ] || continue
    base=${name%% *}
    if [ "$name" = "$base" ]; then # the pictures: not for the shipped copy of the courtyard
        "$ENVTEX" convert "$map" "$work/small.exr" --to latlong --width 256 >/dev/null
        "$ENVTEX" tonemap "$work/small.exr" "$out/$base.png"
        "$ENVTEX" prefilter "$map" "$work/e256.exr" --irradiance --width 256 >/dev/null
        "$ENVTEX" tonemap "$work/e256.exr" "$out/${base}_irradiance.png"
        "$ENVTEX" prefilter "$map" "$work/s256.exr" --irradiance --method sh9 --width 256 >/dev/null
        "$MAPERR" "$work/s256.exr" "$work/e256.exr" "$work/err.exr" >/dev/null
        # white = 5% of the peak: linear (gamma 1), exposure log2(20)
        "$ENVTEX" tonemap "$work/err.exr" "$out/${base}_error.png" --gamma 1 --exposure 4.321928
        echo "$out/$base.png, ${base}_irradiance.png, ${base}_error.png"
    fi
    te=$(cpu "$ENVTEX" prefilter "$map" "$work/exact.exr" --irradiance)
    ts=$(cpu "$ENVTEX" prefilter "$map" "$work/sh9.exr" --irradiance --method sh9)
    "$MAPERR" "$work/sh9.exr" "$work/exact.exr" > "$work/err"
    read -r mean max peak < <(sed 's/mean=\([^ ]*\) max=\([^ ]*\) peak=\(.*\)/\1 \2 \3/' "$work/err")
    awk -v n="$name" -v a="$mean" -v b="$max" -v p="$peak" -v te="$te" -v ts="$ts" 'BEGIN {
        holds = a <= 0.015 && b < 0.05 ? "holds" : (b < 0.05 ? "max holds, mean above" : "fails")
        printf "| %s | %.2f%% | %.2f%% | %s | %.4g | %s | %s |\n", n, 100 * a, 100 * b, holds, p, te, ts }' >> "$work/sh9-table"
done < "$work/maps"
splice "sh9 table" "$work/sh9-table"
echo "$page: the SH9 table"

# ---- speed against error: a lone diffuse and a lone glossy sphere ----
sphere_scene() { # FILE MAP INTEGRATOR-LINES MATERIAL-LINES
    cat > "$1" <<EOF
size 64 64
camera 0 0 3.3  0 0 0  0 1 0  40
maxdepth 3
pushTransform
rotate 1 0 0 -90
envmap $2
popTransform
$3
ambient 0 0 0
$4
sphere 0 0 0 1
EOF
}
PT=$(printf 'integrator pathtracer\nnexteventestimation mis\nimportancesampling brdf')
diffuse="diffuse 0.8 0.8 0.8"
glossy=$(printf 'diffuse 0.1 0.1 0.1\nspecular 0.7 0.7 0.7\nshininess 50')
{
    echo "| map | sphere | renderer | spp | CPU s | relMSE |"
    echo "|---|---|---|---|---|---|"
} > "$work/speed-table"
for mapname in courtyard sunrise; do
    map=$hdri/$mapname.exr
    for kind in diffuse glossy; do
        mat=$diffuse; [ "$kind" = glossy ] && mat=$glossy
        pic=$out/spheres_${mapname}_$kind
        sphere_scene "$work/pt.test" "$map" "$PT" "$mat"
        "$ENVTEX" render "$work/pt.test" -o "$work/ref.exr" --spp "$REF_SPP" --seed 99 --quiet >/dev/null
        "$ENVTEX" tonemap "$work/ref.exr" "${pic}_reference.png"
        for spp in 4 16 64 256; do
            t=$(cpu "$ENVTEX" render "$work/pt.test" -o "$work/img.exr" --spp "$spp" --seed 1 --ref "$work/ref.exr" --quiet)
            e=$(sed -n 's/.* relmse=\([^ ]*\) .*/\1/p' "$work/stdout")
            echo "| $mapname | $kind | path tracer | $spp | $t | $e |" >> "$work/speed-table"
            [ "$spp" = 16 ] && "$ENVTEX" tonemap "$work/img.exr" "${pic}_pathtracer16.png"
        done
        for method in exact sh9; do
            sphere_scene "$work/pf.test" "$map" "$(printf 'integrator prefiltered\nprefilter %s' "$method")" "$mat"
            for spp in 1 16 256; do
                t=$(cpu "$ENVTEX" render "$work/pf.test" -o "$work/img.exr" --spp "$spp" --seed 1 --ref "$work/ref.exr" --quiet)
                e=$(sed -n 's/.* relmse=\([^ ]*\) .*/\1/p' "$work/stdout")
                echo "| $mapname | $kind | prefiltered $method | $spp | $t | $e |" >> "$work/speed-table"
                [ "$spp" = 16 ] && "$ENVTEX" tonemap "$work/img.exr" "${pic}_$method.png"
            done
        done
        echo "${pic}_{exact,sh9,pathtracer16,reference}.png"
    done
done
splice "speed table" "$work/speed-table"
echo "$page: the speed table"
