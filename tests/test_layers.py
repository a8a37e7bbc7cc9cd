"""The package's folders are its layers, and every import goes down (or stays in its folder).

Read with ``ast`` (imports inside functions included, nothing imported): a module
may import from its own folder and from the layers below its own, never above.
"""

from __future__ import annotations

import ast
from pathlib import Path

from conftest import ROOT

# Lowest first. One rank may hold several folders; they do not import each other.
LAYERS = (
    ("autograder.sandbox",),
    ("fixtures",),                                   # ground truth by construction (uses the store)
    ("autograder.loading",),
    ("autograder.engine",),
    ("autograder.labs", "autograder.figures"),      # the built-in course: suites and pictures
    ("autograder.reports",),
    ("autograder.student", "autograder.instructor"),
    ("autograder",),                                 # the entry points: cli, __main__, check()
)


def _layer(module: str) -> tuple[int, str]:
    """(rank, folder) of a dotted module name: the longest folder it is in."""
    best = None
    for rank, folders in enumerate(LAYERS):
        for folder in folders:
            if module == folder or module.startswith(folder + "."):
                if best is None or len(folder) > len(best[1]):
                    best = (rank, folder)
    assert best is not None, f"{module} is in no layer: add its folder to LAYERS"
    return best


def _modules() -> dict[str, Path]:
    found = {}
    for top in ("autograder", "fixtures"):
        for path in (ROOT / top).rglob("*.py"):
            parts = path.relative_to(ROOT).with_suffix("").parts
            name = ".".join(parts[:-1] if parts[-1] == "__init__" else parts)
            found[name] = path
    return found


def _imports(name: str, path: Path) -> set[str]:
    """The modules of this project that ``path`` imports (absolute dotted names)."""
    package = name if path.name == "__init__.py" else name.rpartition(".")[0]
    targets = set()
    for node in ast.walk(ast.parse(path.read_text())):
        if isinstance(node, ast.Import):
            targets |= {alias.name for alias in node.names}
        elif isinstance(node, ast.ImportFrom):
            if node.level:
                base = package.split(".")[: len(package.split(".")) - node.level + 1]
                module = ".".join(base + ([node.module] if node.module else []))
            else:
                module = node.module or ""
            # ``from package import module`` imports the module: judge that, not the package.
            targets |= {f"{module}.{alias.name}" for alias in node.names}
    return {t for t in targets if t.split(".")[0] in ("autograder", "fixtures")}


def _known(target: str, modules: dict) -> str | None:
    """The project module ``target`` names (a name imported from a module is that module)."""
    while target and target not in modules:
        target = target.rpartition(".")[0]
    return target or None


def _upward_imports(modules: dict[str, Path]) -> list[str]:
    upward = []
    for name, path in sorted(modules.items()):
        rank, folder = _layer(name)
        for target in sorted(_imports(name, path)):
            known = _known(target, modules)
            if known is None or known == name:
                continue
            if known == "autograder" and target == "autograder.__version__":
                continue  # the package's own metadata
            target_rank, target_folder = _layer(known)
            if target_rank > rank or (target_rank == rank and target_folder != folder):
                upward.append(f"{name} imports {known} ({target_folder} is not below {folder})")
    return upward


def test_every_import_goes_down_or_stays_in_its_folder():
    assert _upward_imports(_modules()) == []


def test_the_layers_cover_the_package_and_nothing_is_left_flat():
    """Every module is in a folder of its layer: only the entry points sit at the top."""
    flat = sorted(path.name for path in (ROOT / "autograder").glob("*.py"))
    assert flat == ["__init__.py", "__main__.py", "cli.py"]
    for name in _modules():
        _layer(name)


def test_an_import_upward_or_sideways_is_named(tmp_path):
    """The check can fail: a lazy import of a report from the engine, and a suite importing
    a figure (same rank, another folder), are both named."""
    engine = tmp_path / "checks.py"
    engine.write_text("def f():\n    from ..reports import html\n")
    suite = tmp_path / "lab07.py"
    suite.write_text("from ..figures import lab07\n")
    modules = {**_modules(), "autograder.engine.checks": engine, "autograder.labs.lab07": suite}
    assert _upward_imports(modules) == [
        "autograder.engine.checks imports autograder.reports.html "
        "(autograder.reports is not below autograder.engine)",
        "autograder.labs.lab07 imports autograder.figures.lab07 "
        "(autograder.figures is not below autograder.labs)"]
