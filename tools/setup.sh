#!/usr/bin/env bash
# Sets up Rondel on a Debian machine: installs the Debian packages that are missing (as root, with apt-get),
# then configures (Release) and builds in build/: every target, or only the TARGETs given. Safe to run again:
# it installs nothing that is already there and rebuilds only what changed.
#   bash tools/setup.sh [--no-tests] [--paraview] [TARGET ...]
#     TARGET      make targets to build (rondel, rondel_bench, rondel_serial_tests, ...); default: all
#     --no-tests  configure with -DBUILD_TESTING=OFF: no test suite, GoogleTest and Eigen not needed
#     --paraview  also ParaView and xvfb (about 440 MB), so that the test tools.paraview runs instead of being
#                 skipped; implied when CI=true
set -euo pipefail
cd "$(dirname "${BASH_SOURCE[0]}")/.."

fail() {
  echo "tools/setup.sh: ERROR: $*" >&2
  exit 1
}

testing=ON
paraview=OFF
[ "${CI:-}" = true ] && paraview=ON
targets=()
for arg in "$@"; do
  case "$arg" in
    --no-tests) testing=OFF ;;
    --paraview) paraview=ON ;;
    -h | --help)
      sed -n '2,9s/^# \{0,1\}//p' "${BASH_SOURCE[0]}"
      exit 0
      ;;
    -*) fail "unknown option '$arg' (options: --no-tests, --paraview, then make targets)" ;;
    *) targets+=("$arg") ;;
  esac
done

PACKAGES=(
  cmake g++ make
  libopenmpi-dev openmpi-bin
  libmetis-dev
  libhdf5-openmpi-dev hdf5-tools
  libboost-program-options-dev
  python3-h5py python3-numpy python3-matplotlib
  python3-dev python3-pybind11 python3-mpi4py
)
# Needed by the test suite only; ParaView for its ParaView test (tests/tools/test_paraview.py).
if [ "$testing" = ON ]; then
  PACKAGES+=(libeigen3-dev libgtest-dev python3-pytest)
  [ "$paraview" = ON ] && PACKAGES+=(paraview python3-paraview xvfb)
fi

command -v dpkg >/dev/null 2>&1 ||
  fail "dpkg not found: this script supports Debian (and derivatives) only. Install by hand: ${PACKAGES[*]}"

missing=()
for p in "${PACKAGES[@]}"; do
  if ! dpkg -s "$p" 2>/dev/null | grep -q '^Status: install ok installed'; then
    missing+=("$p")
  fi
done

if ((${#missing[@]} > 0)); then
  echo "tools/setup.sh: installing missing Debian packages: ${missing[*]}"
  [ "$(id -u)" -eq 0 ] ||
    fail "packages missing (${missing[*]}) and not running as root; run as root or: sudo apt-get install -y ${missing[*]}"
  command -v apt-get >/dev/null 2>&1 || fail "apt-get not found; install by hand: ${missing[*]}"
  export DEBIAN_FRONTEND=noninteractive
  apt-get update || fail "'apt-get update' failed (no network or no package sources?)"
  apt-get install -y --no-install-recommends "${missing[@]}" ||
    fail "'apt-get install ${missing[*]}' failed (see the apt-get messages above)"
else
  echo "tools/setup.sh: all ${#PACKAGES[@]} Debian packages are installed"
fi

jobs=$(nproc 2>/dev/null || echo 2)
# BUILD_TESTING is given every time, so that a build/ configured without tests gets them back.
echo "tools/setup.sh: configuring (cmake -S . -B build -DCMAKE_BUILD_TYPE=Release -DBUILD_TESTING=${testing})"
cmake -S . -B build -DCMAKE_BUILD_TYPE=Release -DBUILD_TESTING="${testing}" ||
  fail "cmake configuration failed (see above); if build/ comes from another checkout, remove it: rm -rf build"
echo "tools/setup.sh: building (make -C build -j${jobs} ${targets[*]:-all})"
make -C build -j"${jobs}" "${targets[@]}" || fail "the build failed (see the compiler messages above)"
if ((${#targets[@]} == 0)); then
  [ -x build/rondel ] || fail "the build finished but build/rondel is missing"
  echo "tools/setup.sh: build complete: build/rondel, build/rondel_bench, build/rondel_bench_io$(
    [ "$testing" = ON ] && echo ' and the tests')"
else
  echo "tools/setup.sh: build complete: ${targets[*]}"
fi
