#!/usr/bin/env bash
# Sharded runs against one process: shards_test.sh VGROOVE SOURCE_DIR CHECK
#   validate | accuracy | simulate | energy: N shards (run one by one, merged in reverse order) give
#     the report of one process, value for value (timings aside, tests/cluster/same_report.py), and
#     the same exit code, for every suite kind and a model table; N larger than the work splits
#     cases into ray chunks.
#   refusals: merge refuses parts of different suites, seeds, versions or splits, repeated, missing
#     and truncated parts, each with a one-line error and exit 2, and writes nothing; a bad --shard
#     or a shard without --out is refused before any work.
#   killed: a shard killed (SIGKILL) or interrupted (SIGINT) leaves no report, and the merge of the
#     remaining parts is refused.
set -euo pipefail
bin=$1 src=$2 check=$3
t=$(mktemp -d)
trap 'rm -rf "$t"' EXIT
same() { python3 "$src/tests/cluster/same_report.py" "$1" "$2"; }
fail() { echo "FAIL: $*" >&2; exit 1; }

# Small suites of every kind.
cat >"$t/brdf.json" <<'J'
{"name": "tiny_brdf", "kind": "brdf", "description": "a small Fig. 11 suite",
 "ndf": ["ggx"], "alpha": [0.5], "theta_i_deg": [0, 40], "dimensions": ["flatland", "3d"],
 "rays": 6000, "grooves": 2000, "seed": 3, "flatland_bins": 30, "theta_bins": 9, "phi_bins": 8, "max_k": 8,
 "thresholds": {"sigmas": 5, "model_tolerance": {"flatland": 1e-5, "3d": 1e-4}}}
J
cat >"$t/table2.json" <<'J'
{"name": "tiny_table2", "kind": "table2", "ndf": ["ggx"], "alpha": [0.5, 1.0], "percentiles": [90, 99],
 "rays": 4000, "grooves": 2000, "seed": 1,
 "paper": {"source": "made up for the tests", "max_bounces": [[2, 3], [3, 16]]}}
J
cat >"$t/table1.json" <<'J'
{"name": "tiny_table1", "kind": "table1", "description": "a small Table 1 suite",
 "groove": {"type": "symmetric", "theta_v_deg": {"from": 10, "to": 170, "step": 40}},
 "theta_i_deg": {"from": -80, "to": 80, "step": 20}, "rays": 300, "sampling": "random", "seed": 7,
 "thresholds": {"max_l1": 0.5, "mean_l1": 0.5, "max_theta_o_error_rad": 1e-9}}
J
cat >"$t/nonsym.json" <<'J'
{"name": "tiny_nonsymmetric", "kind": "table1",
 "groove": {"type": "nonsymmetric", "theta_l_deg": {"from": -90, "to": -10, "step": 40},
            "theta_r_deg": {"from": 10, "to": 90, "step": 40}},
 "theta_i_deg": {"from": -75, "to": 75, "step": 25}, "rays": 200, "sampling": "stratified", "seed": 2018,
 "thresholds": {"max_l1": 0.004, "mean_l1": 0.0005, "max_theta_o_error_rad": 1e-9}}
J
cat >"$t/set.json" <<'J'
{"name": "tiny_set", "description": "both columns of a small Table 1", "suites": ["table1.json", "nonsym.json"]}
J
cat >"$t/scene.json" <<'J'
{"scene": "tiny_gold", "geometry": {"kind": "groove", "theta_v_deg": 60},
 "light": {"theta_i_deg": [0, 30, 60], "rays": 20000, "sampling": "stratified", "seed": 1},
 "effects": {"fresnel": {"kind": "conductor", "wavelengths": [{"lambda_nm": 548.6, "eta": 0.43, "kappa": 2.455}]},
             "record": {"theta_o_histograms": {"bins": 30, "max_k": 4}, "energy_per_k": true}, "max_bounces": 1000}}
J
cat >"$t/microsurface.json" <<'J'
{"scene": "tiny_microsurface", "geometry": {"kind": "microsurface", "ndf": "ggx", "alpha": 0.5, "grooves": 2000, "seed": 1},
 "light": {"theta_i_deg": [30], "rays": 30000, "sampling": "random", "seed": 1},
 "effects": {"fresnel": {"kind": "schlick", "channels": [{"name": "r", "F0": 0.95}]},
             "record": {"theta_o_histograms": {"bins": 30, "max_k": 4}, "energy_per_k": true}, "max_bounces": 1000}}
J
cat >"$t/furnace.json" <<'J'
{"name": "tiny_furnace", "kind": "furnace", "description": "a small furnace suite",
 "ndf": ["ggx"], "alpha": [0.3], "theta_i_deg": [0], "dimensions": ["flatland"], "max_k": 16,
 "samples": 1000, "strategy": "vndf", "rays": 1000, "grooves": 1000, "seed": 1,
 "thresholds": {"sigmas": 5, "quadrature_tolerance": {"flatland": 1e-9, "3d": 1e-6}}}
