"""The type stubs in step with the code: python/vgroove/__init__.pyi against the package (every
public name, function parameter (name, kind, default), method, property and dataclass field, both
ways) and python/vgroove/_vgroove.pyi against the extension (names, parameters and which have
defaults, from pybind11's signatures). The stubs are read from the source tree."""

import ast
import dataclasses
import inspect
import os
import re

import pytest

from conftest import SOURCE

STUBS = os.path.join(SOURCE, "python", "vgroove")


def parse(name):
    with open(os.path.join(STUBS, name)) as f:
        return ast.parse(f.read())


def stub_params(fn: ast.FunctionDef, skip_first=False):
    """(name, kind, default or None, has_default) per parameter of a stub's def."""
    a = fn.args
    out = []
    positional = a.posonlyargs + a.args
    defaults = [None] * (len(positional) - len(a.defaults)) + list(a.defaults)
    for p, d in zip(positional, defaults):
        out.append((p.arg, "POSITIONAL_OR_KEYWORD", d))
    if a.vararg:
        out.append((a.vararg.arg, "VAR_POSITIONAL", None))
    for p, d in zip(a.kwonlyargs, a.kw_defaults):
        out.append((p.arg, "KEYWORD_ONLY", d))
    if a.kwarg:
        out.append((a.kwarg.arg, "VAR_KEYWORD", None))
    if skip_first:
        out = out[1:]
    return [(n, k, None if d is None else ast.literal_eval(d), d is not None) for n, k, d in out]


def runtime_params(f, skip_first=False):
    ps = list(inspect.signature(f).parameters.values())
    if skip_first:
        ps = ps[1:]
    return [(p.name, p.kind.name, None if p.default is p.empty else p.default, p.default is not p.empty) for p in ps]


def package_stub():
    tree = parse("__init__.pyi")
    names, functions, classes = set(), {}, {}
    for node in tree.body:
        if isinstance(node, ast.FunctionDef):
            functions[node.name] = node
        elif isinstance(node, ast.ClassDef):
            classes[node.name] = node
        elif isinstance(node, ast.AnnAssign):
            names.add(node.target.id)
        elif isinstance(node, ast.Assign):
            names.update(t.id for t in node.targets)
    return names, functions, classes


def test_every_public_name_is_in_the_stub_and_the_reverse(vg):
    names, functions, classes = package_stub()
    stubbed = names | set(functions) | set(classes)
    helpers = {"ArrayLike", "ProgressFn"}  # the stub's own type aliases
    assert set(vg.__all__) - stubbed == set(), "public names the stub does not declare"
    assert stubbed - helpers - set(vg.__all__) == set(), "stub names the package does not export"
    for name in stubbed - helpers:
        assert hasattr(vg, name), name


def test_functions_have_the_stubs_parameters(vg):
    _, functions, _ = package_stub()
    for name, node in functions.items():
        assert stub_params(node) == runtime_params(getattr(vg, name)), name


def test_classes_have_the_stubs_methods_properties_and_fields(vg):
    _, _, classes = package_stub()
    for name, node in classes.items():
        cls = getattr(vg, name)
        methods, properties, fields = {}, set(), []
        for item in node.body:
            if isinstance(item, ast.FunctionDef):
                decorators = {d.id if isinstance(d, ast.Name) else None for d in item.decorator_list}
                if "property" in decorators:
                    properties.add(item.name)
                else:
                    methods[item.name] = item
            elif isinstance(item, ast.AnnAssign):
                fields.append(item.target.id)
        for m, item in methods.items():
            f = getattr(cls, m)
            assert callable(f), (name, m)
            if m in ("__eq__", "__hash__"):
                continue
            assert stub_params(item, skip_first=True) == runtime_params(f, skip_first=not isinstance(
                inspect.getattr_static(cls, m), classmethod)), (name, m)
        for p in properties:
            assert isinstance(inspect.getattr_static(cls, p), property), (name, p)
        public = {m for m, v in vars(cls).items() if not m.startswith("_")}
        if dataclasses.is_dataclass(cls):
            assert fields == [f.name for f in dataclasses.fields(cls)], name
            public -= set(fields)
        else:
            public -= set(fields)
        assert public == set(methods) - {"__init__", "__eq__", "__hash__", "__call__"} | properties, name


def extension_signatures(vg):
    """name -> [(param, has_default)] from pybind11's docstring signatures of vgroove._vgroove."""
    out = {}
    for name, f in vars(vg._vgroove).items():
        if name.startswith("_") or not callable(f) or isinstance(f, type):
            continue
        first = f.__doc__.splitlines()[0]
        m = re.match(rf"{name}\((.*)\) -> ", first)
        assert m, first
        params = []
        depth, cur = 0, ""
        for ch in m.group(1) + ",":
            if ch in "[(":
                depth += 1
            elif ch in "])":
                depth -= 1
            if ch == "," and depth == 0:
                if cur.strip():
                    params.append(cur.strip())
                cur = ""
            else:
                cur += ch
        out[name] = [(p.split(":")[0].strip(), "=" in p) for p in params]
    return out


def test_the_extension_stub_names_every_function_and_parameter(vg):
    tree = parse("_vgroove.pyi")
    stub = {n.name: [(a, d) for a, _, _, d in stub_params(n)] for n in tree.body if isinstance(n, ast.FunctionDef)}
    runtime = extension_signatures(vg)
    # output_deg is a numpy.vectorize'd function: pybind11 names its parameter arg0.
    runtime["output_deg"] = [("rad", False)]
    assert stub == runtime
    values = {n.target.id for n in tree.body if isinstance(n, ast.AnnAssign)}
    assert values == {n for n, v in vars(vg._vgroove).items()
                      if not n.startswith("_") and not callable(v)} | {"__version__"} - {"Microsurface"}
    cls = next(n for n in tree.body if isinstance(n, ast.ClassDef) and n.name == "Microsurface")
    props = {n.name for n in cls.body if isinstance(n, ast.FunctionDef)}
    assert props == {n for n in vars(vg.Microsurface) if not n.startswith("_")}


@pytest.mark.parametrize("broken", ["drop_method", "rename_param", "change_default"])
def test_a_stub_out_of_step_is_found(vg, broken, tmp_path, monkeypatch):
    # The checks above could fail: a stub with BRDF.albedo removed, a parameter renamed or a
    # default changed is told apart.
    with open(os.path.join(STUBS, "__init__.pyi")) as f:
        text = f.read()
    if broken == "drop_method":
        text = re.sub(r"    def albedo\(.*?\) -> np\.ndarray: \.\.\.\n", "", text, flags=re.S)
    elif broken == "rename_param":
        text = text.replace("def uniforms(n: int,", "def uniforms(rows: int,")
    else:
        text = text.replace("k_rows: int = 16, progress: Optional[ProgressFn] = None) -> Lobe", 
                            "k_rows: int = 8, progress: Optional[ProgressFn] = None) -> Lobe")
    os.makedirs(tmp_path / "python" / "vgroove")
    with open(tmp_path / "python" / "vgroove" / "__init__.pyi", "w") as f:
        f.write(text)
    monkeypatch.setattr(__import__(__name__), "STUBS", str(tmp_path / "python" / "vgroove"))
    with pytest.raises(AssertionError):
        test_functions_have_the_stubs_parameters(vg)
        test_classes_have_the_stubs_methods_properties_and_fields(vg)
