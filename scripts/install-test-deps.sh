#!/usr/bin/env bash
# Installs what the tests and CI need beyond scripts/install-deps.sh, from Debian 12
# packages (as root): a single-node Slurm cluster (slurmctld, slurmd, munge) for the farm
# test, clang and its sanitizer runtimes for the fuzz targets, pytest and
# OpenImageIO's Python bindings for the Python tests, Blender for the Cycles route's tests
# (about 30 s to install), matplotlib for the evaluation's charts, and OIDN (the pyoidn
# wheel from PyPI, in /opt/statmc-oidn) for the --oidn tests. A workstation that only
# denoises needs none of them.
set -euo pipefail
cd "$(dirname "$0")"
bash install-deps.sh
packages=(
  slurm-wlm slurmctld slurmd slurm-client munge
  clang libclang-rt-14-dev
  python3-pytest python3-openimageio python3-matplotlib
  blender
)
export DEBIAN_FRONTEND=noninteractive
apt-get install -y -qq --no-install-recommends "${packages[@]}" >/dev/null
# OIDN for the --oidn tests (an optional run-time dependency of statmc, never of its build):
# the library of the pyoidn wheel (PyPI), in a virtual environment of its own.
if ! compgen -G "/opt/statmc-oidn/lib/python3*/site-packages/pyoidn/oidn/lib/libOpenImageDenoise.so.2" >/dev/null; then
  /usr/bin/python3 -m venv /opt/statmc-oidn
  /opt/statmc-oidn/bin/pip install -q pyoidn
fi