J
cat >"$t/nonsymmetric_brdf.json" <<'J'
{"name": "tiny_nonsymmetric_brdf", "kind": "nonsymmetric_brdf", "ndf": ["ggx"], "alpha": [0.5], "theta_i_deg": [30],
 "dimensions": ["flatland", "3d"],
 "anisotropic": {"ndf": ["beckmann"], "alpha_x": [0.1], "alpha_y": [0.3], "theta_i_deg": [40], "phi_i_deg": [90],
                 "partners": ["independent"]},
 "rays": 4000, "grooves": 2000, "seed": 5, "flatland_bins": 30, "theta_bins": 6, "phi_bins": 8, "max_k": 6,
 "plane_k": 2, "reciprocity_pairs": 3, "thresholds": {"sigmas": 5, "model_tolerance": {"flatland": 1e-3, "3d": 3e-3}}}
J
cat >"$t/profiles.json" <<'J'
{"name": "tiny_profiles", "kind": "profiles", "ndf": ["ggx"], "alpha": [0.5], "theta_deg": [0, 60],
 "surfaces": ["random", "vgroove"], "realizations": 2, "segments": 2048, "samples_per_length": 8, "rays": 3000,
 "walk_paths": 20000, "normal_bins": 6, "lobe_bins": 18, "max_k": 4, "seed": 2,
 "thresholds": {"p_min": 1e-3, "sigmas": 5, "model_tolerance": 1e-5}}
J
cat >"$t/heightfield.json" <<'J'
{"name": "tiny_heightfield", "kind": "heightfield", "ndf": ["beckmann", "ggx"], "alpha": [0.5], "theta_i_deg": [0, 60],
 "field_size": 64, "correlation_length": 4, "fields": 2, "rays": 3000, "walk_paths": 5000, "theta_bins": 6,
 "phi_bins": 4, "seed": 3, "thresholds": {"sigmas": 5},
 "masking": {"theta_o_deg": [45, 85], "phi_deg": [0, 180], "points": 500, "theta_m_bins": 3, "phi_m_bins": 2},
 "controls": [{"model": "cook_torrance_smith", "ndf": "beckmann", "alpha": 0.5, "theta_i_deg": 0}]}
J
cat >"$t/heightfield_grooves.json" <<'J'
{"name": "tiny_heightfield_grooves", "kind": "heightfield", "surface": "grooves", "ndf": ["ggx"], "alpha": [0.5],
 "theta_i_deg": [0, 60], "field_size": 64, "correlation_length": 4, "fields": 2, "rays": 3000, "walk_paths": 5000,
 "theta_bins": 6, "phi_bins": 4, "seed": 3, "thresholds": {"sigmas": 5}}
J
cat >"$t/heightfield_aniso.json" <<'J'
{"name": "tiny_heightfield_aniso", "kind": "heightfield", "aspect": 1.5, "ndf": ["beckmann"], "alpha": [0.3, 0.5],
 "theta_i_deg": [0], "field_size": 64, "correlation_length": 4, "fields": 2, "rays": 3000, "walk_paths": 5000,
 "theta_bins": 6, "phi_bins": 4, "seed": 3, "thresholds": {"sigmas": 5},
 "controls": [{"model": "smith_walk", "ndf": "beckmann", "alpha": 0.3, "theta_i_deg": 0}]}
J
cat >"$t/heightfield_aspects.json" <<'J'
{"name": "tiny_heightfield_aspects", "kind": "heightfield", "aspect": [1, 1.5], "walk_heights": ["log_c1", "gaussian"],
 "ndf": ["beckmann"], "alpha": [0.3], "theta_i_deg": [0, 60], "field_size": 64, "correlation_length": 4, "fields": 2,
 "rays": 3000, "walk_paths": 5000, "theta_bins": 6, "phi_bins": 4, "seed": 3, "thresholds": {"sigmas": 5},
 "controls": [{"model": "smith_walk", "ndf": "beckmann", "alpha": 0.3, "theta_i_deg": 0, "aspect": 1.5}]}
