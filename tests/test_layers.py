"""The package's layers import only downward (issue #16): the base (errors, status, the compiled core) below
the I/O layer (lieng.io), below the restored programs (lieng.programs), below the modern analyses
(lieng.analysis), below diagnose (lieng.diagnose), below the command line (lieng.cli).  Every import is
counted, also those inside functions."""

import ast

from conftest import ROOT

PKG = ROOT / "python" / "lieng"
RANK = {"errors": 0, "status": 0, "_core": 0, "io": 1, "programs": 2, "analysis": 3, "diagnose": 4, "cli": 5}


def layer(module: str) -> int | None:
    parts = module.split(".")
    if parts[0] != "lieng":
        return None
    if len(parts) == 1:
        return None            # the package's __init__ (the public surface) is not a layer
    return RANK[parts[1]]


def imports(path):
    tree = ast.parse(path.read_text())
    rel = path.relative_to(PKG.parent).with_suffix("")
    pkg = list(rel.parts[:-1]) if rel.name != "__init__" else list(rel.parts[:-1])
    for node in ast.walk(tree):
        if isinstance(node, ast.Import):
            for a in node.names:
                yield a.name, node.lineno
        elif isinstance(node, ast.ImportFrom):
            if node.level:
                base = pkg[:len(pkg) - (node.level - 1)]
                mod = ".".join(base + ([node.module] if node.module else []))
            else:
                mod = node.module
            yield mod, node.lineno
            for a in node.names:     # from lieng import cycles: the attribute may be a module
                yield f"{mod}.{a.name}", node.lineno


def test_every_module_has_a_layer_and_imports_only_downward():
    bad = []
    for f in sorted(PKG.rglob("*.py")):
        rel = f.relative_to(PKG)
        if rel.parts == ("__init__.py",):
            continue
        own = RANK[rel.parts[0] if len(rel.parts) > 1 else rel.stem]
        for mod, line in imports(f):
            parts = mod.split(".")
            if parts[0] != "lieng" or len(parts) < 2 or parts[1] not in RANK:
                continue
            if RANK[parts[1]] > own:
                bad.append(f"{rel}:{line} imports {mod}")
    assert not bad, "upward imports:\n" + "\n".join(bad)
