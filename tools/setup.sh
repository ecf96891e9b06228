#!/usr/bin/env bash
# Sets up Rondel on a Debian machine: installs the Debian packages that are missing (as root, with apt-get),
# then configures and builds everything (Release) in build/. Safe to run again: it installs nothing that is
# already there and rebuilds only what changed.
#   bash tools/setup.sh
set -euo pipefail
cd "$(dirname "${BASH_SOURCE[0]}")/.."

fail() {
  echo "tools/setup.sh: ERROR: $*" >&2
  exit 1
}

PACKAGES=(
  cmake g++ make
  libopenmpi-dev openmpi-bin
  libmetis-dev
  libhdf5-openmpi-dev hdf5-tools
  libeigen3-dev
  libboost-program-options-dev
  libgtest-dev
  python3-h5py python3-numpy python3-matplotlib
)

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
echo "tools/setup.sh: configuring (cmake -S . -B build -DCMAKE_BUILD_TYPE=Release)"
cmake -S . -B build -DCMAKE_BUILD_TYPE=Release ||
  fail "cmake configuration failed (see above); if build/ comes from another checkout, remove it: rm -rf build"
echo "tools/setup.sh: building (make -C build -j${jobs})"
make -C build -j"${jobs}" || fail "the build failed (see the compiler messages above)"
[ -x build/rondel ] || fail "the build finished but build/rondel is missing"
echo "tools/setup.sh: build complete: build/rondel, build/rondel_bench"
