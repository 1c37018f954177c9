"""Docs that run (issue 17, item 5): every command README.md and docs/ show.

Each command line in a fenced block whose program is the project's own (a
build/bin program, a console command of pyproject.toml such as
`.venv/bin/auv-launch`, a bench script, `make TARGET`, `chasm`) is checked:

- the program exists; a tool is shown as its console command, never as
  `python/tools/X.py` (which needs the venv's python to run);
- `make TARGET`: the Makefile has the target;
- offline commands whose files all exist (`chasm check|dot|describe` on
  shipped plans, `auv-lcmlog --help` and the like) run, exit 0;
- a command that needs a running system (LCM traffic, a vehicle) or is a
  synopsis with placeholders (PLAN, DIR, [...]) runs as `PROGRAM --help`,
  which must exit 0 and name the subcommand the doc uses.

Commands that cannot run here say why in SKIP_WHY (real hardware, sudo).
"""

from __future__ import annotations

import functools
import re
import shlex
import subprocess
from pathlib import Path

import pytest
import tomllib

ROOT = Path(__file__).resolve().parents[1]
SCRIPTS = set(tomllib.loads((ROOT / "pyproject.toml").read_text())["project"]["scripts"])
DOCS = [ROOT / "README.md", *sorted((ROOT / "docs").glob("*.md"))]
WRAPPERS = {
    "tests/isolated_net.sh",
    "--only-if-needed",
    ".venv/bin/python",
    "python",
    "python3",
    "PY",
    "$PY",
    "${PY}",
    "$(VPY)",
    "exec",
    "time",
    "env",
}
# a word that is a placeholder, not a value: the line is a synopsis
PLACEHOLDER = re.compile(r"^(\[.*|.*\]|\.\.\.|[A-Z][A-Z_0-9]*(\.\.\.)?|<.*>|.*[A-Z]{3,}\.\w+)$")
SKIP_WHY = {"sudo": "changes the host's routing (needs root; the README's one-line fix)"}
# run for real: programs that work offline, on files in the repository
OFFLINE = {
    ("build/bin/chasm", "check"),
    ("build/bin/chasm", "dot"),
    ("build/bin/chasm", "describe"),
    ("build/bin/chasm", "run"),
}


def command_lines(path: Path) -> list[tuple[int, str]]:
    """(line number, command) of every line of every fenced block, continuations joined."""
    out, block, joined, start = [], False, "", 0
    for n, line in enumerate(path.read_text().splitlines(), 1):
        if line.strip().startswith("```"):
            block = not block
            continue
        if not block:
            continue
        text = line.strip()
        if text.startswith("$ "):
            text = text[2:]
        if not joined:
            start = n
        if text.endswith("\\"):
            joined += text[:-1] + " "
            continue
        out.append((start, joined + text))
        joined = ""
    return out


def program_of(words: list[str]) -> tuple[str, list[str]] | None:
    """The project's program a command runs and its arguments, or None."""
    i = 0
    while i < len(words) and (words[i] in WRAPPERS or re.match(r"^[A-Z_]+=\S*$", words[i])):
        i += 1
    if i >= len(words):
        return None
    prog, args = words[i], words[i + 1 :]
    if prog == "chasm":
        prog = "build/bin/chasm"
    if prog == "chasm-manager":
        prog = "build/bin/chasm-manager"
    if prog == "-m" and args:
        return None  # python -m MODULE: not a file path
    if prog.endswith("/"):
        return None  # a folder in a layout listing
    if prog.removeprefix(".venv/bin/") in SCRIPTS:
        return ".venv/bin/" + prog.removeprefix(".venv/bin/"), args
    if prog == "make" or prog.startswith(("build/bin/", "python/tools/", "python/sim", "bench/")):
        return prog, args
    return None


def all_commands() -> list[tuple[str, int, str, list[str]]]:
    found = []
    for doc in DOCS:
        for n, text in command_lines(doc):
            text = text.split(" #")[0].strip()
            if not text or text.startswith("#"):
                continue
            try:
                words = shlex.split(text)
            except ValueError:
                continue
            # pipelines and redirections: the first command is the project's
            cut = next((k for k, w in enumerate(words) if w in ("|", ">", ">>", "&&", ";", "<")), len(words))
            words = words[:cut]
            if words and words[0] in SKIP_WHY:
                continue
            if program_of(words):
                found.append((doc.name, n, text, words))
    return found


