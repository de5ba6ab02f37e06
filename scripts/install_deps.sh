#!/usr/bin/env bash
# Installs the Debian 12 packages iarap needs; skips what is already there (idempotent).
set -euo pipefail
packages=(
  cmake ninja-build g++ pkg-config clang-format-14
  libeigen3-dev libsuitesparse-dev libmetis-dev libspectra-dev libopenblas0-pthread
  libcli11-dev nlohmann-json3-dev libnanoflann-dev libpng-dev libcpp-httplib-dev libtinyobjloader-dev
  libgtest-dev libgmock-dev libbenchmark-dev
  pybind11-dev python3-dev python3-numpy python3-scipy python3-pytest python3-pytest-xdist python3-matplotlib python3-distributed
  python3-venv python3-setuptools python3-wheel python3-build python3-mypy dpkg-dev
  python3-vtk9 xvfb xauth
  chromium
  tetgen # run as a program by deform --volume (AGPL: never linked)
)
missing=()
for p in "${packages[@]}"; do
  if ! dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed"; then
    missing+=("$p")
  fi
done
if [ ${#missing[@]} -eq 0 ]; then
  echo "install_deps: all ${#packages[@]} Debian packages present"
  exit 0
fi
echo "install_deps: installing ${missing[*]}"
sudo_cmd=()
if [ "$(id -u)" -ne 0 ]; then sudo_cmd=(sudo); fi
export DEBIAN_FRONTEND=noninteractive
"${sudo_cmd[@]}" apt-get update -qq
"${sudo_cmd[@]}" apt-get install -y -qq --no-install-recommends "${missing[@]}"
