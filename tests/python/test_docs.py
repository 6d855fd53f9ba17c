"""Docs that stay true: the ranges the docstrings state are validation/ranges.h's (read here from
the header itself) and are the ones enforced; every public function, class and method has a
numpydoc docstring whose Examples run (doctest); the README's Python section uses the API as it
is (its snippet runs and prints what it says) and its quick start names the JSON schemas."""

import doctest
import inspect
import os
import re

import numpy as np
import pytest

from conftest import SOURCE

RANGES_H = os.path.join(SOURCE, "validation", "ranges.h")
README = os.path.join(SOURCE, "README.md")

# RANGES keys and the constants of validation/ranges.h they export.
HEADER_NAMES = {
    "min_aperture_deg": "kMinApertureDeg", "max_theta_i_deg": "kMaxThetaIDeg",
    "max_surface_theta_i_deg": "kMaxSurfaceThetaIDeg", "min_alpha": "kMinAlpha", "max_alpha": "kMaxAlpha",
    "max_rays": "kMaxRays", "max_seed": "kMaxSeed", "max_grooves": "kMaxGrooves",
    "default_max_bounces": "kDefaultMaxBounces", "max_bounces": "kMaxBounces", "max_threads": "kMaxThreads",
    "max_flatland_k": "kMaxFlatlandBrdfK", "max_nonsymmetric_k": "kMaxNonsymmetricBrdfK",
    "min_histogram_k": "kMinHistogramK", "max_histogram_k": "kMaxHistogramK", "max_flatland_bins": "kMaxFlatlandBins",
    "max_theta_bins": "kMaxThetaBins", "max_phi_bins": "kMaxPhiBins", "max_sampler_k": "kMaxSamplerK",
    "max_fresnel_eta": "kMaxFresnelEta", "max_fresnel_kappa": "kMaxFresnelKappa",
    "min_glass_eta": "kMinGlassEta", "max_glass_eta": "kMaxGlassEta", "max_glass_grooves": "kMaxGlassGrooves",
    "min_mu": "kMinMu", "max_energy_rays": "kMaxEnergyRays", "max_energy_k": "kMaxEnergyK",
}


def header_constants():
    """name -> value of every `inline constexpr T kName = VALUE;` in validation/ranges.h."""
    with open(RANGES_H) as f:
        text = f.read()
    out = {}
    for name, value in re.findall(r"inline constexpr [\w: ]+? (k\w+) = ([^;]+);", text):
        value = re.sub(r"(?<=\d)[uUlL]+$", "", value.replace("'", "").strip())  # 10'000LL -> 10000
        if value == "std::numeric_limits<long long>::max()":
            out[name] = 2 ** 63 - 1
        else:
            out[name] = float(value) if re.search(r"[.eE]", value) else int(value)
    return out


def test_the_ranges_are_the_headers(vg):
    h = header_constants()
    assert set(vg.RANGES) == set(HEADER_NAMES) | {"unit_tolerance"}
    for key, const in HEADER_NAMES.items():
        assert vg.RANGES[key] == h[const], key
    # Power: the parse reads the numbers (a changed header would be seen).
    assert h["kMaxAlpha"] == 2.0 and h["kMaxRays"] == 10 ** 9 and h["kMaxSeed"] == 2 ** 63 - 1


def every_docstring(vg):
    objs = [vg]
    for name in vg.__all__:
        obj = getattr(vg, name)
        if callable(obj):
            objs.append(obj)
            if inspect.isclass(obj):
                objs += [getattr(obj, m) for m, v in vars(obj).items() if not m.startswith("_") and
                         (callable(v) or isinstance(v, (classmethod, property)))]
    return [(o, inspect.getdoc(o) or "") for o in objs]


def test_no_docstring_names_a_range_the_module_does_not_fill(vg):
    for obj, doc in every_docstring(vg):
        assert "$" not in doc, (obj, re.findall(r"\$\w+", doc))


# Each range the module docstring states, and a call just outside it that must be refused with
# a message naming the same interval, and one at its edge that must be taken.
STATED = [
    ("[0.001, 180]", "vg.trace(10.0, 10, 0.0009)", "vg.trace(10.0, 10, 0.001)"),
    ("[-89.999, 89.999]", "vg.trace(89.9991, 10, 60.0)", "vg.trace(89.999, 10, 60.0)"),
    ("[0.01, 2]", "vg.BRDF(alpha=2.0001)", "vg.BRDF(alpha=2.0)"),
    ("[0, 89.9]", "vg.sample('ggx', 0.5, vg.uniforms(1), theta_i_deg=89.91)",
     "vg.sample('ggx', 0.5, vg.uniforms(1), theta_i_deg=89.9)"),
    ("[0, 1000]", "vg.lobe('vgroove', 'ggx', 0.5, 30, theta_bins=2, phi_bins=2, max_k=1001)",
     "vg.lobe('vgroove', 'ggx', 0.5, 30, theta_bins=2, phi_bins=2, max_k=1000)"),
    ("[0, 1024]", "vg.brdf('vgroove', 'ggx', 0.5, [0, 0, 1], [0, 0, 1], threads=1025)",
     "vg.brdf('vgroove', 'ggx', 0.5, [0, 0, 1], [0, 0, 1], threads=1024)"),
    ("1e-06", "vg.brdf('vgroove', 'ggx', 0.5, [0, 0, 1.0000011], [0, 0, 1])",
     "vg.brdf('vgroove', 'ggx', 0.5, [0, 0, 1.0000009], [0, 0, 1])"),
]


