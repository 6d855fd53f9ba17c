"""validate() from Python: the report `vgroove validate --out` writes, field for field (wall
times aside), for every suite kind; a bad suite is a ValueError with the command line's line."""

import json

import pytest

from conftest import cli_error, strip_timing, write_json


@pytest.mark.parametrize("kind", ["table1", "table1_set", "brdf", "furnace", "table2"])
def test_validate_equals_the_cli_report(vg, suites, reports, kind):
    ours = vg.validate(suites[kind], threads=1)
    with open(reports[kind]) as f:
        theirs = json.load(f)
    # The thread count is reported; the figures do not depend on it.
    ours["threads"] = theirs["threads"]
    for s in ours.get("suites", []):
        s["threads"] = theirs["threads"]
    assert strip_timing(ours) == strip_timing(theirs)


def test_overrides(vg, suites):
    a = vg.validate(suites["table1"], rays=50, seed=3, sampling="stratified", eq6_form="printed")
    assert a["rays_per_facet"] == 50 and a["seed"] == 3 and a["sampling"] == "stratified"
    assert a["eq6_form"] == "printed"


@pytest.mark.parametrize("kwargs,flags", [
    ({"rays": 0}, ["--rays", 0]),
    ({"seed": -4}, ["--seed", -4]),
    ({"threads": 2000}, ["--threads", 2000]),
    ({"sampling": "sobol"}, ["--sampling", "sobol"]),
])
def test_bad_overrides_give_the_cli_message(vg, suites, kwargs, flags):
    expected = cli_error("validate", suites["table1"], *flags)
    name = flags[0][2:].replace("-", "_")
    with pytest.raises(ValueError) as e:
        vg.validate(suites["table1"], **kwargs)
    assert str(e.value) == expected.replace(flags[0], name)


def test_bad_suites_give_the_cli_message(vg, tmp_path):
    cases = {
        "missing.json": None,
        "syntax.json": "{\"name\": ",
        "unknown_key.json": {"name": "x", "kind": "table1", "roughnes": 1},
        "range.json": {"name": "x", "kind": "brdf", "ndf": ["ggx"], "alpha": [3.0], "theta_i_deg": [0],
                       "dimensions": ["3d"], "rays": 10, "grooves": 10,
                       "thresholds": {"sigmas": 5, "model_tolerance": {"flatland": 0, "3d": 0}}},
        "rough_sampling.json": dict(name="x"),
    }
    for name, content in cases.items():
        path = tmp_path / name
        if isinstance(content, str):
            path.write_text(content)
        elif content is not None:
            write_json(path, content)
        expected = cli_error("validate", path)
        with pytest.raises(ValueError) as e:
            vg.validate(str(path))
        assert str(e.value) == expected, name
    # An option that does not apply to the suite's kind.
    brdf = tmp_path / "range.json"
    write_json(brdf, {**json.loads(brdf.read_text()), "alpha": [0.5]})
    expected = cli_error("validate", brdf, "--sampling", "random")
    with pytest.raises(ValueError) as e:
        vg.validate(str(brdf), sampling="random")
    assert str(e.value) == expected.replace("--sampling", "sampling")


def test_ctrl_c_stops_a_long_run(vg, tmp_path):
    # A run of minutes (Fig. 11 at full size) stops within seconds of SIGINT with KeyboardInterrupt.
    import signal
    import subprocess
    import sys
    import time
    from conftest import SOURCE
    code = ("import signal, sys, time, vgroove\n"
            "signal.signal(signal.SIGINT, signal.default_int_handler)\n"
            "print('started', flush=True)\n"
            "t = time.monotonic()\n"
            "try:\n"
            f"    vgroove.validate({SOURCE + '/data/suites/fig11.json'!r}, threads=2)\n"
            "except KeyboardInterrupt:\n"
            "    print('interrupted', flush=True)\n")
    p = subprocess.Popen([sys.executable, "-c", code], stdout=subprocess.PIPE, text=True)
    assert p.stdout.readline().strip() == "started"
    time.sleep(1.0)
    t0 = time.monotonic()
    p.send_signal(signal.SIGINT)
    out, _ = p.communicate(timeout=60)
    assert out.strip() == "interrupted"
    assert time.monotonic() - t0 < 30  # a case in flight finishes (about a second on an idle machine)
