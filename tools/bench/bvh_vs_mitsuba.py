#!/usr/bin/env python3
"""Primary-ray throughput of envtex against Mitsuba 3, in one run, interleaved, in CPU time.

    tools/bench/bvh_vs_mitsuba.py BUILD [ROUNDS]

The scene is a stand-in for the course's hw4 dragon: gen_mesh's displaced sphere (about 100k
triangles, written as OBJ here, at bench time), two quad lights, 1280 x 960 pixels, one primary
ray a pixel.  envtex casts them through its integrator (bench_bvh primary: the scene's BVH and
its quad lights), 8 x 8 pixels at a time as its renders do (bvh_packet.h), and one at a time;
Mitsuba renders the same camera, mesh and two rectangles at 1 sample a pixel in llvm_ad_rgb,
limited to one thread (Embree, ray wavefronts), with its `aov` integrator (depth only) and its
`path` integrator at max_depth 1 (the emission seen), and in scalar_rgb (aov).
Each renderer runs in a process of its own, all of them interleaved round by round; each time
is the CPU time of that process (all its threads), so a busy machine slows every one alike.
Prints Mrays per CPU-second, medians over the rounds, and envtex's ratio to each Mitsuba variant
round by round.  Exits 0 with a note when Mitsuba 3 is
not importable (pip install mitsuba).
"""
import glob
import os
import re
import statistics
import subprocess
import sys
import time

W, H = 1280, 960
EYE, CENTER, UP, FOVY = (0, 0.9, 3.6), (0, 0, 0), (0, 1, 0), 45
# quad lights as the scene file writes them: corner a, edges ab and ac, radiance
QUADS = [((-1.5, 3, -1), (0, 0, 2), (2, 0, 0), 1.0), ((2, 1, 2), (0, 1, 0), (0, 0, 1), 0.8)]


def write_scene(build, folder):
    obj = os.path.join(folder, "dragon.obj")
    subprocess.run([os.path.join(build, "tools", "gen_mesh"), "dragon", obj], check=True)
    lines = [f"size {W} {H}", "integrator analyticdirect",
             "camera %g %g %g  %g %g %g  %g %g %g  %g" % (EYE + CENTER + UP + (FOVY,))]
    for a, ab, ac, L in QUADS:
        lines.append("quadLight %g %g %g  %g %g %g  %g %g %g  %g %g %g" % (a + ab + ac + (L, L, L)))
    lines += ["diffuse 0.6 0.6 0.6", "obj dragon.obj"]
    path = os.path.join(folder, "dragon.test")
    with open(path, "w") as f:
        f.write("\n".join(lines) + "\n")
    return path


# what Mitsuba does at each primary ray's hit: `aov` the depth alone (the leanest: a ray cast
# and its surface interaction), `path` at max_depth 1 the emission seen (a renderer's pass of
# primary rays that shades what it finds)
INTEGRATORS = {"aov": {"type": "aov", "aovs": "dd.y:depth"},
               "path": {"type": "path", "max_depth": 1}}


def mitsuba_scene(mi, folder, integrator):
    shapes = {"dragon": {"type": "obj", "filename": os.path.join(folder, "dragon.obj"),
                         "bsdf": {"type": "diffuse"}}}
    for k, (a, ab, ac, L) in enumerate(QUADS):
        # rectangle: [-1, 1]^2 in z = 0; columns ab / 2, ac / 2, their normal, the centre
        n = [ab[1] * ac[2] - ab[2] * ac[1], ab[2] * ac[0] - ab[0] * ac[2],
             ab[0] * ac[1] - ab[1] * ac[0]]
        c = [a[i] + 0.5 * ab[i] + 0.5 * ac[i] for i in range(3)]
        m = [[ab[i] / 2, ac[i] / 2, n[i], c[i]] for i in range(3)] + [[0, 0, 0, 1]]
        shapes[f"quad{k}"] = {"type": "rectangle", "to_world": mi.ScalarTransform4f(m),
                              "emitter": {"type": "area", "radiance": {"type": "rgb", "value": L}}}
    return mi.load_dict({
        "type": "scene",
        "integrator": INTEGRATORS[integrator],
        "sensor": {"type": "perspective", "fov": FOVY, "fov_axis": "y",
                   "to_world": mi.ScalarTransform4f().look_at(origin=EYE, target=CENTER, up=UP),
                   "film": {"type": "hdrfilm", "width": W, "height": H, "rfilter": {"type": "box"}},
                   "sampler": {"type": "independent", "sample_count": 1}},
        **shapes})


