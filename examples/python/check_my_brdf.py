#!/usr/bin/env python3
"""Check a BRDF of your own against vgroove's exact simulation, and see where it fails.

The BRDF here is Cook-Torrance (GGX, V-cavity G, F = 1) with a Kulla-Conty style energy
compensation term (Kulla and Conty 2017, "Revisiting Physically Based Shading at Imageworks"):

    f_ms(wi, wo) = (1 - E(mu_i)) (1 - E(mu_o)) / (pi (1 - E_avg)),

where E(mu) is Cook-Torrance's directional albedo (vgroove.BRDF("cook-torrance", ...).albedo) and
E_avg = 2 int E(mu) mu dmu. It restores the energy Cook-Torrance loses, but spreads it as a
diffuse lobe; light that really bounces between the facets of a V-groove leaves in particular
directions (vgroove's Eq. 16). check_brdf traces a
procedural V-groove surface of the same NDF and says per incident angle whether the BRDF's lobe
and albedo agree with the traced light within what the sample count allows.

    PYTHONPATH=build/python /usr/bin/python3 examples/python/check_my_brdf.py [--rays N] [--alpha A] [--out DIR]

Writes DIR/check_my_brdf.json (the check_brdf report of both BRDFs) and DIR/check_my_brdf.png.
"""

import argparse
import json
import os

import numpy as np

import vgroove as vg


def cook_torrance(alpha):
    return vg.BRDF("cook-torrance", "ggx", alpha).eval


def kulla_conty(alpha, table=64):
    """Cook-Torrance plus the Kulla-Conty multiple-scattering lobe, vectorized over directions.
    E(mu), Cook-Torrance's directional albedo, is exact (vgroove.BRDF.albedo: its lobe's total)."""
    ct = vg.BRDF("cook-torrance", "ggx", alpha)
    mu = np.linspace(np.cos(np.radians(vg.RANGES["max_surface_theta_i_deg"])), 1.0, table)  # theta_i <= 89.9 deg
    E = ct.albedo(vg.direction(np.degrees(np.arccos(mu)), 180.0))
    E_avg = 2.0 * np.trapz(E * mu, mu)

    def f(wi, wo):
        ei = np.interp(np.clip(wi[:, 2], 0, 1), mu, E)
        eo = np.interp(np.clip(wo[:, 2], 0, 1), mu, E)
        ms = (1.0 - ei) * (1.0 - eo) / (np.pi * (1.0 - E_avg))
        return ct.eval(wi, wo) + np.where((wi[:, 2] > 0) & (wo[:, 2] > 0), ms, 0.0)

    return f


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--rays", type=int, default=1_000_000, help="rays per incident angle")
    ap.add_argument("--grooves", type=int, default=250_000)
    ap.add_argument("--alpha", type=float, default=1.0)
    ap.add_argument("--theta-i-deg", default="0,20,40,60,80")
    ap.add_argument("--out", default=".")
    args = ap.parse_args()
    theta_i = [float(t) for t in args.theta_i_deg.split(",")]
    common = dict(ndf="ggx", alpha=args.alpha, theta_i_deg=theta_i, rays=args.rays, grooves=args.grooves)
    reports = {
        "Cook-Torrance": vg.check_brdf(cook_torrance(args.alpha), name="cook_torrance", **common),
        "Cook-Torrance + Kulla-Conty": vg.check_brdf(kulla_conty(args.alpha), name="kulla_conty", **common),
    }
    for name, r in reports.items():
        print(f"{name}: {'PASS' if r['pass'] else 'FAIL'}")
        for c in r["cases"]:
            print(f"  theta_i {c['theta_i_deg']:5.1f} deg: albedo {c['albedo_model']:.4f} (traced "
                  f"{c['albedo_sim']:.4f} +- {c['albedo_threshold']:.4f}), lobe L1 {c['l1']:.4f} "
                  f"(threshold {c['l1_threshold']:.4f}) {'ok' if c['pass'] else 'FAILS'}")
    os.makedirs(args.out, exist_ok=True)
    with open(os.path.join(args.out, "check_my_brdf.json"), "w") as f:
        json.dump(reports, f, indent=1)

    import matplotlib
    matplotlib.use("Agg")
    from matplotlib.figure import Figure
    fig = Figure(figsize=(11, 4.2), layout="constrained")
    a1, a2 = fig.subplots(1, 2)
    for (name, r), marker in zip(reports.items(), "os"):
        t = [c["theta_i_deg"] for c in r["cases"]]
        a1.plot(t, [c["albedo_model"] for c in r["cases"]], marker + "-", label=name)
        a2.plot(t, [c["l1"] / c["l1_threshold"] for c in r["cases"]], marker + "-", label=name)
    t = [c["theta_i_deg"] for c in reports["Cook-Torrance"]["cases"]]
    a1.plot(t, [c["albedo_sim"] for c in reports["Cook-Torrance"]["cases"]], "k^", label="traced V-grooves")
    a1.set_xlabel("theta_i (deg)")
    a1.set_ylabel("albedo (fraction of the incident flux)")
    a1.legend(fontsize=8)
    a2.axhline(1.0, color="red", lw=1)
    a2.set_yscale("log")
    a2.set_xlabel("theta_i (deg)")
    a2.set_ylabel("lobe L1 / threshold (> 1: fails)")
    a2.legend(fontsize=8)
    fig.suptitle(f"check_brdf: GGX alpha {args.alpha:g} against exact V-groove tracing, {args.rays} rays per angle")
    fig.savefig(os.path.join(args.out, "check_my_brdf.png"))
    print(f"wrote {args.out}/check_my_brdf.json and {args.out}/check_my_brdf.png")


if __name__ == "__main__":
    main()
