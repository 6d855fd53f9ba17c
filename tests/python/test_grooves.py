"""Single grooves from Python: the same figures as `vgroove trace --json` / `analytic --json` /
`validate`, to the last digit; vectorized calls equal scalar ones; bad input is a ValueError
with the command line's message; no NaN at the hard cases."""

import json
import math

import numpy as np
import pytest

from conftest import cli_error, cli_json, strip_timing

GROOVES = [
    {"theta_v_deg": 90.0}, {"theta_v_deg": 7.3}, {"theta_v_deg": 0.01}, {"theta_v_deg": 180.0},
    {"theta_l_deg": -30.0, "theta_r_deg": 60.0}, {"theta_l_deg": -85.0, "theta_r_deg": 40.0},
]
ANGLES = [30.0, -61.0, 89.99, 0.0, -89.9]


def flags(groove):
    return [x for k, v in groove.items() for x in (f"--{k.replace('_', '-')}", v)]


@pytest.mark.parametrize("groove", GROOVES)
@pytest.mark.parametrize("theta_i", ANGLES)
def test_analytic_equals_cli_json(vg, groove, theta_i):
    for form in ("corrected", "printed") if "theta_v_deg" in groove else ("corrected",):
        ours = vg.analytic(theta_i, **groove, eq6_form=form)
        theirs = cli_json("analytic", *flags(groove), "--theta-i-deg", theta_i, "--eq6-form", form, "--json")
        assert ours == theirs


@pytest.mark.parametrize("groove", GROOVES)
@pytest.mark.parametrize("sampling,seed", [("stratified", 1), ("random", 5)])
def test_trace_summary_equals_cli_json(vg, groove, sampling, seed):
    rays = 700 if groove.get("theta_v_deg") == 0.01 else 3000
    for theta_i in (30.0, -61.0):
        t = vg.trace(theta_i, rays, **groove, sampling=sampling, seed=seed, max_bounces=50000)
        theirs = cli_json("trace", *flags(groove), "--theta-i-deg", theta_i, "--rays", rays, "--sampling", sampling,
                          "--seed", seed, "--max-bounces", 50000, "--json")
        assert t["summary"] == theirs


def test_trace_rays_reproduce_the_summary(vg):
    # Per-ray arrays: counts per (facet, k) / rays are the rows' fractions exactly; each row's
    # theta_o is its first ray's.
    t = vg.trace(-61.0, 5000, 7.3, sampling="random", seed=5)
    s = t["summary"]
    assert len(t["k"]) == 5000 and t["exit_dir"].shape == (5000, 2)
    esc = t["fate"] == vg.FATES.index("escaped")
    assert s["buckets"]["escaped"] == int(esc.sum())
    for row in s["bounces"]:
        sel = esc & (t["first_facet"] == ("left", "right").index(row["first_facet"])) & (t["k"] == row["k"])
        assert row["fraction"] == sel.sum() / 5000
        first = np.flatnonzero(sel)[0]
        assert abs(t["theta_o_deg"][first] - row["theta_o_deg"]) <= 5e-10
        assert vg.output_deg(np.arctan2(-t["exit_dir"][first, 0], t["exit_dir"][first, 1])) == row["theta_o_deg"]
    # Unit exit directions, zero where the ray did not escape.
    assert np.allclose(np.hypot(*t["exit_dir"][esc].T), 1.0, atol=1e-15)
    assert not t["exit_dir"][~esc].any()
    assert np.all(np.isfinite(t["theta_o_deg"]))


def test_trace_is_deterministic(vg):
    a = vg.trace(20.0, 20000, 13.0, sampling="random", seed=99)
    b = vg.trace(20.0, 20000, 13.0, sampling="random", seed=99)
    for key in ("x", "first_facet", "k", "fate", "exit_dir", "theta_o_deg"):
        assert np.array_equal(a[key], b[key])
    c = vg.trace(20.0, 20000, 13.0, sampling="random", seed=100)
    assert not np.array_equal(a["x"], c["x"])


