#!/usr/bin/env python3
"""The JSON Schemas in docs/schemas/ describe the files vgroove reads and writes: every checked-in
suite and scene validates against its schema, broken copies of them do not, and what the CLI writes
carries the report envelope. Run by ctest: schemas_test.py SOURCE_DIR VGROOVE_BIN."""
import copy
import json
import pathlib
import subprocess
import sys

import jsonschema

src = pathlib.Path(sys.argv[1])
vgroove = sys.argv[2]
schemas = {p.stem.replace(".schema", ""): json.loads(p.read_text()) for p in (src / "docs/schemas").glob("*.json")}
failures = []


def check(instance, schema, what, valid=True):
    errors = list(jsonschema.Draft202012Validator(schemas[schema]).iter_errors(instance))
    if valid and errors:
        failures.append(f"{what}: {errors[0].message}")
    if not valid and not errors:
        failures.append(f"{what}: accepted, should be refused")


for schema in schemas.values():
    jsonschema.Draft202012Validator.check_schema(schema)

suites = sorted((src / "data/suites").glob("*.json"))
scenes = sorted((src / "data/scenes").glob("*.json"))
assert suites and scenes
for p in suites:
    check(json.loads(p.read_text()), "suite", p.name)
for p in scenes:
    check(json.loads(p.read_text()), "scene", p.name)

# Broken copies: a typo'd key, a value out of range; the schema must refuse what the loader refuses.
fig11 = json.loads((src / "data/suites/fig11.json").read_text())
typo = copy.deepcopy(fig11)
typo["roughnes"] = typo.pop("alpha")
check(typo, "suite", "fig11 with a typo'd key", valid=False)
odd = copy.deepcopy(fig11)
odd["phi_bins"] = 7
check(odd, "suite", "fig11 with odd phi_bins", valid=False)
profiles = json.loads((src / "data/suites/profiles.json").read_text())
profiles["ndf"] = ["phong"]
check(profiles, "suite", "profiles with phong", valid=False)
heightfield = json.loads((src / "data/suites/heightfield.json").read_text())
heightfield["field_size"] = 100
check(heightfield, "suite", "heightfield with a field_size not a power of two", valid=False)
heightfield["field_size"] = 256
heightfield["surface"] = "voronoi"
check(heightfield, "suite", "heightfield with an unknown surface", valid=False)
heightfield["surface"] = "gaussian"
heightfield["aspect"] = 5
check(heightfield, "suite", "heightfield with aspect 5", valid=False)
gold = json.loads((src / "data/scenes/gold_groove.json").read_text())
gold["geometry"]["theta_v_deg"] = 195
check(gold, "scene", "gold_groove with theta_v 195", valid=False)

# What the CLI writes: the report envelope; the bin layout gives the model table's cases.
brdf = json.loads(subprocess.run([vgroove, "brdf", "--json", "--theta-o-deg", "20"], check=True,
                                 capture_output=True, text=True).stdout)
check(brdf, "report", "vgroove brdf --json")
layout = json.loads(subprocess.run([vgroove, "bins", str(src / "data/suites/fig11.json")], check=True,
                                   capture_output=True, text=True).stdout)
check(layout, "report", "vgroove bins")
table = {"kind": "model_table", "suite": layout["suite"], "model": "zeros",
         "cases": [dict({k: v for k, v in c.items() if k != "bins"}, flux=[0.0] * c["bins"]) for c in layout["cases"]]}
check(table, "model_table", "a model table filled from the layout")
import tempfile
with tempfile.TemporaryDirectory() as tmp:
    out = pathlib.Path(tmp) / "sample.json"
    subprocess.run([vgroove, "sample", "--n", "2000", "--dim", "flatland", "--out", str(out)], check=True,
                   capture_output=True, text=True)
    check(json.loads(out.read_text()), "report", "vgroove sample --out")
hf_brdf = json.loads((src / "data/suites/brdf_heightfield.json").read_text())
for key, value in (("surface", "heightfields"), ("dimensions", ["flatland"]), ("ndf", ["phong"])):
    check(dict(hf_brdf, **{key: value}), "suite", f"brdf_heightfield with {key} {value}", valid=False)
check(dict(hf_brdf, heightfield=dict(hf_brdf["heightfield"], field_size=100)), "suite",
      "brdf_heightfield with field_size 100", valid=False)
check({k: v for k, v in hf_brdf.items() if k != "heightfield"}, "suite", "brdf_heightfield without its fields",
      valid=False)
check(dict(fig11, heightfield=hf_brdf["heightfield"]), "suite", "fig11 with heightfield fields", valid=False)
furnace = json.loads((src / "data/suites/furnace.json").read_text())
furnace["strategy"] = "uniform"
check(furnace, "suite", "furnace with an unknown strategy", valid=False)
bad = copy.deepcopy(table)
bad["cases"][0]["flux"][0] = -1
check(bad, "model_table", "a model table with a negative flux", valid=False)

if failures:
    print("\n".join(failures))
    sys.exit(1)
print(f"schemas: {len(suites)} suites, {len(scenes)} scenes and the CLI's reports validate")
