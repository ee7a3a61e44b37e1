#!/usr/bin/env bash
# Installs the Debian 12 packages this project needs, only those missing. Quiet when all are present.
set -euo pipefail

PACKAGES=(
  build-essential cmake pkg-config
  libglfw3-dev libglm-dev libimgui-dev libstb-dev libeigen3-dev tetgen libopenmesh-dev catch2
  libsuitesparse-dev libepoxy-dev nlohmann-json3-dev libtinygltf-dev
  libcgal-dev  # 4D Delaunay triangulations (dD, Epick_d) for transitions between keys
  libboost-dev  # Boost Graph (header-only): max-flow for the robust volume's graph cut
  libassimp-dev  # FBX, Collada and BVH import (rigged characters, motion)
  xvfb xauth libgl1-mesa-dri
  clang libclang-rt-14-dev
  libopenblas0-pthread  # optimized BLAS behind CHOLMOD (Debian switches libblas.so.3 to it)
)

missing=()
for p in "${PACKAGES[@]}"; do
  if ! dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed"; then
    missing+=("$p")
  fi
done
[ ${#missing[@]} -eq 0 ] && exit 0

if ! command -v apt-get >/dev/null 2>&1; then
  echo "install-deps: apt-get not found; this script supports Debian 12. Missing: ${missing[*]}" >&2
  exit 1
fi
SUDO=""
if [ "$(id -u)" -ne 0 ]; then
  if command -v sudo >/dev/null 2>&1; then SUDO=sudo; else
    echo "install-deps: run as root (or install sudo) to install: ${missing[*]}" >&2
    exit 1
  fi
fi
echo "install-deps: installing ${missing[*]}"
export DEBIAN_FRONTEND=noninteractive
if ! $SUDO apt-get update -qq >/tmp/deform-apt.log 2>&1 ||
   ! $SUDO apt-get install -y -qq --no-install-recommends "${missing[@]}" >>/tmp/deform-apt.log 2>&1; then
  echo "install-deps: apt-get failed installing: ${missing[*]} (log: /tmp/deform-apt.log)" >&2
  tail -n 20 /tmp/deform-apt.log >&2
  exit 1
fi
