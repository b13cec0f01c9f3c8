#!/usr/bin/env bash
# setup.sh: Gradescope's autograder setup (make autograder; docs/grading.md, "Gradescope").  Runs
# once, as root, when Gradescope builds the autograder's image, in AUTOGRADER_ROOT/source (default
# /autograder/source), where the zip is unpacked: installs the Debian packages the Makefile
# names, stops on an OpenEXR older than 3.1 (its C API), builds the grader's envtex and renders
# the references of tools/grade/points.txt's scenes once, into build/grade-refs.
set -eu
ROOT=${AUTOGRADER_ROOT:-/autograder}
cd "$ROOT/source"
packages=$(sed -n 's/^DEB_PACKAGES = //p' Makefile)
missing=""
for p in $packages; do
    dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q 'install ok installed' ||
        missing="$missing $p"
done
if [ -n "$missing" ]; then
    echo "setup.sh: installing$missing"
    export DEBIAN_FRONTEND=noninteractive
    apt-get update -qq && apt-get install -y -qq $missing >/dev/null
fi
v=$(pkg-config --modversion OpenEXR 2>/dev/null || echo none)
if ! pkg-config --atleast-version=3.1 OpenEXR; then
    echo "envtex: setup.sh: this image has OpenEXR $v; envtex needs 3.1 or later (its C API):" \
        "choose Ubuntu 24.04 (or Debian 12) as the autograder's base image" >&2
    exit 1
fi
# the unprivileged user a student's code runs as where no sandbox can be made (run_autograder): in
# Gradescope's own root only, not in a trial root on someone's machine
if [ -z "${AUTOGRADER_ROOT:-}" ] && ! id -u envtex-student >/dev/null 2>&1; then
    useradd --system --uid 64000 --user-group --no-create-home --shell /usr/sbin/nologin \
        envtex-student || echo "setup.sh: no user envtex-student: uid 64000 is used bare" >&2
fi
make -j"$(nproc)" build/envtex
tools/grade/run --references build/grade-refs
