#!/usr/bin/env bash
# The main job: set up, build, run the paper suites on the default data, print each table beside
# the paper's figures and write the report JSONs to results/ (with the Fig. 11 plots as SVG):
#   table1   Table 1, symmetric and nonsymmetric single grooves       results/table1.json
#   fig11    Fig. 11: BRDF vs traced procedural surfaces (2D and 3D)  results/fig11.json, results/fig11-*.svg
#   table2   Table 2: bounce counts at percentiles of D               results/table2.json
#   furnace  white furnace of the BRDF: Eq. 17 by quadrature and by   results/furnace.json
#            importance sampling; Cook-Torrance's loss
#   sampling importance sampling (Sec. 6): chi-square of the samplers,  results/sampling.json
#            variance per strategy, furnace
# Extra arguments go to every `vgroove validate` (e.g. --threads 1). Exit status: 0 when every
# suite passes, 1 when a threshold is exceeded, 2 on bad input.
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/setup.sh vgroove
mkdir -p results
status=0
for suite in table1 fig11 table2 furnace sampling; do
  build/vgroove validate "data/suites/$suite.json" --out "results/$suite.json" --force "$@" || status=$?
  [[ $status -eq 0 || $status -eq 1 ]] || exit "$status"
  echo
done
build/vgroove plot results/fig11.json --force
exit "$status"
