"""The Python side is one installed project (pyproject.toml): every console
command it declares runs from the venv with no path set by hand, and no
module sets one either."""

from __future__ import annotations

import os
import re
import subprocess
import sys
from pathlib import Path

import tomllib
from conftest import ROOT

SCRIPTS = tomllib.loads((ROOT / "pyproject.toml").read_text())["project"]["scripts"]
BIN = Path(sys.executable).parent


def test_every_console_command_is_installed_and_answers_help():
    # PYTHONPATH removed: the commands must find the project through the install alone
    env = {k: v for k, v in os.environ.items() if k not in ("PYTHONPATH", "VIRTUAL_ENV")}
    assert len(SCRIPTS) >= 15, sorted(SCRIPTS)
    runs = {
        name: subprocess.Popen(
            [BIN / name, "--help"], env=env, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True
        )
        for name in SCRIPTS
    }
    for name, proc in runs.items():
        out, err = proc.communicate(timeout=120)
        assert proc.returncode == 0 and "usage:" in out.lower(), (name, proc.returncode, err[-2000:])
        assert "Traceback" not in err, (name, err)


def test_no_module_changes_the_import_path():
    offenders = [
        f"{path.relative_to(ROOT)}:{n}"
        for path in sorted((ROOT / "python").rglob("*.py"))
        for n, line in enumerate(path.read_text().splitlines(), 1)
        if re.search(r"\bsys\.path\s*(\.insert|\.append|\[|=|\+=)", line)
    ]
    assert not offenders, offenders


def _module_name(path: Path) -> str:
    parts = path.relative_to(ROOT / "python").with_suffix("").parts
    return ".".join(parts[:-1] if parts[-1] == "__init__" else parts)


def _import_graph() -> dict[str, set[str]]:
    """Every module of python/ and the project modules it imports, at any depth of
    the file (an import inside a function closes a circle as surely as one at the top)."""
    import ast

    paths = {_module_name(p): p for p in sorted((ROOT / "python").rglob("*.py"))}
    graph: dict[str, set[str]] = {}
    for name, path in paths.items():
        package = name if path.name == "__init__.py" else name.rpartition(".")[0]
        found: set[str] = set()
        for node in ast.walk(ast.parse(path.read_text(), str(path))):
            if isinstance(node, ast.Import):
                found |= {a.name for a in node.names if a.name in paths}
            elif isinstance(node, ast.ImportFrom):
                base = node.module or ""
                if node.level:
                    up = package.split(".")[: len(package.split(".")) - node.level + 1]
                    base = ".".join(up + ([base] if base else []))
                found |= {m for m in [base, *(f"{base}.{a.name}" for a in node.names)] if m in paths}
        graph[name] = found - {name}
    return graph


def test_no_import_circle_in_python():
    graph = _import_graph()
    assert len(graph) > 100 and "tools.launch.launcher" in graph["tools.hosts.agent_part"]
    state: dict[str, int] = {}  # 1 on the current path, 2 done
    circles: list[list[str]] = []

    def visit(node: str, path: list[str]) -> None:
        state[node] = 1
        for dep in sorted(graph[node]):
            if state.get(dep) == 1:
                circles.append(path[path.index(dep) :] + [dep])
            elif dep not in state:
                visit(dep, path + [dep])
        state[node] = 2

    for node in sorted(graph):
        if node not in state:
            visit(node, [node])
    assert not circles, "import circles: " + "; ".join(" -> ".join(c) for c in circles)


def test_tools_are_grouped_by_job():
    """python/tools/ holds packages, one job each, none over about 15 modules; only
    the front end above them all (demo.py) sits at the top."""
    tools = ROOT / "python" / "tools"
    loose = sorted(p.name for p in tools.glob("*.py") if p.name not in ("__init__.py", "demo.py"))
    assert not loose, f"modules outside a package in python/tools/: {loose}"
    for package in sorted(p for p in tools.iterdir() if (p / "__init__.py").exists()):
        modules = [p for p in package.glob("*.py") if p.name not in ("__init__.py", "__main__.py")]
        assert 0 < len(modules) <= 15, (package.name, len(modules))
        assert (package / "__init__.py").read_text().startswith('"""'), f"{package.name}: say its job in a docstring"