def test_kaleidoscope_vectorized_equals_scalar_and_the_rows(vg):
    ti = np.array([[-89.9, -45.0, 0.0], [12.5, 60.0, 89.99]])
    v = np.array([[0.01], [120.0]])  # broadcast against ti
    k = vg.kaleidoscope(ti, v)
    assert k["G"].shape == (2, 3, 2, 4) and k["k"].shape == (2, 3, 2)
    for a in range(2):
        for b in range(3):
            one = vg.kaleidoscope(ti[a, b], v[a, 0])
            for key in k:
                assert np.array_equal(k[key][a, b], one[key]), key
            # The rows of `analytic` from the arrays: zones of equal n summed, G f_a / width.
            rows = vg.analytic(ti[a, b], v[a, 0])["bounces"]
            expect = []
            for f in range(2):
                if not one["lit"][f]:
                    continue
                width = sum(one["f_a"][g] * one["G"][g].sum() for g in range(2) if one["lit"][g])
                assert one["fraction"][f].sum() == pytest.approx(one["G"][f].sum() * one["f_a"][f] / width, rel=1e-15)
                for z in range(2):
                    if one["G"][f, z] != 0:
                        expect.append((("left", "right")[f], int(one["n"][f, z]),
                                       float(one["G"][f, z] * one["f_a"][f] / width)))
            assert sorted(expect) == sorted((r["first_facet"], r["k"], r["fraction"]) for r in rows)
    nonsym = vg.kaleidoscope([10.0, -70.0], theta_l_deg=-30.0, theta_r_deg=[60.0, 5.0])
    assert nonsym["n"].shape == (2, 2, 4)
    assert np.array_equal(nonsym["G"][1], vg.kaleidoscope(-70.0, theta_l_deg=-30.0, theta_r_deg=5.0)["G"])
    for key, a in nonsym.items():
        assert np.all(np.isfinite(a)), key


def test_kaleidoscope_is_finite_and_sums_to_one_at_the_hard_cases(vg):
    ti = np.linspace(-89.99, 89.99, 181)
    for v in (1e-3, 0.01, 1.0, 60.0, 179.99, 180.0):
        k = vg.kaleidoscope(ti, v)
        for key, a in k.items():
            assert np.all(np.isfinite(a)), (v, key)
        # The fractions of the beam entering the opening sum to 1 (zones and both facets).
        np.testing.assert_allclose(k["fraction"].sum(axis=(-1, -2)), 1.0, atol=1e-9, err_msg=str(v))


def test_groove_case_equals_the_reports_case(vg, suites, reports):
    with open(reports["table1"]) as f:
        report = json.load(f)
    spec = json.load(open(suites["table1"]))
    for n, case in enumerate(report["cases"]):
        if n % 7:
            continue  # a sample of the cells
        ours = vg.groove_case(case["theta_i_deg"], case["theta_v_deg"], rays=spec["rays"], sampling=spec["sampling"],
                              seed=spec["seed"], stream=n)
        assert ours == case


# Bad input: the command line's message, with the flag named as the keyword.
FLAG_CASES = [
    ({"theta_i_deg": 30.0, "theta_v_deg": 200.0}, ["--theta-v-deg", 200, "--theta-i-deg", 30]),
    ({"theta_i_deg": 30.0, "theta_v_deg": 0.0}, ["--theta-v-deg", 0, "--theta-i-deg", 30]),
    ({"theta_i_deg": 90.0, "theta_v_deg": 60.0}, ["--theta-v-deg", 60, "--theta-i-deg", 90]),
    ({"theta_i_deg": float("nan"), "theta_v_deg": 60.0}, ["--theta-v-deg", 60, "--theta-i-deg", "nan"]),
    ({"theta_i_deg": 10.0, "theta_l_deg": 5.0, "theta_r_deg": 30.0},
     ["--theta-l-deg", 5, "--theta-r-deg", 30, "--theta-i-deg", 10]),
    ({"theta_i_deg": 10.0, "theta_l_deg": -90.0, "theta_r_deg": 90.0},
     ["--theta-l-deg", -90, "--theta-r-deg", 90, "--theta-i-deg", 10]),
    ({"theta_i_deg": 10.0, "theta_v_deg": 60.0, "eq6_form": "printd"},
     ["--theta-v-deg", 60, "--theta-i-deg", 10, "--eq6-form", "printd"]),
]
KEYWORD = {"--theta-v-deg": "theta_v_deg", "--theta-l-deg": "theta_l_deg", "--theta-r-deg": "theta_r_deg",
           "--theta-i-deg": "theta_i_deg", "--eq6-form": "eq6_form", "--rays": "rays", "--seed": "seed",
           "--sampling": "sampling", "--max-bounces": "max_bounces", "--threads": "threads"}


def as_keywords(message):
    for flag, kw in KEYWORD.items():
        message = message.replace(flag, kw)
    return message


