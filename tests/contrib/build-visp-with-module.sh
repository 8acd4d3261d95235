#!/usr/bin/env bash
# Builds ViSP 3.5.0 from Debian's source package with this repository's modules/ as VISP_CONTRIB_MODULES_PATH, so
# that visp_projective is built as one more ViSP module, then builds and runs a tutorial of this repository against
# that ViSP build tree (find_package(VISP COMPONENTS visp_projective)).
#
# Usage (as root on Debian 12, after scripts/install-deps.sh):
#   bash tests/contrib/build-visp-with-module.sh [--configure-only] [WORK_DIR]
# --configure-only stops after ViSP's configuration: ViSP found the module, its dependencies (ViSP modules, Ceres,
# OpenCV, Eigen, nlohmann-json) and its sources (CI does that: about a minute; the build below took about 13 of CI's
# minutes, for sources the main build compiles as they are).
# WORK_DIR defaults to build/contrib-visp in the repository (.ci/run uses that). The source download and the ViSP
# build are reused by later runs (incremental). JOBS (default 2) sets the build parallelism. About 9 minutes from
# scratch on 2 shared cores (ViSP 8 min of it), seconds when nothing changed.
#
# ViSP is configured minimal: modules core, gui, io, me, blob, visual_features, vs, vision, robot (+ projective);
# no tests, examples, tutorials, demos, apps or Java; every optional 3rd party off except Eigen3 (ViSP's matrix
# back-end), a BLAS/LAPACK when found, pthread and X11 (for visp_gui).
set -euo pipefail
configure_only=0
if [ "${1:-}" = "--configure-only" ]; then
  configure_only=1
  shift
fi

repo="$(cd "$(dirname "$0")/../.." && pwd)"
work="$(mkdir -p "${1:-$repo/build/contrib-visp}" && cd "${1:-$repo/build/contrib-visp}" && pwd)"
jobs="${JOBS:-2}"
visp_version=3.5.0
start=$(date +%s)
step() { echo "== [$(( $(date +%s) - start )) s] $*"; }

# 1. ViSP's source, from Debian's source package (deb-src entry added if the machine has none).
src="$work/visp-$visp_version"
if [ ! -f "$src/CMakeLists.txt" ]; then
  step "getting the ViSP $visp_version source package"
  if ! grep -rqs '^\s*\(Types:.*deb-src\|deb-src\)' /etc/apt/sources.list /etc/apt/sources.list.d/; then
    [ "$(id -u)" -eq 0 ] || { echo "no deb-src entry and not root: cannot add one" >&2; exit 1; }
    cat > /etc/apt/sources.list.d/visp-projective-src.sources <<'SOURCES'
Types: deb-src
URIs: http://deb.debian.org/debian
Suites: bookworm
Components: main
Signed-By: /usr/share/keyrings/debian-archive-keyring.gpg
SOURCES
    apt-get update -qq
  fi
  command -v dpkg-source >/dev/null || { echo "dpkg-source missing: install dpkg-dev (scripts/install-deps.sh)" >&2; exit 1; }
  (cd "$work" && apt-get source -qq visp 2>&1 | grep -v "unsandboxed as root" || true)
  [ -f "$src/CMakeLists.txt" ] || { echo "apt-get source visp did not give $src" >&2; exit 1; }
fi

# 2. Minimal ViSP with the contrib module.
build="$work/visp-build"
off=()
for m in ar imgproc klt mbt tt tt_mi sensor; do off+=("-DBUILD_MODULE_visp_$m=OFF"); done
for u in AFMA4 AFMA6 VIPER650 VIPER850 VIRTUOSE ARSDK FFMPEG FRANKA JACOSDK DC1394 V4L2 FLYCAPTURE PYLON UEYE COMEDI \
         FTIITSDK BICLOPS PTU46 FLIRPTUSDK CMU1394 GDI DIRECTSHOW OPENMP COIN3D YARP OGRE OIS LIBFREENECT LIBUSB_1 \
         REALSENSE REALSENSE2 OCCIPITAL_STRUCTURE SOWIN SOQT QT SOXT XML2 OPENCV ZLIB GTK2 JPEG PNG ARIA ZBAR DMTX PCL \
         TENSORRT; do
  off+=("-DUSE_$u=OFF")
done
for w in ATIDAQ CLIPPER QBDEVICE TAKKTILE2 CATCH2; do off+=("-DWITH_$w=OFF"); done
step "configuring ViSP in $build"
# -O0: this checks that the module configures, builds, installs its headers and links as part of ViSP; the optimised
# library is what the main build tests (at -O3 ViSP and the module took 9 of CI's minutes here).
cmake -S "$src" -B "$build" -Wno-dev -DCMAKE_BUILD_TYPE=Release -DCMAKE_CXX_FLAGS_RELEASE="-O0 -DNDEBUG" \
  -DCMAKE_C_FLAGS_RELEASE="-O0 -DNDEBUG" -DBUILD_SHARED_LIBS=ON \
  -DBUILD_TESTS=OFF -DBUILD_EXAMPLES=OFF -DBUILD_TUTORIALS=OFF -DBUILD_DEMOS=OFF -DBUILD_APPS=OFF -DBUILD_JAVA=OFF \
  -DUSE_CXX_STANDARD=17 -DUSE_EIGEN3=ON -DUSE_X11=ON -DUSE_PTHREAD=ON "${off[@]}" \
  -DVISP_CONTRIB_MODULES_PATH="$repo/modules" > "$work/visp-configure.log"
grep -A3 "ViSP modules:" "$work/visp-configure.log" || true
grep -q "visp_projective" "$build/VISPModules.cmake" 2>/dev/null || { echo "visp_projective not among the configured modules" >&2; exit 1; }
if [ "$configure_only" -eq 1 ]; then
  grep -q "To be built:.* projective" "$work/visp-configure.log" \
    || { echo "ViSP configured without its visp_projective module" >&2; exit 1; }
  step "ViSP configured with the visp_projective module (--configure-only: not built)"
  exit 0
fi

step "building ViSP with -j$jobs"
cmake --build "$build" -j"$jobs" > "$work/visp-build.log" 2>&1 || { tail -50 "$work/visp-build.log"; exit 1; }
ls "$build"/lib/libvisp_projective.so* >/dev/null

# 3. A user's project against that build tree: a tutorial of this repository.
step "building the tutorial against the ViSP build tree"
consumer="$work/consumer-build"
cmake -S "$repo/tests/contrib" -B "$consumer" -DCMAKE_BUILD_TYPE=Release -DVISP_DIR="$build" > "$work/consumer-configure.log" \
  || { cat "$work/consumer-configure.log"; exit 1; }
cmake --build "$consumer" -j"$jobs"

step "running it"
ldd "$consumer/tutorial-projective-displacement" | grep "libvisp_projective" | grep -q "$build" \
  || { echo "the tutorial does not use the contrib build's libvisp_projective" >&2; ldd "$consumer/tutorial-projective-displacement"; exit 1; }
"$consumer/tutorial-projective-displacement" | tail -8
step "OK: visp_projective built as a ViSP contrib module, tutorial built and run against it"