@pytest.mark.parametrize("interval,outside,edge", STATED)
def test_the_module_docstring_states_the_enforced_ranges(vg, interval, outside, edge):
    assert interval in vg.__doc__
    with pytest.raises(ValueError) as e:
        eval(outside, {"vg": vg})
    assert interval in str(e.value), str(e.value)
    eval(edge, {"vg": vg})
    # What the issue found stated and not enforced is gone.
    assert "1e-6, 180" not in vg.__doc__ and "(0, 2]" not in vg.__doc__


SECTIONS = ("Parameters", "Returns", "Raises", "Examples")


def test_every_public_callable_has_a_numpydoc_docstring(vg):
    missing = []
    for obj, doc in every_docstring(vg):
        if obj is vg or isinstance(obj, property):
            continue
        if inspect.isclass(obj):
            wanted = ("Attributes", "Examples") if hasattr(obj, "__dataclass_fields__") else (
                ("Parameters", "Raises", "Examples") if obj is vg.BRDF else ("Examples",) if obj.__doc__ else ())
            if obj is vg.TqdmProgress:
                wanted = ()
        else:
            params = [p for p in inspect.signature(obj).parameters if p not in ("self", "cls")]
            wanted = SECTIONS if params else ("Returns", "Raises", "Examples")
            if getattr(obj, "__name__", "") in ("as_dict", "from_dict"):
                wanted = ()
        for s in wanted:
            if not re.search(rf"^{s}\n-{{{len(s)}}}$", doc, re.M):
                missing.append((getattr(obj, "__qualname__", obj), s))
        if "Parameters" in wanted:
            documented = set(re.findall(r"^(\*{0,2}[a-z_]\w*)(?: :|,|$)", doc.split("Returns")[0], re.M))
            documented |= {n.strip() for line in re.findall(r"^([a-z_][\w, ]*)(?: :|$)", doc, re.M)
                           for n in line.split(",")}
            params = [p.name if p.kind != p.VAR_KEYWORD else "**" + p.name
                      for p in inspect.signature(obj).parameters.values() if p.name not in ("self", "cls")]
            missing += [(obj.__qualname__, "parameter " + p) for p in params if p not in documented]
    assert missing == []


def test_the_examples_run(vg):
    vgroove = vg
    finder = doctest.DocTestFinder()
    runner = doctest.DocTestRunner(optionflags=doctest.ELLIPSIS | doctest.NORMALIZE_WHITESPACE)
    tests = [t for name in vgroove.__all__ if callable(getattr(vgroove, name))
             for t in finder.find(getattr(vgroove, name), f"vgroove.{name}", module=False, globs={}) if t.examples]
    for t in tests:
        runner.run(t)
    failed, attempted = runner.summarize(verbose=False)
    assert failed == 0
    # Every public function and BRDF method has examples, so there are many.
    names = {t.name.split(".", 1)[1] for t in tests if "." in t.name}
    for name in ("BRDF", "BRDF.eval", "BRDF.sample", "BRDF.pdf", "BRDF.lobe", "BRDF.albedo", "BRDF.trace", "brdf",
                 "sample", "pdf", "lobe", "validate", "check_brdf", "tqdm_progress", "Lobe", "SampleBatch",
                 "SurfaceTrace", "direction", "kaleidoscope", "trace", "groove_case", "uniforms"):
        assert name in names, name
    assert attempted > 60


def readme_section(title):
    with open(README) as f:
        text = f.read()
    start = text.index(title)
    end = text.index("\n## ", start + 1) if "\n## " in text[start + 1:] else len(text)
    nxt = text.find("\n### ", start + 1)
    return text[start:min(end, nxt) if nxt != -1 else end]


def test_the_readmes_python_snippet_runs_and_prints_what_it_says(vg, capsys):
    section = readme_section("### From Python")
    blocks = re.findall(r"```python\n(.*?)```", section, re.S)
    assert blocks
    for block in blocks:
        # Lines ending in `# -> VALUE` state what the expression prints.
        for line in block.splitlines():
            m = re.match(r"(.*?)\s+# -> (.*)$", line)
            code = m.group(1) if m else line.split("  #")[0]
            if not code.strip():
                continue
            if m:
                got = eval(code, ns)
                assert repr(got) == m.group(2).strip() or str(got) == m.group(2).strip(), (code, got)
            else:
                exec(code, ns)


ns = {}


def test_the_readme_names_every_public_name_and_no_other(vg):
    section = readme_section("### From Python")
    named = set(re.findall(r"`(?:vgroove\.|vg\.)?([A-Za-z_]\w*)(?:\(|`)", section))
    for name in vg.__all__:
        if name.startswith("__") or name in ("FATES", "LEFT", "RIGHT", "TqdmProgress", "git_revision", "RANGES"):
            continue
        assert name in named, name
    # vgroove.NAME in code (not a path such as share/vgroove/vgroove.pth).
    for name in re.findall(r"(?<![/\w])vgroove\.([A-Za-z_]\w*)", section) + re.findall(r"(?<![/\w])vg\.([A-Za-z_]\w*)", section):
        assert hasattr(vg, name), name
    for method in re.findall(r"\.(eval|sample|pdf|lobe|albedo|trace)\(", section):
        assert hasattr(vg.BRDF, method)


def test_the_quick_start_names_the_schemas():
    section = readme_section("## Quick start")
    schemas = sorted(f for f in os.listdir(os.path.join(SOURCE, "docs", "schemas")) if f.endswith(".schema.json"))
    assert schemas
    for s in schemas:
        assert f"docs/schemas/{s}" in section, s