J
cat >"$t/sampling.json" <<'J'
{"name": "tiny_sampling", "kind": "sampling", "seed": 4, "max_k": 32,
 "chi_square": {"level": 0.01, "samples": {"3d": 20000, "flatland": 20000}, "cos_bins": 4, "phi_bins": 8, "theta_bins": 12,
                "cases": [{"dimension": "3d", "ndf": "ggx", "alpha": 0.5, "theta_i_deg": 30, "strategy": "vndf"},
                          {"dimension": "flatland", "ndf": "beckmann", "alpha": 0.3, "theta_i_deg": 60, "strategy": "printed"}]},
 "variance": {"samples": 2000, "schlick_f0": [1.0], "cases": [{"dimension": "flatland", "ndf": "ggx", "alpha": 0.5, "theta_i_deg": 30}]},
 "furnace": {"max_k": 32, "samples": 2000, "strategy": "vndf", "rays": 1000, "grooves": 1000, "sigmas": 5,
             "quadrature_tolerance": {"flatland": 1e-9, "3d": 1e-6},
             "cases": [{"dimension": "flatland", "ndf": "ggx", "alpha": 0.5, "theta_i_deg": 30}]}}
J
cat >"$t/dielectric_grooves.json" <<'J'
{"name": "tiny_dielectric_grooves", "kind": "dielectric_grooves", "theta_v_deg": [40, 90], "theta_i_deg": [0, 60],
 "eta": [1.5], "inverses": true, "grid": 16, "surface_rays": 100, "surface_min_weight": 1e-6,
 "thresholds": {"max_l1": 1e-12, "max_direction_error_rad": 1e-12}}
J
# (The 3D model's quadrature costs about a second of CPU per cell: few 3D cells.)
ENERGY=(energy --ndf ggx --dim flatland,3d --mu-points 1 --alpha-points 2 --rays 3000 --max-k 4)
ENERGY_FLAT=(energy --ndf ggx,phong --dim flatland --mu-points 3 --alpha-points 2 --rays 3000 --max-k 4)

# sharded NAME N CMD...: runs CMD --shard i/N for every i, merges the parts (last first) into
# $t/NAME.merged.json and compares it with CMD run in one process.
sharded() {
  local name=$1 n=$2
  shift 2
  local rc_one=0 rc_merged=0 parts=()
  "$bin" "$@" --threads 2 --out "$t/$name.one.json" >/dev/null || rc_one=$?
  for ((i = 1; i <= n; ++i)); do
    "$bin" "$@" --threads 1 --shard "$i/$n" --out "$t/$name.part$i.json" >/dev/null || fail "$name: shard $i/$n"
    parts=("$t/$name.part$i.json" "${parts[@]}")
  done
  "$bin" merge "${parts[@]}" --out "$t/$name.merged.json" >/dev/null || rc_merged=$?
  [[ $rc_one == "$rc_merged" ]] || fail "$name: exit $rc_one in one process, $rc_merged merged"
  same "$t/$name.one.json" "$t/$name.merged.json" || fail "$name: merged report differs"
  echo "ok: $name ($n shards, exit $rc_one)"
}

# refused MESSAGE_PART CMD...: CMD exits 2 with one line on stderr that holds MESSAGE_PART.
refused() {
  local want=$1 rc=0
  shift
  "$@" >"$t/out.txt" 2>"$t/err.txt" || rc=$?
  [[ $rc == 2 ]] || fail "exit $rc (want 2) from: $* ($(cat "$t/err.txt"))"
  [[ $(wc -l <"$t/err.txt") == 1 ]] || fail "not one line from: $*: $(cat "$t/err.txt")"
  grep -qF -- "$want" "$t/err.txt" || fail "'$want' not in: $(cat "$t/err.txt")"
  echo "ok: refused: $(cat "$t/err.txt")"
}

case $check in
  validate)
    sharded brdf 3 validate "$t/brdf.json"
    sharded brdf_chunks 7 validate "$t/brdf.json" --rays 3000   # 4 cases: some split into ray chunks
    sharded table2 3 validate "$t/table2.json"
    sharded set 4 validate "$t/set.json"
    sharded table1_overrides 2 validate "$t/table1.json" --rays 100 --seed 11 --sampling stratified
    sharded furnace 3 validate "$t/furnace.json"
    sharded furnace_seed 2 validate "$t/furnace.json" --seed 9
    sharded nonsymmetric_brdf 4 validate "$t/nonsymmetric_brdf.json"
    sharded profiles 3 validate "$t/profiles.json"
    sharded sampling 3 validate "$t/sampling.json"
    sharded heightfield 3 validate "$t/heightfield.json"
    sharded heightfield_grooves 2 validate "$t/heightfield_grooves.json"
    sharded heightfield_aniso 2 validate "$t/heightfield_aniso.json"
    sharded heightfield_aspects 3 validate "$t/heightfield_aspects.json"
    sharded dielectric_grooves 3 validate "$t/dielectric_grooves.json"
    # A foreign model: the brdf suite's layout filled with a flat lobe (it fails: the same verdict
    # merged as in one process).
    "$bin" bins "$t/brdf.json" --out "$t/layout.json" >/dev/null
    python3 - "$t/layout.json" "$t/table.json" <<'PY'
