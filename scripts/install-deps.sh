#!/usr/bin/env bash
# Installs the Debian 12 packages fogradar builds with, only those that are missing; arguments name
# further packages a script needs (scripts/fuzz.sh: clang and its fuzzer runtime).
set -euo pipefail
packages=(
  build-essential cmake ninja-build pkg-config clang-format
  libeigen3-dev libfftw3-dev libboost-dev
  libgtest-dev libgmock-dev libbenchmark-dev
  libcli11-dev libtomlplusplus-dev nlohmann-json3-dev
  libhdf5-dev hdf5-tools libopenmpi-dev openmpi-bin
  pybind11-dev python3-dev python3-numpy python3-pandas python3-pytest python3-h5py
  python3-matplotlib
  "$@"
)
missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if ((${#missing[@]})); then
  echo "installing: ${missing[*]}" >&2
  sudo_cmd=()
  [ "$(id -u)" -eq 0 ] || sudo_cmd=(sudo)
  "${sudo_cmd[@]}" apt-get update -qq
  DEBIAN_FRONTEND=noninteractive "${sudo_cmd[@]}" apt-get install -y -qq --no-install-recommends "${missing[@]}"
fi
