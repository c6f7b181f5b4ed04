"""The type stubs (`python/stiffid/_stiffid.pyi`) describe the compiled module as it is: every
public name of the module is stubbed and every stub exists, with the same methods per class and,
where the module gives a signature, the same parameter names in the same order. The documents'
types (`python/stiffid/_documents.pyi`) are those `tools/stubs.py` generates from docs/schemas."""

import ast
import importlib.util
import inspect
from pathlib import Path

import stiffid._stiffid as module

CRATE = Path(__file__).resolve().parents[1]
STUBS = CRATE / "python" / "stiffid" / "_stiffid.pyi"
DOCUMENTS = CRATE / "python" / "stiffid" / "_documents.pyi"


def overloads():
    """{name: [ast node]} of the stub file's top-level functions (several for an overload)."""
    found = {}
    for node in ast.parse(STUBS.read_text()).body:
        if isinstance(node, ast.FunctionDef):
            found.setdefault(node.name, []).append(node)
    return found


def stubbed():
    """{name: ast node} of the stub file's top-level functions, classes and assignments."""
    tree = ast.parse(STUBS.read_text())
    names = {}
    for node in tree.body:
        if isinstance(node, (ast.FunctionDef, ast.ClassDef)):
            names[node.name] = node
        elif isinstance(node, ast.AnnAssign) and isinstance(node.target, ast.Name):
            names[node.target.id] = node
        elif isinstance(node, ast.Assign):
            for target in node.targets:
                if isinstance(target, ast.Name):
                    names[target.id] = node
    return names


def is_property(node):
    return any(isinstance(d, ast.Name) and d.id == "property" for d in node.decorator_list)


def public(obj):
    return {n for n in dir(obj) if not n.startswith("_")}


def parameters(node):
    """The stub's parameter names, `self` left out."""
    a = node.args
    names = [p.arg for p in a.posonlyargs + a.args + a.kwonlyargs]
    return [n for n in names if n not in ("self", "cls")]


def runtime_parameters(obj):
    """The module's parameter names, or None where PyO3 gives no signature."""
    try:
        signature = inspect.signature(obj)
    except (TypeError, ValueError):
        return None
    return [n for n, p in signature.parameters.items()
            if n not in ("self", "cls") and p.kind not in (p.VAR_POSITIONAL, p.VAR_KEYWORD)]


def test_every_public_name_is_stubbed_and_every_stub_exists():
    stubs = stubbed()
    names = public(module) | {"__version__"}
    assert sorted(names - set(stubs)) == [], "in the module, not in the stubs"
    aliases = {n for n in stubs if n.startswith("_") and n != "__version__"}
    assert sorted(set(stubs) - names - aliases) == [], "in the stubs, not in the module"


def test_classes_have_the_stubbed_methods():
    for name, node in stubbed().items():
        if not isinstance(node, ast.ClassDef) or name.startswith("_") or issubclass(getattr(module, name), BaseException):
            continue
        cls = getattr(module, name)
        functions = [n for n in node.body if isinstance(n, ast.FunctionDef) and not n.name.startswith("_")]
        stubbed_public = {n.name for n in functions}
        assert sorted(public(cls) - stubbed_public) == [], f"{name}: not stubbed"
        # Properties a class serves from its fields (PyO3's `__getattr__`, a `__getattribute__`
        # slot) are not in `dir`.
        dynamic = {n.name for n in functions if is_property(n)} if "__getattribute__" in cls.__dict__ else set()
        assert sorted(stubbed_public - public(cls) - dynamic) == [], f"{name}: no such method"


def test_signatures_agree_where_the_module_gives_them():
    checked = 0
    for name, nodes in overloads().items():
        if len(nodes) > 1:
            # An overloaded function: together the overloads name every parameter.
            union = {p for node in nodes for p in parameters(node)}
            assert union == set(runtime_parameters(getattr(module, name))), name
            checked += 1
    for name, node in stubbed().items():
        targets = []
        if isinstance(node, ast.FunctionDef) and len(overloads()[name]) == 1:
            targets.append((name, node, getattr(module, name)))
        elif isinstance(node, ast.ClassDef) and not name.startswith("_"):
            cls = getattr(module, name)
            if issubclass(cls, BaseException):
                continue
            for item in node.body:
                if isinstance(item, ast.FunctionDef) and not item.name.startswith("_") and not is_property(item):
                    targets.append((f"{name}.{item.name}", item, getattr(cls, item.name)))
        for label, stub, obj in targets:
            if is_property(stub):
                continue
            real = runtime_parameters(obj)
            if real is None:
                continue
            assert parameters(stub) == real, label
            checked += 1
    assert checked >= 20, f"only {checked} signatures compared"


def generator():
    spec = importlib.util.spec_from_file_location("stubs", CRATE / "tools" / "stubs.py")
    tool = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(tool)
    return tool


def test_the_document_types_are_generated_from_the_schemas():
    assert DOCUMENTS.read_text() == generator().generate(), \
        "_documents.pyi is not what the schemas give: python3 crates/stiffid-py/tools/stubs.py"


def test_the_module_returns_defined_document_types():
    documents = ast.parse(DOCUMENTS.read_text())
    defined = {t.id for node in documents.body if isinstance(node, ast.Assign) for t in node.targets}
    imported = {a.name for node in ast.parse(STUBS.read_text()).body
                if isinstance(node, ast.ImportFrom) and node.module == "_documents" for a in node.names}
    assert len(imported) >= 8 and imported <= defined, sorted(imported - defined)
