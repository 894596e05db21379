#!/usr/bin/env bash
# Installs Debian 12's ParaView and its Python (paraview, python3-paraview: pvpython), which
# tests/regression/test_postprocessors.py uses to open Peridot's Exodus output with ParaView's own reader.
# Optional: about 440 MB in some 140 packages, so the main install (scripts/install_deps.sh) leaves it out, and
# that test skips its ParaView part, saying so, when pvpython is missing. Idempotent. Needs root (or sudo).
set -euo pipefail

packages=(paraview python3-paraview)

missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if [ "${#missing[@]}" -eq 0 ]; then
  echo "install_paraview: all ${#packages[@]} packages present"
else
  sudo_cmd=()
  [ "$(id -u)" -eq 0 ] || sudo_cmd=(sudo)
  echo "install_paraview: installing ${missing[*]}"
  export DEBIAN_FRONTEND=noninteractive
  "${sudo_cmd[@]}" apt-get update -qq
  "${sudo_cmd[@]}" apt-get install -y -qq --no-install-recommends "${missing[@]}" </dev/null
fi
command -v pvpython >/dev/null || { echo "install_paraview: pvpython not found on PATH" >&2; exit 1; }
