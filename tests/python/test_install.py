"""The package from an installed prefix: `cmake --install` of the build tree into a temporary
prefix, then `import vgroove` with that prefix's Python directory on the path (and nothing of the
build tree), the installed `vgroove plot` finding its plot script there, the line the install
prints (where the package went) and the .pth file it writes (a venv of another prefix imports the
package through it); and what a broken install says (no NumPy, a module built for another Python,
no module)."""

import os
import pathlib
import shutil
import subprocess
import sys
import venv

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
    INSTALL_OUTPUT[str(p)] = r.stdout
    return p


INSTALL_OUTPUT = {}


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


def test_the_install_says_where_the_package_went_and_a_pth_file_names_it(prefix, tmp_path):
    if not HAVE_MODULE:
        pytest.skip("built without the Python module")
    pydir = prefix / cmake_cache("VGROOVE_PYTHON_INSTALL_DIR")
    pth = prefix / "share" / "vgroove" / "vgroove.pth"
    line = (f"-- vgroove Python package: {pydir}/vgroove (import it with PYTHONPATH={pydir}, or copy {pth} into a "
            "Python's site-packages)")
    assert line in INSTALL_OUTPUT[str(prefix)].splitlines(), INSTALL_OUTPUT[str(prefix)]
    assert pth.read_text() == f"{pydir}\n"
    # A venv of its own (another prefix, Debian's NumPy through --system-site-packages) imports the
    # installed package once the .pth file is in its site-packages; without it, it cannot.
    env_dir = tmp_path / "venv"
    venv.create(env_dir, system_site_packages=True, with_pip=False)
    vpython = str(env_dir / "bin" / "python")
    site = subprocess.run([vpython, "-c", "import sysconfig; print(sysconfig.get_paths()['purelib'])"],
                          capture_output=True, text=True).stdout.strip()
    env = {k: v for k, v in os.environ.items() if k != "PYTHONPATH"}
    code = "import vgroove; print(vgroove.__file__)"
    before = subprocess.run([vpython, "-c", code], capture_output=True, text=True, env=env, cwd=str(tmp_path))
    assert before.returncode != 0 and "No module named 'vgroove'" in before.stderr
    shutil.copy(pth, site)
    after = subprocess.run([vpython, "-c", code], capture_output=True, text=True, env=env, cwd=str(tmp_path))
    assert after.returncode == 0, after.stderr
    assert after.stdout.strip() == str(pydir / "vgroove" / "__init__.py")


def import_error(python, pkg_parent, prelude=""):
    """What `import vgroove` raises with pkg_parent on the path (one line), or None."""
    code = prelude + "import vgroove\n"
    env = {k: v for k, v in os.environ.items() if k != "PYTHONPATH"}
    env["PYTHONPATH"] = str(pkg_parent)
    r = subprocess.run([python, "-c", code], capture_output=True, text=True, env=env)
    if r.returncode == 0:
        return None
    return r.stderr.strip().splitlines()[-1]


def test_a_broken_install_says_what_is_missing(vg, tmp_path):
    src = os.path.dirname(vg.__file__)
    parent = tmp_path / "site"
    shutil.copytree(src, parent / "vgroove", ignore=shutil.ignore_patterns("__pycache__"))
    assert import_error(sys.executable, parent) is None
    # No NumPy for this interpreter.
    msg = import_error(sys.executable, parent, "import sys; sys.modules['numpy'] = None\n")
    assert msg.startswith(f"ImportError: vgroove needs NumPy, which this Python ({sys.executable}, "), msg
    assert "apt-get install python3-numpy" in msg
    # The extension module built for another Python (its file name says which).
    so = next(f for f in os.listdir(parent / "vgroove") if f.startswith("_vgroove.cpython-"))
    other = "_vgroove.cpython-39-x86_64-linux-gnu.so"
    os.rename(parent / "vgroove" / so, parent / "vgroove" / other)
    msg = import_error(sys.executable, parent)
    assert f"its extension module is {other}, built for another Python: this one ({sys.executable}" in msg, msg
    assert "-DPython3_EXECUTABLE=" in msg
    # No extension module at all.
    os.unlink(parent / "vgroove" / other)
    msg = import_error(sys.executable, parent)
    assert "its extension module vgroove._vgroove is not there" in msg, msg