@pytest.mark.parametrize("kwargs,args", FLAG_CASES)
def test_bad_groove_input_gives_the_cli_message(vg, kwargs, args):
    expected = as_keywords(cli_error("analytic", *args))
    with pytest.raises(ValueError) as e:
        vg.analytic(**kwargs)
    assert str(e.value) == expected
    with pytest.raises(ValueError) as e:
        vg.kaleidoscope(**{k: v for k, v in kwargs.items()})
    assert str(e.value) == expected


@pytest.mark.parametrize("kwargs,args", [
    ({"rays": 0}, ["--rays", 0]), ({"sampling": "sobol"}, ["--sampling", "sobol"]),
    ({"seed": -1}, ["--seed", -1]), ({"max_bounces": 0}, ["--max-bounces", 0]),
])
def test_bad_trace_input_gives_the_cli_message(vg, kwargs, args):
    expected = as_keywords(cli_error("trace", "--theta-v-deg", 60, "--theta-i-deg", 10, *args))
    with pytest.raises(ValueError) as e:
        vg.trace(10.0, **{"rays": 100, "theta_v_deg": 60.0, **kwargs})
    assert str(e.value) == expected


def test_values_no_flag_can_hold_are_value_errors(vg):
    with pytest.raises(ValueError, match=r"^seed = 9223372036854775808 is out of range \[0, 9223372036854775807\]$"):
        vg.trace(10.0, 10, 60.0, seed=2**63)
    with pytest.raises(ValueError, match=r"^rays = 1.5 must be an integer$"):
        vg.trace(10.0, 1.5, 60.0)
    with pytest.raises(ValueError, match=r"^theta_v_deg\[1\] = 300 is out of range"):
        vg.kaleidoscope(10.0, [60.0, 300.0])
    with pytest.raises(ValueError, match="theta_l_deg needs theta_r_deg"):
        vg.kaleidoscope(10.0, theta_l_deg=-30.0)


def test_narrow_grooves_get_the_command_lines_bounce_limit(vg):
    # A 0.001 deg groove needs up to ceil(180 / 0.001) = 180000 reflections: by default the limit
    # is what the command line sets (validation::default_max_bounces), and every ray leaves.
    t = vg.trace(0.0, 40, 0.001)
    assert np.all(t["fate"] == 0) and t["k"].max() > 100000
    theirs = cli_json("trace", "--theta-v-deg", 0.001, "--theta-i-deg", 0, "--rays", 40, "--json")
    assert strip_timing(t["summary"]) == strip_timing(theirs)
    c = vg.groove_case(0.0, 0.001, rays=40)
    assert c["l1"] < 0.06, c["l1"]  # 2.0 with every ray held at a limit of 100000
    with pytest.raises(ValueError, match=r"^max_bounces = 0 is out of range \[1, 100000000\]$"):
        vg.groove_case(0.0, 0.001, rays=40, max_bounces=0)


def test_numpy_scalars_are_numbers_and_bools_or_complex_are_refused(vg):
    ref = vg.trace(30.0, 50, 60.0, seed=3, sampling="random")
    t = vg.trace(np.float32(30.0), np.int64(50), np.float64(60.0), seed=np.int32(3), sampling="random",
                 max_bounces=np.uint16(1000))
    assert np.array_equal(t["k"], ref["k"]) and np.array_equal(t["x"], ref["x"])
    assert vg.groove_case(np.int64(30), np.int64(60), rays=np.int64(20))["l1"] == vg.groove_case(30, 60, rays=20)["l1"]
    with pytest.raises(ValueError, match=r"^rays = True must be an integer, not a bool$"):
        vg.trace(30.0, True, 60.0)
    with pytest.raises(ValueError, match=r"^theta_i_deg = True must be a real number, not a bool$"):
        vg.trace(True, 10, 60.0)
    with pytest.raises(ValueError, match=r"^theta_i_deg = \(30\+1j\) must be a real number, not complex"):
        vg.trace(30 + 1j, 10, 60.0)
    with pytest.raises(ValueError, match=r"^theta_v_deg = .*60.*1j.* must be a real number, not complex"):
        vg.groove_case(30.0, np.complex128(60 + 1j))
    with pytest.raises(ValueError, match=r"^theta_i_deg has complex values \(dtype complex128\)"):
        vg.kaleidoscope(np.array([10.0, 20.0 + 1e-3j]), 60.0)
