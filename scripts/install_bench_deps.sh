#!/usr/bin/env bash
# Installs what the LAMMPS comparison benchmark (bench/lammps/) needs on Debian 12:
# Debian's `lammps` package (binary `lmp`, PERI package built in, links OpenMPI) and numpy.
# Only for the benchmark, not for building or testing Peridot. Idempotent. Needs root (or sudo).
set -euo pipefail

packages=(lammps openmpi-bin python3-numpy)

missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if [ "${#missing[@]}" -eq 0 ]; then
  echo "install_bench_deps: all ${#packages[@]} packages present"
else
  sudo_cmd=()
  [ "$(id -u)" -eq 0 ] || sudo_cmd=(sudo)
  echo "install_bench_deps: installing ${missing[*]}"
  export DEBIAN_FRONTEND=noninteractive
  "${sudo_cmd[@]}" apt-get update -qq
  "${sudo_cmd[@]}" apt-get install -y -qq --no-install-recommends "${missing[@]}"
fi
command -v lmp >/dev/null || { echo "install_bench_deps: lmp not found on PATH" >&2; exit 1; }
