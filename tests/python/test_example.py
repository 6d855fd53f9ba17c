"""examples/python/check_my_brdf.py runs (on a small ray count) and says what it should: plain
Cook-Torrance fails at alpha = 1 (it loses energy); the output files are a report and a PNG."""

import json
import os
import subprocess
import sys

from conftest import SOURCE

PNG_SIGNATURE = b"\x89PNG\r\n\x1a\n"


def test_check_my_brdf_example(vg, tmp_path):
    script = os.path.join(SOURCE, "examples", "python", "check_my_brdf.py")
    r = subprocess.run([sys.executable, script, "--rays", "20000", "--grooves", "20000", "--theta-i-deg", "0,60",
                        "--out", str(tmp_path)], capture_output=True, text=True, timeout=240)
    assert r.returncode == 0, r.stderr
    assert "Cook-Torrance: FAIL" in r.stdout
    with open(tmp_path / "check_my_brdf.json") as f:
        reports = json.load(f)
    ct, kc = reports["Cook-Torrance"], reports["Cook-Torrance + Kulla-Conty"]
    assert not ct["pass"]
    # The compensation restores the albedo to within a few per cent of the traced 1.
    for c, k in zip(ct["cases"], kc["cases"]):
        assert abs(k["albedo_model"] - k["albedo_sim"]) < abs(c["albedo_model"] - c["albedo_sim"])
    assert open(tmp_path / "check_my_brdf.png", "rb").read(8) == PNG_SIGNATURE