COMMANDS = all_commands()
MAKE_TARGETS = set(re.findall(r"^([a-zA-Z][\w.-]*)\s*:", (ROOT / "Makefile").read_text(), re.M))


def test_docs_show_commands():
    """The scan finds the docs' commands (a broken scan would pass everything)."""
    assert len(COMMANDS) >= 60, len(COMMANDS)
    assert {d for d, *_ in COMMANDS} >= {"README.md", "managers.md", "tools.md", "chasm.md"}


def _id(c):
    return f"{c[0]}:{c[1]}"


@pytest.mark.parametrize("cmd", COMMANDS, ids=[_id(c) for c in COMMANDS])
def test_doc_command_runs(cmd, child_env):
    doc, line, text, words = cmd
    prog, args = program_of(words)
    where = f"docs {doc}:{line}: `{text}`"
    if prog == "make":
        targets = [a for a in args if not a.startswith("-") and "=" not in a]
        assert all(t in MAKE_TARGETS for t in targets), f"{where}: no such make target"
        return
    assert not prog.startswith("python/"), f"{where}: show the tool's console command (README, Commands)"
    path = ROOT / prog
    assert path.exists(), f"{where}: {prog} does not exist"
    if prog.endswith(".py"):
        exe = [str(ROOT / ".venv/bin/python"), str(path)]
    else:
        exe = [str(path)]
    sub = args[0] if args and re.fullmatch(r"[a-z][a-z_-]*", args[0]) and prog != "make" else None
    args = [
        g
        for a in args
        for g in (sorted(str(p.relative_to(ROOT)) for p in ROOT.glob(a)) or [a] if "*" in a and "/" in a else [a])
    ]
    concrete = not any(PLACEHOLDER.match(a) for a in args) and all(
        (ROOT / a).exists() for a in args if "/" in a and not a.startswith(("-", "udpm:", "http"))
    )
    env = child_env
    if concrete and (prog, sub) in OFFLINE:
        p = subprocess.run(exe + args, cwd=ROOT, env=env, capture_output=True, text=True, timeout=60)
        assert p.returncode == 0, f"{where}: exit {p.returncode}\n{p.stderr[-2000:]}"
        return
    # needs a running system, or a synopsis: the program and its subcommand answer --help
    rc, out = _help(tuple(exe + ([sub] if sub else []) + ["--help"]), tuple(sorted(env.items())))
    assert rc == 0, f"{where}: `{prog} {sub or ''} --help` exits {rc}\n{out[-2000:]}"
    assert "Traceback" not in out, f"{where}: {out[-2000:]}"


@functools.lru_cache(maxsize=None)
def _help(argv: tuple[str, ...], env: tuple[tuple[str, str], ...]) -> tuple[int, str]:
    """One run per distinct help command: many doc lines share a program."""
    p = subprocess.run(list(argv), cwd=ROOT, env=dict(env), capture_output=True, text=True, timeout=60)
    return p.returncode, p.stdout + p.stderr


def test_missions_completion_example_runs(tmp_path, child_env):
    """docs/missions.md, "Completion": the plan there goes where the text says."""
    text = (ROOT / "docs" / "missions.md").read_text()
    section = text[text.index("## Completion") :]
    plan = section[section.index("```chasm\n") + 9 :]
    plan = plan[: plan.index("```")]
    (tmp_path / "plan.chasm").write_text(plan)
    p = subprocess.run(
        [ROOT / "build/bin/chasm", "run", tmp_path / "plan.chasm", "--inputs", "/dev/null", "--until", "200"],
        capture_output=True,
        text=True,
        env=child_env,
        timeout=60,
    )
    assert p.returncode == 0, p.stderr
    got = re.findall(r"^\s*([\d.]+) s  (\S+)", p.stdout, re.M)
    assert [(float(t), s) for t, s in got[:4]] == [
        (0.0, "mission/leg1"),
        (60.0, "mission/leg2"),
        (120.0, "recover"),
        (130.0, "done"),
    ], p.stdout
