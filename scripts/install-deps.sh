#!/usr/bin/env bash
# Installs what building and running statmc need, from Debian 12 packages (as root): the
# compiler and CMake, the image, renderer and math libraries, GoogleTest and Google
# Benchmark (the default build builds the tests and benchmarks), and Python's headers,
# pybind11, numpy and venv for `import statmc`. The tests' own tools (Slurm, clang's fuzzer,
# pytest) are scripts/install-test-deps.sh's.
set -euo pipefail
packages=(
  build-essential cmake ninja-build pkg-config
  libopenimageio-dev openimageio-tools libopenexr-dev libimath-dev openexr
  libopencolorio-dev libembree-dev libtbb-dev libboost-math-dev
  libgtest-dev libgmock-dev libbenchmark-dev libcli11-dev zlib1g-dev
  python3-dev pybind11-dev python3-numpy python3-venv
)
export DEBIAN_FRONTEND=noninteractive
apt-get update -qq
apt-get install -y -qq --no-install-recommends "${packages[@]}" >/dev/null