import json, sys
layout = json.load(open(sys.argv[1]))
cases = [{k: c[k] for k in ("case", "ndf", "alpha", "theta_i_deg", "dimension")} | {"flux": [0.9 / c["bins"]] * c["bins"]}
         for c in layout["cases"]]
json.dump({"kind": "model_table", "suite": layout["suite"], "model": "flat", "cases": cases}, open(sys.argv[2], "w"))
PY
    sharded model_table 3 validate "$t/brdf.json" --model-table "$t/table.json"
    ;;
  accuracy) sharded accuracy 3 bench accuracy "$t/table1.json" --rays 50,200 --sampling stratified,random ;;
  simulate)
    sharded simulate 2 simulate "$t/scene.json"
    sharded simulate_chunks 5 simulate "$t/microsurface.json"   # one case: ray chunks
    ;;
  energy)
    sharded energy 3 "${ENERGY[@]}"
    sharded energy_chunks 40 "${ENERGY_FLAT[@]}"   # 12 cells: split into ray chunks
    # Glass tables (--eta): both sides, both dimensions, the hemispherical cells; 5 shards split cells.
    sharded glass 5 energy --eta 1.5,0.8 --dim 3d,flatland --alpha 0.3 --mu 1,0.5 --rays 3000 --grooves 300
    ;;
  refusals)
    p() { "$bin" validate "$t/$1" --threads 1 --shard "$2" --out "$t/$3" "${@:4}" >/dev/null; }
    p table1.json 1/2 a1.json
    p table1.json 2/2 a2.json
    p table2.json 2/2 b2.json
    p table1.json 2/2 s2.json --seed 99
    p table1.json 2/2 r2.json --rays 100
    p table1.json 1/3 c1.json
    "$bin" merge "$t/a1.json" "$t/a2.json" --out "$t/ok.json" >/dev/null || fail "the control merge"
    refused "suite" "$bin" merge "$t/a1.json" "$t/b2.json" --out "$t/x.json"
    refused "seed" "$bin" merge "$t/a1.json" "$t/s2.json" --out "$t/x.json"
    refused "options" "$bin" merge "$t/a1.json" "$t/r2.json" --out "$t/x.json"
    refused "shard" "$bin" merge "$t/a1.json" "$t/a1.json" "$t/a2.json" --out "$t/x.json"
    refused "missing" "$bin" merge "$t/a1.json" --out "$t/x.json"
    refused "1/3" "$bin" merge "$t/c1.json" "$t/a2.json" --out "$t/x.json"
    head -c $(($(wc -c <"$t/a2.json") / 2)) "$t/a2.json" >"$t/trunc.json"
    refused "trunc.json" "$bin" merge "$t/a1.json" "$t/trunc.json" --out "$t/x.json"
    python3 - "$t/a2.json" "$t/v2.json" <<'PY'
import json, sys
j = json.load(open(sys.argv[1]))
j["version"] = "0.0.0-other"
json.dump(j, open(sys.argv[2], "w"))
PY
    refused "version" "$bin" merge "$t/a1.json" "$t/v2.json" --out "$t/x.json"
    [[ ! -e $t/x.json ]] || fail "a refused merge wrote a report"
    refused "--shard" "$bin" validate "$t/table1.json" --shard 3/2 --out "$t/f.json"
    refused "--out" "$bin" validate "$t/table1.json" --shard 1/2
    [[ ! -e $t/f.json ]] || fail "a refused shard wrote a part"
    ;;
  killed)
    "$bin" validate "$t/table2.json" --threads 1 --shard 1/2 --out "$t/k1.json" >/dev/null
    rc=0
    timeout -s KILL 1 "$bin" validate "$t/table2.json" --rays 100000000 --threads 1 --shard 2/2 --out "$t/k2.json" \
      >/dev/null 2>&1 || rc=$?
    [[ $rc == 137 ]] || fail "the shard ended by itself (exit $rc) before SIGKILL"
    [[ ! -e $t/k2.json ]] || fail "a killed shard left a report"
    rc=0
    timeout -s INT 1 "$bin" validate "$t/table2.json" --rays 100000000 --threads 1 --shard 2/2 --out "$t/k2.json" \
      >/dev/null 2>&1 || rc=$?
    [[ $rc != 0 ]] || fail "an interrupted shard exited 0"
    [[ ! -e $t/k2.json ]] || fail "an interrupted shard left a report"
    leftovers=$(find "$t" -name 'k2*')
    [[ -z $leftovers ]] || fail "files left: $leftovers"
    refused "missing" "$bin" merge "$t/k1.json" --out "$t/x.json"
    echo "ok: killed and interrupted shards left nothing"
    ;;
  *) fail "unknown check $check" ;;
esac
