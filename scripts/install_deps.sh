#!/usr/bin/env bash
# Installs every Debian 12 package Peridot needs to build, test, run its examples and plot.
# Idempotent: re-running it installs nothing new. Needs root (or sudo).
set -euo pipefail

packages=(
  cmake ninja-build g++ pkg-config
  libyaml-cpp-dev libeigen3-dev libmuparser-dev libtinyxml2-dev
  libexodusii-dev libnetcdf-dev
  libopenmpi-dev openmpi-bin libtrilinos-zoltan-dev libpetsc-real-dev libhwy-dev
  googletest libgtest-dev libbenchmark-dev libcli11-dev libfmt-dev
  pybind11-dev python3-dev
  python3-numpy python3-matplotlib python3-netcdf4 python3-meshio python3-scipy
  clang libclang-rt-14-dev libomp-14-dev
)

missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if [ "${#missing[@]}" -eq 0 ]; then
  echo "install_deps: all ${#packages[@]} packages present"
  exit 0
fi

sudo_cmd=()
[ "$(id -u)" -eq 0 ] || sudo_cmd=(sudo)
echo "install_deps: installing ${missing[*]}"
export DEBIAN_FRONTEND=noninteractive
"${sudo_cmd[@]}" apt-get update -qq
"${sudo_cmd[@]}" apt-get install -y -qq --no-install-recommends "${missing[@]}"
