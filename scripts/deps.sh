#!/usr/bin/env bash
# Installs the Debian 12 packages ffsim builds with, skipping those already present.
# Non-interactive; uses sudo only when not root.
set -euo pipefail
pkgs=(cmake g++ make pkg-config libglm-dev libopenimageio-dev libopenexr-dev doctest-dev valgrind)
missing=()
for p in "${pkgs[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if ((${#missing[@]})); then
  sudo=""
  [ "$(id -u)" -ne 0 ] && sudo=sudo
  echo "deps.sh: installing ${missing[*]}"
  $sudo apt-get update -q
  DEBIAN_FRONTEND=noninteractive $sudo apt-get install -y -q --no-install-recommends "${missing[@]}"
else
  echo "deps.sh: all packages present"
fi
