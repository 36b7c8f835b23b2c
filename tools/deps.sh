#!/bin/sh
# deps.sh — make sure the Debian packages shlab needs are installed.
# As root: installs what is missing (apt-get update first).  Otherwise: prints
# the exact command to run and fails.  --quiet: say nothing when all is there.
# OPT_PKGS are peers for optional tests and benchmarks (tests/peers): `make
# deps` (this script without --quiet) installs them as root; otherwise their
# absence only skips those tests, with a message.
# --fuzz: also clang and its libFuzzer runtime (make fuzz).
set -eu
PKGS="build-essential pkg-config libgsl-dev libopenexr-dev libjansson-dev libmpfr-dev check gnuplot-nox"
PKGS="$PKGS libfftw3-dev"  # fast transforms (FFTW3 in φ)
# scenes: meshes (assimp), ray casting (Embree 3), PNG pictures
PKGS="$PKGS libassimp-dev libembree-dev libpng-dev"
PKGS="$PKGS parallel" # GNU parallel: sweeps run as shards on one machine (README, make check)
PKGS="$PKGS python3-numpy python3-pytest" # the Python package's tests (python/tests, make check)
# peers: HEALPix C++ (rotation oracle), libsharp (transform oracle)
OPT_PKGS="libhealpix-cxx-dev libsharp-dev"
OPT_PKGS="$OPT_PKGS valgrind" # bench --instructions (make bench-count) and its test
# shaders: the Vulkan loader, lavapipe (a CPU device: mesa-vulkan-drivers),
# shaderc with glslang and SPIRV-Tools (verify/bench --shader and their tests)
OPT_PKGS="$OPT_PKGS libvulkan-dev mesa-vulkan-drivers libshaderc-dev glslang-dev spirv-tools"
missing_of() {
    m=""
    for p in $1; do
        if ! dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed"; then
            m="$m $p"
        fi
    done
    echo "$m"
}
quiet=0
for a in "$@"; do
    case "$a" in
    --quiet) quiet=1 ;;
    --fuzz) PKGS="$PKGS clang libclang-rt-14-dev" ;; # make fuzz: clang's libFuzzer
    esac
done
missing=$(missing_of "$PKGS")
optional=""
[ "$quiet" = 1 ] || optional=$(missing_of "$OPT_PKGS")
if [ -z "$missing" ] && { [ -z "$optional" ] || [ "$(id -u)" != 0 ]; }; then
    if [ "$quiet" = 0 ]; then
        echo "deps: all present ($PKGS)"
        [ -z "$optional" ] || echo "deps: optional peers missing:$optional (their tests are skipped; run as root to install)"
    fi
    exit 0
fi
cmd="apt-get update && apt-get install -y --no-install-recommends$missing"
if [ "$(id -u)" = 0 ]; then
    echo "deps: installing$missing$optional"
    export DEBIAN_FRONTEND=noninteractive
    apt-get update -qq
    # shellcheck disable=SC2086
    [ -z "$missing" ] || apt-get install -y -qq --no-install-recommends $missing
    # shellcheck disable=SC2086
    [ -z "$optional" ] || apt-get install -y -qq --no-install-recommends $optional ||
        echo "deps: optional peers not installed:$optional (their tests are skipped)"
else
    echo "deps: missing packages:$missing" >&2
    echo "deps: run as root:  $cmd" >&2
    exit 1
fi
