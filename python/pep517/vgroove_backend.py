"""vgroove's PEP 517 build backend (pyproject.toml): `pip install .` builds the Python module with
the project's own CMake build (python/CMakeLists.txt) and packs the installed component "python"
(the package vgroove: the extension module, the pure-Python files, plot.py and the stubs) into a
wheel. It needs nothing from PyPI (no build requirements; Debian 12's cmake, a C++ compiler,
pybind11-dev and python3-dev build it), so that

    python3 -m venv --system-site-packages VENV && VENV/bin/pip install --no-build-isolation .

works offline with Debian's NumPy, matplotlib and pybind11.

Environment:
  VGROOVE_PIP_BUILD_DIR  a build directory to configure once and reuse (incremental builds; a
                         tree configured by scripts/setup.sh, e.g. build/, is reused as it is when
                         it was made for this Python's ABI). Unset: a temporary one, removed after.
  VGROOVE_CMAKE_ARGS     more arguments for a new configuration (as scripts/setup.sh takes them),
                         e.g. "-DCMAKE_CXX_COMPILER_LAUNCHER=ccache".
  CMAKE_BUILD_PARALLEL_LEVEL  the build's parallel jobs (CMake's own variable).
"""

from __future__ import annotations

import base64
import glob
import hashlib
import io
import os
import re
import shlex
import shutil
import subprocess
import sys
import sysconfig
import tarfile
import tempfile
import zipfile

ROOT = os.path.abspath(os.path.join(os.path.dirname(__file__), "..", ".."))
NAME = "vgroove"


class BuildError(RuntimeError):
    pass


def _version():
    with open(os.path.join(ROOT, "CMakeLists.txt")) as f:
        m = re.search(r"project\(vgroove\s+VERSION\s+([0-9.]+)", f.read())
    if not m:
        raise BuildError("vgroove_backend: no `project(vgroove VERSION ...)` in CMakeLists.txt")
    return m.group(1)


def _project():
    try:
        import tomllib
    except ImportError:  # Python < 3.11
        import tomli as tomllib
    with open(os.path.join(ROOT, "pyproject.toml"), "rb") as f:
        return tomllib.load(f)["project"]


def _metadata():
    p = _project()
    lines = ["Metadata-Version: 2.1", f"Name: {NAME}", f"Version: {_version()}", f"Summary: {p['description']}",
             f"License: {p['license']['text']}", f"Requires-Python: {p['requires-python']}"]
    lines += [f"Requires-Dist: {d}" for d in p.get("dependencies", [])]
    for extra, deps in p.get("optional-dependencies", {}).items():
        lines.append(f"Provides-Extra: {extra}")
        lines += [f'Requires-Dist: {d}; extra == "{extra}"' for d in deps]
    return "\n".join(lines) + "\n"


def _tag():
    v = f"{sys.version_info.major}{sys.version_info.minor}"
    if sys.implementation.name != "cpython":
        raise BuildError(f"vgroove_backend: CPython only (this is {sys.implementation.name})")
    plat = sysconfig.get_platform().replace("-", "_").replace(".", "_")
    return f"cp{v}", f"cp{v}{sys.abiflags}", plat


def _dist_info():
    return f"{NAME}-{_version()}.dist-info"


def _wheel_text():
    py, abi, plat = _tag()
    return f"Wheel-Version: 1.0\nGenerator: vgroove_backend\nRoot-Is-Purelib: false\nTag: {py}-{abi}-{plat}\n"


def _run(cmd, what):
    print("vgroove_backend: " + " ".join(shlex.quote(c) for c in cmd), file=sys.stderr, flush=True)
    r = subprocess.run(cmd, stdout=sys.stderr, stderr=sys.stderr)
    if r.returncode != 0:
        raise BuildError(f"vgroove_backend: {what} failed (exit {r.returncode}): {' '.join(cmd)}")


def _cache_value(build, key):
    with open(os.path.join(build, "CMakeCache.txt")) as f:
        for line in f:
            if line.startswith(key + ":"):
                return line.split("=", 1)[1].strip()
    return None


def _ext_suffix(python):
    r = subprocess.run([python, "-c", "import sysconfig; print(sysconfig.get_config_var('EXT_SUFFIX'))"],
                       capture_output=True, text=True)
    return r.stdout.strip() if r.returncode == 0 else None


def _configure(build):
    """A new tree for this Python, or the tree given if it was made for this Python's ABI."""
    ext = sysconfig.get_config_var("EXT_SUFFIX")
    if os.path.exists(os.path.join(build, "CMakeCache.txt")):
        python = _cache_value(build, "Python3_EXECUTABLE")
        theirs = _ext_suffix(python) if python else None
        if theirs != ext:
            raise BuildError(f"vgroove_backend: VGROOVE_PIP_BUILD_DIR={build} was configured for {python} "
                             f"(modules {theirs}); this pip runs {sys.executable} (modules {ext}): give another "
                             "build directory, or none")
        if _cache_value(build, "VGROOVE_PYTHON") in ("OFF", "0", "FALSE", "NO"):
            raise BuildError(f"vgroove_backend: {build} was configured with -DVGROOVE_PYTHON=OFF")
        return
    cmd = ["cmake", "-S", ROOT, "-B", build, "-DCMAKE_BUILD_TYPE=Release", "-DVGROOVE_BUILD_TESTS=OFF",
           "-DVGROOVE_BUILD_BENCH=OFF", "-DVGROOVE_BUILD_APP=OFF", "-DVGROOVE_PYTHON=ON",
           f"-DPython3_EXECUTABLE={sys.executable}"]
    if shutil.which("ninja"):
        cmd += ["-G", "Ninja"]
    cmd += shlex.split(os.environ.get("VGROOVE_CMAKE_ARGS", ""))
    _run(cmd, "configuring")


