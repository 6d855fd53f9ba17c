#!/usr/bin/env bash
# The main job: set up, build, run the paper suite on the default data, print the table beside
# the paper's figures and write the report JSON to results/. Exit status is vgroove's: 0 pass,
# 1 a threshold exceeded, 2 bad input.
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/setup.sh vgroove
mkdir -p results
exec build/vgroove validate data/suites/table1.json --out results/table1.json --force "$@"
