#!/usr/bin/env python3
"""Writes data/suites/stress.json: the numerically hard cases of a single groove.

Run from the repository root: python3 data/suites/generators/make_stress.py
The JSON is checked in; this script records how its listed cases were chosen.
"""
import json

apertures = [0.01, 0.1, 1, 179, 179.99, 180]
grazing = [-89.99, -89.9, -60, -30, 0, 30, 60, 89.9, 89.99]
cases = []


def sym(v, i, note):
    cases.append({"theta_v_deg": v, "theta_i_deg": i, "note": note})


def nonsym(l, r, i, note):
    cases.append({"theta_l_deg": l, "theta_r_deg": r, "theta_i_deg": i, "note": note})


for v in apertures:
    if v / 2 < 90:
        for s in (-1, 1):
            sym(v, s * v / 2, "incident direction parallel to a facet")
# Eq. (4)'s floor boundary: (180 + 2 theta_i) / theta_v = m exactly (in degrees).
for v, ms in [(0.1, [1, 2, 3, 900, 1799]), (1, [1, 2, 3, 90, 180, 181, 359]), (7, [1, 13, 25, 51]),
              (36, [1, 2, 5, 9]), (40, [1, 3, 5, 8]), (60, [1, 2, 3, 4, 5]), (90, [1, 2, 3]), (120, [1, 2])]:
    for m in ms:
        i = (m * v - 180) / 2
        if -90 < i < 90:
            sym(v, i, "(180 + 2 theta_i) / theta_v = %d: Eq. 4's floor boundary" % m)
# Nonsymmetric: facets at 0 deg (flat) and 90 deg (vertical), tiny apertures, grazing light.
for l, r in [(-90, 5), (-90, 45), (-90, 89.99), (-5, 90), (-45, 90), (-89.99, 90), (0, 30), (-30, 0),
             (0, 90), (-90, 0), (0, 0), (-89.995, 89.995), (-45.005, 134.995 - 45)]:
    if not (-90 <= l <= 0 and 0 <= r <= 90):
        continue
    for i in (-89.99, -45, 0, 45, 89.99):
        nonsym(l, r, i, "facet at 0 or 90 deg, or aperture 0.01 deg")

suite = {
    "name": "stress",
    "description": "Numerically hard single-groove cases: apertures 0.01..180 deg (up to 18,000 bounces), grazing light to +-89.99 deg, light parallel to a facet, Eq. 4's floor boundaries, facets at 0 and 90 deg; rays aimed exactly at the apex and rims are traced too. Every ray must be accounted for, no NaN anywhere, and tracer and model must agree.",
    "kind": "table1",
    "groove": {"type": "symmetric", "theta_v_deg": apertures},
    "theta_i_deg": grazing,
    "cases": cases,
    "rays": 1000,
    "sampling": "stratified",
    "seed": 6,
    "probe_vertices": True,
    "thresholds": {"max_l1": 0.003, "mean_l1": 0.0005, "max_theta_o_error_rad": 1e-9},
}
with open("data/suites/stress.json", "w") as f:
    json.dump(suite, f, indent=1)
    f.write("\n")
print("wrote data/suites/stress.json: %d listed cases" % len(cases))