def _build_package(stage):
    """Builds the module and installs the component "python" under `stage`; returns the package's
    directory there."""
    if shutil.which("cmake") is None:
        raise BuildError("vgroove_backend: cmake is not installed (Debian: apt-get install cmake g++ ninja-build "
                         "pybind11-dev python3-dev libeigen3-dev nlohmann-json3-dev, or scripts/install-deps.sh)")
    given = os.environ.get("VGROOVE_PIP_BUILD_DIR")
    build = os.path.abspath(given) if given else tempfile.mkdtemp(prefix="vgroove-pip-build-")
    try:
        _configure(build)
        _run(["cmake", "--build", build, "--target", "_vgroove", "vgroove_python_files"], "building")
        ext = sysconfig.get_config_var("EXT_SUFFIX")
        if not os.path.exists(os.path.join(build, "python", NAME, "_vgroove" + ext)):
            raise BuildError(f"vgroove_backend: the extension module _vgroove{ext} was not built in {build} (see "
                             "CMake's 'vgroove Python module' line above: pybind11-dev or python3-dev missing?)")
        _run(["cmake", "--install", build, "--component", "python", "--prefix", stage], "installing")
    finally:
        if not given:
            shutil.rmtree(build, ignore_errors=True)
    found = glob.glob(os.path.join(stage, "**", NAME, "__init__.py"), recursive=True)
    if len(found) != 1:
        raise BuildError(f"vgroove_backend: the install put {len(found)} packages vgroove under {stage}")
    return os.path.dirname(found[0])


def _record_line(arcname, data):
    digest = base64.urlsafe_b64encode(hashlib.sha256(data).digest()).rstrip(b"=").decode()
    return f"{arcname},sha256={digest},{len(data)}"


# PEP 517 hooks.

def get_requires_for_build_wheel(config_settings=None):
    return []


def get_requires_for_build_sdist(config_settings=None):
    return []


def prepare_metadata_for_build_wheel(metadata_directory, config_settings=None):
    d = os.path.join(metadata_directory, _dist_info())
    os.makedirs(d, exist_ok=True)
    with open(os.path.join(d, "METADATA"), "w") as f:
        f.write(_metadata())
    with open(os.path.join(d, "WHEEL"), "w") as f:
        f.write(_wheel_text())
    return _dist_info()


def build_wheel(wheel_directory, config_settings=None, metadata_directory=None):
    py, abi, plat = _tag()
    name = f"{NAME}-{_version()}-{py}-{abi}-{plat}.whl"
    with tempfile.TemporaryDirectory(prefix="vgroove-pip-stage-") as stage:
        pkg = _build_package(stage)
        files = []
        for dirpath, _, filenames in os.walk(pkg):
            for fn in sorted(filenames):
                if fn.endswith(".pyc"):
                    continue
                path = os.path.join(dirpath, fn)
                files.append((os.path.join(NAME, os.path.relpath(path, pkg)), path))
        record = []
        with zipfile.ZipFile(os.path.join(wheel_directory, name), "w", zipfile.ZIP_DEFLATED) as z:
            for arcname, path in sorted(files):
                with open(path, "rb") as f:
                    data = f.read()
                z.writestr(zipfile.ZipInfo.from_file(path, arcname), data, zipfile.ZIP_DEFLATED)
                record.append(_record_line(arcname, data))
            info = _dist_info()
            for fn, text in (("METADATA", _metadata()), ("WHEEL", _wheel_text())):
                data = text.encode()
                z.writestr(f"{info}/{fn}", data)
                record.append(_record_line(f"{info}/{fn}", data))
            record.append(f"{info}/RECORD,,")
            z.writestr(f"{info}/RECORD", "\n".join(record) + "\n")
    return name


def build_sdist(sdist_directory, config_settings=None):
    """The files git tracks, as NAME-VERSION.tar.gz."""
    r = subprocess.run(["git", "-C", ROOT, "ls-files", "-z"], capture_output=True)
    if r.returncode != 0:
        raise BuildError("vgroove_backend: an sdist is made from a git checkout (git ls-files failed)")
    base = f"{NAME}-{_version()}"
    name = base + ".tar.gz"
    with tarfile.open(os.path.join(sdist_directory, name), "w:gz", format=tarfile.PAX_FORMAT) as t:
        data = _metadata().encode()
        info = tarfile.TarInfo(f"{base}/PKG-INFO")
        info.size = len(data)
        t.addfile(info, io.BytesIO(data))
        for rel in sorted(p for p in r.stdout.decode().split("\0") if p):
            t.add(os.path.join(ROOT, rel), arcname=f"{base}/{rel}", recursive=False)
    return name