def worker(config, folder):
    """Load the scene once, then render once for every line read; print the CPU seconds."""
    import drjit as dr
    import mitsuba as mi
    variant, integrator = config.split(":")
    mi.set_variant(variant)
    dr.set_thread_count(1)
    sc = mitsuba_scene(mi, folder, integrator)
    dr.eval(mi.render(sc, spp=1))  # the first render compiles the kernels: not timed
    for _ in sys.stdin:
        t = time.process_time()
        img = mi.render(sc, spp=1)
        dr.eval(img)
        dr.sync_thread()
        print(time.process_time() - t, flush=True)


def main():
    if len(sys.argv) >= 4 and sys.argv[1] == "--worker":
        return worker(sys.argv[2], sys.argv[3])
    build = sys.argv[1] if len(sys.argv) > 1 else "build"
    rounds = int(sys.argv[2]) if len(sys.argv) > 2 else 5
    try:
        import mitsuba  # noqa: F401
    except ImportError:
        print("bench bvh_vs_mitsuba: skipped: this Python cannot import Mitsuba 3 (to compare, "
              "`pip install mitsuba` into a venv, then `PYTHON=VENV/bin/python make bench`)")
        return 0
    folder = os.path.join(build, "bench")
    os.makedirs(folder, exist_ok=True)
    scene = write_scene(build, folder)
    variants = ["llvm_ad_rgb:aov", "llvm_ad_rgb:path", "scalar_rgb:aov"]
    # Dr.Jit loads the first libLLVM it finds; an old one (Debian 12's 14) fails to compile its
    # kernels ("Cannot select: fminimum"): offer the newest installed unless the user chose one
    llvms = sorted(glob.glob("/usr/lib/*/libLLVM-[0-9]*.so"),
                   key=lambda p: int(re.search(r"LLVM-(\d+)", p).group(1)))
    if llvms and "DRJIT_LIBLLVM_PATH" not in os.environ:
        os.environ["DRJIT_LIBLLVM_PATH"] = llvms[-1]
    workers = {v: subprocess.Popen([sys.executable, __file__, "--worker", v, folder],
                                   stdin=subprocess.PIPE, stdout=subprocess.PIPE, text=True)
               for v in variants}
    rays = W * H / 1e6
    rates = {"envtex": [], "envtex1": [], **{v: [] for v in variants}}
    for _ in range(rounds):
        out = subprocess.run([os.path.join(build, "tools", "bench_bvh"), "primary", scene, "1"],
                             check=True, capture_output=True, text=True).stdout
        last = out.splitlines()[-1]
        rates["envtex"].append(rays / float(re.search(r"\bcpu_s=([0-9.]+)", last).group(1)))
        rates["envtex1"].append(rays / float(re.search(r"single_cpu_s=([0-9.]+)", last).group(1)))
        for v, p in workers.items():
            p.stdin.write("go\n")
            p.stdin.flush()
            rates[v].append(rays / float(p.stdout.readline()))
    for p in workers.values():
        p.stdin.close()
        p.wait()
    print(f"primary rays, dragon stand-in ({W}x{H}, 99856 triangles, 2 quad lights), "
          f"Mrays per CPU-second, median of {rounds} interleaved rounds:")
    label = {"envtex": "envtex, 64 rays at a time", "envtex1": "envtex, one ray at a time",
             "llvm_ad_rgb:aov": "Mitsuba llvm_ad_rgb, 1 thread, aov",
             "llvm_ad_rgb:path": "Mitsuba llvm_ad_rgb, 1 thread, path",
             "scalar_rgb:aov": "Mitsuba scalar_rgb, aov"}
    for k, v in rates.items():
        print(f"  {label[k]:36s} {statistics.median(v):7.3f}   rounds: "
              + " ".join(f"{x:.3f}" for x in v))
    for mine in ("envtex", "envtex1"):
        for v in variants:
            ratio = [a / b for a, b in zip(rates[mine], rates[v])]
            print(f"  {mine:7s} / {v:16s} median {statistics.median(ratio):.3f}   rounds: "
                  + " ".join(f"{x:.3f}" for x in ratio))
    return 0


if __name__ == "__main__":
    sys.exit(main())
