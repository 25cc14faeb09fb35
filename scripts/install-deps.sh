#!/usr/bin/env bash
# Installs everything statmc needs to build, test and run, from Debian 12 packages.
set -euo pipefail
packages=(
  build-essential cmake ninja-build pkg-config
  libopenimageio-dev openimageio-tools libopenexr-dev libimath-dev openexr
  libopencolorio-dev libembree-dev libtbb-dev libboost-math-dev
  libgtest-dev libgmock-dev libbenchmark-dev libcli11-dev zlib1g-dev
  slurm-wlm slurmctld slurmd slurm-client munge
  clang libclang-rt-14-dev
  python3-matplotlib python3-numpy python3-openimageio python3-venv
  python3-dev pybind11-dev python3-pytest
)
export DEBIAN_FRONTEND=noninteractive
apt-get update -qq
apt-get install -y -qq --no-install-recommends "${packages[@]}" >/dev/null
