"""The package from an installed prefix: `cmake --install` of the build tree into a temporary
prefix, then `import vgroove` with that prefix's Python directory on the path (and nothing of the
build tree), and the installed `vgroove plot` finding its plot script there."""

import os
import pathlib
import shutil
import subprocess
import sys

import pytest

from conftest import BIN, HAVE_MODULE, SOURCE

BUILD = os.path.dirname(BIN)


def cmake_cache(key):
    with open(os.path.join(BUILD, "CMakeCache.txt")) as f:
        for line in f:
            if line.startswith(key + ":"):
                return line.split("=", 1)[1].strip()
    return None


@pytest.fixture(scope="module")
def prefix(tmp_path_factory):
    cmake = shutil.which("cmake")
    if cmake is None or not os.path.exists(os.path.join(BUILD, "cmake_install.cmake")):
        pytest.skip("no cmake or no build tree beside VGROOVE_BIN")
    p = tmp_path_factory.mktemp("prefix")
    r = subprocess.run([cmake, "--install", BUILD, "--prefix", str(p)], capture_output=True, text=True)
    assert r.returncode == 0, r.stderr
    return p


def test_import_from_the_installed_prefix(prefix):
    if not HAVE_MODULE:
        pytest.skip("built without the Python module")
    pydir = prefix / cmake_cache("VGROOVE_PYTHON_INSTALL_DIR")
    assert (pydir / "vgroove" / "__init__.py").is_file() and (pydir / "vgroove" / "plot.py").is_file()
    code = ("import numpy as np, vgroove, sys\n"
            "assert vgroove.__file__.startswith(sys.argv[1]), vgroove.__file__\n"
            "wi = vgroove.direction(30, 180); wo = vgroove.direction(40, 0)\n"
            "print(float(vgroove.brdf('vgroove', 'ggx', 0.5, wi, wo)))\n"
            "print(float(vgroove.pdf('ggx', 0.5, wo, wi=wi)))\n")
    env = {k: v for k, v in os.environ.items() if k != "PYTHONPATH"}
    env["PYTHONPATH"] = str(pydir)
    r = subprocess.run([sys.executable, "-c", code, str(pydir)], capture_output=True, text=True, env=env,
                       cwd=str(prefix))
    assert r.returncode == 0, r.stderr
    import vgroove
    wi, wo = vgroove.direction(30, 180), vgroove.direction(40, 0)
    assert r.stdout.split() == [repr(float(vgroove.brdf("vgroove", "ggx", 0.5, wi, wo))),
                                repr(float(vgroove.pdf("ggx", 0.5, wo, wi=wi)))]


def test_installed_command_line_plots(prefix, reports, tmp_path):
    out = tmp_path / "t2"
    env = {k: v for k, v in os.environ.items() if k not in ("PYTHONPATH", "VGROOVE_PLOT")}
    r = subprocess.run([str(prefix / "bin" / "vgroove"), "plot", reports["table2"], "--out", str(out)],
                       capture_output=True, text=True, env=env)
    assert r.returncode == 0, r.stderr
    assert (tmp_path / "t2.png").read_bytes().startswith(b"\x89PNG\r\n\x1a\n")
    assert SOURCE  # the source tree is not needed by the installed package


def test_the_schemas_are_installed(prefix):
    schemas = prefix / "share" / "vgroove" / "schemas"
    names = sorted(p.name for p in schemas.glob("*.schema.json"))
    source = pathlib.Path(SOURCE) / "docs" / "schemas"
    assert names == sorted(p.name for p in source.glob("*.schema.json")) and names, names
    for p in schemas.glob("*.schema.json"):
        assert p.read_bytes() == (source / p.name).read_bytes()
