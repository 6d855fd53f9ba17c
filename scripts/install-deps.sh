#!/usr/bin/env bash
# Installs the Debian packages vgroove needs that are missing (and any named as arguments).
# Does nothing, quickly, when all are installed.
set -euo pipefail
# The Python module and the plots: pybind11-dev python3-dev (build), python3-numpy
# python3-matplotlib (run; matplotlib brings PIL), python3-tqdm (progress bars, optional),
# python3-pytest (tests), python3-venv python3-pip (`pip install .` into a venv, tested offline);
# all for Debian's /usr/bin/python3. MPI (libopenmpi-dev openmpi-bin): the tests run vgroove under mpirun
# (tests/cluster/); the default build does not need it. Boost.Math (header-only): the tests'
# chi-square p-values. libpng-dev libopenexr-dev: `vgroove energy --export`'s 16-bit PNG and
# OpenEXR tables. libembree-dev: bench/heightfield_embree_bench.cpp (optional: built when found).
# The tests of scripts/cluster/ run GNU parallel (parallel) and a single-node
# Slurm of their own (munge slurmctld slurmd slurm-client); the test of `vgroove report` loads the
# page in headless Chromium (chromium). None of these is needed to build or run vgroove.
packages=(g++ cmake ninja-build git libeigen3-dev libcli11-dev nlohmann-json3-dev
          libgtest-dev libgmock-dev libbenchmark-dev libboost-math-dev python3-jsonschema
          libpng-dev libopenexr-dev libembree-dev
          pybind11-dev python3-dev python3-numpy python3-matplotlib python3-pytest python3-tqdm python3-venv
          python3-pip
          libopenmpi-dev openmpi-bin parallel munge slurmctld slurmd slurm-client chromium "$@")
missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
((${#missing[@]})) || exit 0
if [[ $(id -u) -ne 0 ]]; then
  echo "install-deps: missing packages: ${missing[*]}; run as root (or: sudo apt-get install ${missing[*]})" >&2
  exit 1
fi
echo "install-deps: installing ${missing[*]}" >&2
export DEBIAN_FRONTEND=noninteractive
apt-get update -qq
apt-get install -y -qq --no-install-recommends "${missing[@]}" >&2
