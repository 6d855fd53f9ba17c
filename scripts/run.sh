#!/usr/bin/env bash
# The main job: set up, build, run the paper suites on the default data, print each table beside
# the paper's figures, write the report JSONs to results/ and the plots next to them (matplotlib,
# `vgroove plot`):
#   table1   Table 1, symmetric and nonsymmetric single grooves       results/table1.json, table1.png (L1 heatmaps)
#   table1_breakpoints  the same, traced fractions exact by breakpoint  results/table1_breakpoints.json,
#            search (thresholds 10^6 times tighter)                     table1_breakpoints.png
#   fig11    Fig. 11: BRDF vs traced procedural surfaces (2D and 3D)  results/fig11.json, fig11-NDF-DIM.png (6 grids)
#   table2   Table 2: bounce counts at percentiles of D               results/table2.json, table2.png
#   furnace  white furnace of the BRDF: Eq. 17 by quadrature and by   results/furnace.json, furnace.png (albedo),
#            importance sampling; Cook-Torrance's loss                  furnace-errors.png
#   sampling importance sampling (Sec. 6): chi-square of the samplers,  results/sampling.json, sampling.png (chi-square),
#            variance per strategy, furnace                             sampling-variance.png, sampling-furnace*.png
#   nonsymmetric_brdf  the nonsymmetric BRDF (Eq. 23) and anisotropy    results/nonsymmetric_brdf.json,
#            vs traced nonsymmetric surfaces                            nonsymmetric_brdf.png (L1 per case),
#                                                                       nonsymmetric_brdf[-aniso]-NDF-DIM.png (grids)
# and then one page of them all, results/index.html (`vgroove report`: every suite's verdict, the paper's
# figures beside ours, thresholds, worst cases, wall times, versions, seeds and the plots, in one
# self-contained file to open in a browser or keep as a CI artifact).
# Extra arguments go to every `vgroove validate` (e.g. --threads 1). Exit status: 0 when every
# suite passes, 1 when a threshold is exceeded, 2 on bad input.
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/setup.sh vgroove
mkdir -p results
status=0
for suite in table1 table1_breakpoints fig11 table2 furnace sampling nonsymmetric_brdf; do
  build/vgroove validate "data/suites/$suite.json" --out "results/$suite.json" --force "$@" || status=$?
  [[ $status -eq 0 || $status -eq 1 ]] || exit "$status"
  echo
done
for suite in table1 table1_breakpoints fig11 table2 furnace sampling nonsymmetric_brdf; do
  build/vgroove plot "results/$suite.json" --force
done
build/vgroove report results --out results/index.html --force
exit "$status"
