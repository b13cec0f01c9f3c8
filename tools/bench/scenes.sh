# tools/bench/scenes.sh - what the speed-against-error benches render, sourced by
# tools/bench/speed_vs_error and tools/bench/equal_time (bash), so that both render the same
# scenes against the same cached references.  The sourcing script sets ENVTEX (the renderer),
# REF_SPP (the reference's spp), refs (the reference cache) and work (a scratch folder), and
# runs from the repository's top.

# strategy name -> scene lines
strategy_lines() {
    case $1 in
        brdf)         echo "nexteventestimation off" ;;
        uniform)      echo "nexteventestimation on"; echo "envsampling uniform" ;;
        cdf)          echo "nexteventestimation on"; echo "envsampling cdf" ;;
        cdf-sintheta) echo "nexteventestimation on"; echo "envsampling cdf-sintheta" ;;
        mediancut)    echo "nexteventestimation on"; echo "envsampling mediancut 64" ;;
        mis)          echo "nexteventestimation mis"; echo "envsampling cdf" ;;
    esac
}
strategies="brdf uniform cdf cdf-sintheta mediancut mis"

# The bench scenes (kinds), three balls on a plane each, path traced (4 bounces):
#   matte: a diffuse ball and GGX balls of roughness 0.2 and 0.5 (light reaches the camera
#          after a diffuse or glossy bounce: what environment sampling is for);
#   shiny: a GGX 0.05 ball, a mirror ball and a glass ball (the floor also receives caustics,
#          light that only BRDF sampling can find: every strategy converges slowly there);
#   lamps: matte's balls under two quad lights beside the envmap, a large dim one and a small
#          bright one (next-event estimation samples each light and the envmap, lightselection
#          all: the strategies' envmap sampling is one of three lights there).
# BENCH_KINDS chooses some of them (default: all three).
kinds=${BENCH_KINDS:-matte shiny lamps}
scene() { # kind envfile strategy spp
    cat <<EOS
size 160 40
integrator pathtracer
importancesampling brdf
maxdepth 4
spp $4
camera 0 1.1 6.5  0 0.45 0  0 1 0  24
pushTransform
rotate 1 0 0 -90
envmap $(basename "$2")
popTransform
$(strategy_lines "$3")
ambient 0 0 0
diffuse 0.5 0.5 0.5
vertex -20 0 -20
vertex 20 0 -20
vertex 20 0 20
vertex -20 0 20
tri 0 2 1
tri 0 3 2
EOS
    if [ "$1" = lamps ]; then cat <<EOS
quadLight -2.5 3 -1.5  0 0 2  2 0 0  5 5 5
quadLight 1.8 1.6 0.8  0 0 0.3  0.3 0 0  150 150 150
EOS
    fi
    if [ "$1" != shiny ]; then cat <<EOS
diffuse 0.7 0.7 0.7
sphere -1.65 0.5 0 0.5
brdf ggx
diffuse 0.1 0.1 0.1
specular 0.8 0.8 0.8
roughness 0.2
sphere 0 0.5 0 0.5
roughness 0.5
sphere 1.65 0.5 0 0.5
EOS
    else cat <<EOS
brdf ggx
diffuse 0.1 0.1 0.1
specular 0.8 0.8 0.8
roughness 0.05
sphere -1.65 0.5 0 0.5
brdf mirror
diffuse 0 0 0
specular 0.9 0.9 0.9
sphere 0 0.5 0 0.5
brdf glass
sphere 1.65 0.5 0 0.5
EOS
    fi
}

# bench_field NAME: the VALUE of " NAME=VALUE" in the `envtex render` line on stdin ("relmse" is
# not "relmse_trim")
bench_field() {
    local line
    line=$(cat)
    sed -n "s/.* $1=\([^ ]*\).*/\1/p" <<<" $line"
}

# bench_map ENV FILE: the map ENV made afresh as FILE: sky and sun from gen-env (512 wide), the
# others copied from ../shared/hdri.  One kept from an earlier run would outlive changes to
# genenv or ../shared/hdri, and the references' checksums, taken of this file, could not tell (a
# cached sun.exr kept the 1.5-degree sun of before genenv's 0.5-degree default).
bench_map() {
    case $1 in
        sky|sun) "$ENVTEX" gen-env "$1" "$2" --width 512 >/dev/null ;;
        *) cp "../shared/hdri/$1.exr" "$2" ;;
    esac
}

# bench_ref KIND ENVFILE NAME WHO: print the path of the REF_SPP-spp MIS reference of scene KIND
# under ENVFILE (seed 99), rendering it first if it is not cached (WHO says so on stderr).  Its
# name holds the spp and a checksum of the scene and the map, so changing either renders anew.
bench_ref() {
    scene "$1" "$2" mis "$REF_SPP" > "$work/$3-ref.test"
    local sum ref
    sum=$( (cat "$work/$3-ref.test"; cksum < "$2") | cksum | cut -d' ' -f1)
    ref="$refs/$3-$REF_SPP-$sum.exr"
    if [ ! -f "$ref" ]; then
        echo "$4: rendering the $REF_SPP-spp reference for $3 (once; cached as $ref)" >&2
        "$ENVTEX" render "$work/$3-ref.test" -o "$ref" --quiet --seed 99 >/dev/null || return 1
    fi
    echo "$ref"
}
