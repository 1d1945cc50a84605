"""The type stubs and py.typed ship with the package and match the extension module."""

import ast
import inspect
from pathlib import Path

import hapstab as hs

STUB = Path(hs.__file__).with_name("_hapstab.pyi")


def stub_tree():
    assert STUB.exists() and STUB.with_name("py.typed").exists()
    return ast.parse(STUB.read_text())


def params(fn: ast.FunctionDef):
    a = fn.args
    return [x.arg for x in a.posonlyargs + a.args + a.kwonlyargs]


def test_functions_match_their_stubs():
    funcs = {n.name: n for n in stub_tree().body if isinstance(n, ast.FunctionDef)}
    assert set(funcs) == {
        "check", "region", "kmax", "stability_map", "discretize", "simulate", "passivity", "margins",
        "frequency_response", "root_locus", "robust_kmax", "identify", "identify_frequency", "stability_probability", "sweep", "zwidth", "linear_condition", "nyquist_regions",
    }
    for name, node in funcs.items():
        sig = inspect.signature(getattr(hs, name))
        assert params(node) == list(sig.parameters), name
        for p, d in zip(sig.parameters.values(), node.args.kw_defaults):
            assert p.kind != p.KEYWORD_ONLY or d is not None, (name, p)


def test_classes_match_their_stubs():
    classes = [n for n in stub_tree().body if isinstance(n, ast.ClassDef)]
    assert {c.name for c in classes} == {n for n in hs.__all__ if n[0].isupper()}
    for c in classes:
        cls = getattr(hs, c.name)
        for item in c.body:
            if isinstance(item, ast.AnnAssign):
                assert hasattr(cls, item.target.id), (c.name, item.target.id)
            elif isinstance(item, ast.FunctionDef) and item.name != "__init__":
                assert hasattr(cls, item.name), (c.name, item.name)
            elif isinstance(item, ast.FunctionDef):
                sig = inspect.signature(cls)
                assert params(item)[1:] == list(sig.parameters), c.name
