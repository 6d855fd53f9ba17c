"""`pip install --no-build-isolation .` in a new venv made with `python3 -m venv
--system-site-packages`, offline (--no-index), with Debian's pybind11, NumPy and matplotlib: the
package lands in the venv, imports there without the build tree, computes what the build tree's
module computes, and draws a report's plot (python -m vgroove.plot).

VGROOVE_PIP_TEST_BUILD selects the build the backend drives (pyproject.toml, python/pep517/):
  reuse   the ctest build tree (VGROOVE_PIP_BUILD_DIR=build: the module is up to date, so the
          install takes seconds; the default test run, ctest python.test_pip_install)
  fresh   a new build directory from scratch (minutes; ctest -L long, python.test_pip_install_fresh;
          VGROOVE_CMAKE_ARGS, e.g. ccache, is passed on)
"""

import json
import os
import shutil
import subprocess
import sys
import venv

import pytest

from conftest import BIN, HAVE_MODULE, SOURCE

BUILD = os.path.dirname(BIN)
MODE = os.environ.get("VGROOVE_PIP_TEST_BUILD", "reuse")


@pytest.fixture(scope="module")
def installed(tmp_path_factory):
    if not HAVE_MODULE:
        pytest.skip("built without the Python module")
    if MODE == "reuse" and not os.path.exists(os.path.join(BUILD, "CMakeCache.txt")):
        pytest.skip("no build tree beside VGROOVE_BIN to reuse")
    d = tmp_path_factory.mktemp("venv")
    # Debian's interpreter (the one the module is built for) makes the venv, with its packages.
    python = sys.executable
    r = subprocess.run([python, "-m", "venv", "--system-site-packages", str(d / "venv")], capture_output=True,
                       text=True)
    assert r.returncode == 0, r.stderr
    vpython = str(d / "venv" / "bin" / "python")
    env = {k: v for k, v in os.environ.items() if k not in ("PYTHONPATH", "VGROOVE_PIP_BUILD_DIR")}
    env["PIP_NO_INDEX"] = "1"  # offline: nothing may come from PyPI
    env["PIP_DISABLE_PIP_VERSION_CHECK"] = "1"
    if MODE == "reuse":
        env["VGROOVE_PIP_BUILD_DIR"] = BUILD
    r = subprocess.run([vpython, "-m", "pip", "install", "--no-build-isolation", "--no-index", "-v", SOURCE],
                       capture_output=True, text=True, env=env, cwd=str(d), timeout=3000)
    assert r.returncode == 0, r.stdout[-4000:] + r.stderr[-4000:]
    return vpython, env, r


def run(installed, code, *args):
    vpython, env, _ = installed
    r = subprocess.run([vpython, "-c", code, *map(str, args)], capture_output=True, text=True, env=env,
                       cwd=os.path.dirname(vpython))
    assert r.returncode == 0, r.stderr
    return r.stdout


def test_the_package_is_in_the_venv_and_imports_without_the_build_tree(installed, vg):
    vpython = installed[0]
    venv_root = os.path.dirname(os.path.dirname(vpython))
    out = json.loads(run(installed, "import json, sys, vgroove, numpy\n"
                                    "print(json.dumps([vgroove.__file__, vgroove.__version__, numpy.__file__, "
                                    "sorted(p for p in sys.path if 'build' in p)]))"))
    assert out[0].startswith(venv_root), out[0]
    assert out[1] == vg.__version__
    assert out[2].startswith("/usr/lib/python3/dist-packages"), out[2]  # Debian's NumPy
    assert not any(p.startswith(BUILD) for p in out[3]), out[3]
    files = os.listdir(os.path.dirname(out[0]))
    for f in ("__init__.py", "__init__.pyi", "_vgroove.pyi", "py.typed", "plot.py", "_brdf.py"):
        assert f in files, f
    assert any(f.startswith("_vgroove.cpython-") for f in files), files
    # pip knows it (metadata from pyproject.toml and CMakeLists.txt's version).
    show = subprocess.run([vpython, "-m", "pip", "show", "vgroove"], capture_output=True, text=True,
                          env=installed[1]).stdout
    assert f"Version: {vg.__version__}" in show and "Requires: numpy" in show


def test_the_installed_module_computes_what_the_build_trees_does(installed, vg):
    code = ("import vgroove, numpy as np\n"
            "f = vgroove.BRDF('vgroove', 'ggx', 0.5)\n"
            "wi, wo = vgroove.direction(30, 180), vgroove.direction(np.linspace(0, 89, 7), 20)\n"
            "print(repr(f.eval(wi, wo).tolist()))\nprint(repr(f.albedo(wi).tolist()))\n")
    f = vg.BRDF("vgroove", "ggx", 0.5)
    import numpy as np
    wi, wo = vg.direction(30, 180), vg.direction(np.linspace(0, 89, 7), 20)
    assert run(installed, code).splitlines() == [repr(f.eval(wi, wo).tolist()), repr(f.albedo(wi).tolist())]


def test_the_installed_package_draws_a_plot(installed, reports, tmp_path):
    out = tmp_path / "t2"
    vpython, env, _ = installed
    r = subprocess.run([vpython, "-m", "vgroove.plot", reports["table2"], "--out", str(out)], capture_output=True,
                       text=True, env=dict(env, MPLBACKEND="Agg"))
    assert r.returncode == 0, r.stderr
    assert (tmp_path / "t2.png").read_bytes().startswith(b"\x89PNG\r\n\x1a\n")


def test_the_backend_refuses_a_build_tree_of_another_python(tmp_path):
    # A tree configured for another interpreter's modules is named, not silently rebuilt.
    if MODE != "reuse" or not os.path.exists(os.path.join(BUILD, "CMakeCache.txt")):
        pytest.skip("reuse mode only")
    fake = tmp_path / "other"
    fake.mkdir()
    with open(os.path.join(BUILD, "CMakeCache.txt")) as f:
        cache = f.read()
    python = shutil.which("python2") or "/bin/false"
    (fake / "CMakeCache.txt").write_text(
        "\n".join(line if not line.startswith("Python3_EXECUTABLE:") else f"Python3_EXECUTABLE:FILEPATH={python}"
                  for line in cache.splitlines()))
    code = ("import sys; sys.path.insert(0, sys.argv[1]); import vgroove_backend as b\n"
            "try:\n    b._configure(sys.argv[2])\nexcept b.BuildError as e:\n    print(e)\n")
    r = subprocess.run([sys.executable, "-c", code, os.path.join(SOURCE, "python", "pep517"), str(fake)],
                       capture_output=True, text=True)
    assert r.returncode == 0, r.stderr
    assert f"was configured for {python}" in r.stdout and f"this pip runs {sys.executable}" in r.stdout, r.stdout
