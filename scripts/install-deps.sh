#!/usr/bin/env bash
# Installs the Debian 12 packages visp_projective needs, only when one is missing (run as root).
set -euo pipefail
# dpkg-dev: apt-get source visp (tests/contrib/build-visp-with-module.sh); doxygen: the doc target and its ctest case;
# clang-14, libclang-rt-14-dev: the libFuzzer target (tests/fuzz/run-fuzz.sh); xvfb, xauth: the live view's suite
# (testStereoServoDisplay) opens its windows, and runs the AprilTag tutorial with its display on, in an X server of
# its own (Xvfb; xauth for xvfb-run by hand); python3-dev, python3-numpy, pybind11-dev: the Python module (python/);
# python3-matplotlib, python3-pytest: its tutorials' figures and its tests.
packages=(build-essential cmake libvisp-dev libeigen3-dev libopencv-dev libceres-dev libgtest-dev libbenchmark-dev
          nlohmann-json3-dev
          gnuplot-nox dpkg-dev doxygen clang-14 libclang-rt-14-dev xvfb xauth
          python3-dev python3-numpy pybind11-dev python3-matplotlib python3-pytest)
missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if [ ${#missing[@]} -gt 0 ]; then
  echo "Installing: ${missing[*]}"
  export DEBIAN_FRONTEND=noninteractive
  apt-get update -qq
  apt-get install -y -qq --no-install-recommends "${missing[@]}"
fi
