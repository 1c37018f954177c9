"""One way to register a behavior or test handler (c/chasm/chasm_plugin.h,
"Registration"): every plugin, test plugin and doc example does it the same.

The rules, read from the sources (comments removed):

- a table of behaviors or test handlers is `static const chasm_behavior_spec
  NAME[] = {...}` (or chasm_test_spec), and nothing else of those types is
  defined or declared: no spec objects in other files copied into an array,
  no array filled at run time;
- each entry names its fields: every item is a designator (`.name = ...`) or
  CHASM_SCHEMA(params); no positional entry, no macro of the plugin's own
  that builds one;
- the descriptor is CHASM_PLUGIN_EXPORT(name, version, CHASM_BEHAVIORS(t),
  CHASM_TESTS(t)) over those tables, once per plugin;
- a shipped plugin has no constructor (nothing to fill), and keeps its tables
  in <plugin>_plugin.c;
- the doc examples compile against chasm_plugin.h with the project's warnings.

A rule broken here is a plugin that registers another way: make it use the
idiom rather than widen the rule.
"""

from __future__ import annotations

import os
import re
import subprocess
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[2]
PLUGINS = ROOT / "c" / "plugins"
TEST_PLUGINS = ROOT / "tests" / "chasm" / "plugins"
DOCS = [ROOT / "docs" / "chasm.md", ROOT / "docs" / "contributing.md"]

# Test plugins that write the descriptor by hand, and why: they claim another
# ABI, which the export macro cannot (it always says CHASM_PLUGIN_ABI).
HAND_DESCRIPTOR = {
    "test_basic_abi2.c": "built as for ABI 2",
    "test_basic_badabi.c": "built as for a newer ABI",
}
# Test plugins whose constructor is the point of the test (it crashes, exits
# or hangs in the loader's probe process); none fills a table.
CONSTRUCTOR_TESTS = {"test_ctor_crash.c", "test_ctor_exit.c", "test_ctor_hang.c"}

TOKENS = re.compile(r'"(?:\\.|[^"\\\n])*"|\'(?:\\.|[^\'\\\n])*\'|/\*.*?\*/|//[^\n]*', re.S)
SPEC_TYPE = re.compile(r"\bchasm_(behavior|test)_spec\b")
TABLE = re.compile(r"\bstatic const chasm_(behavior|test)_spec (\w+)\[\] = \{")
SCHEMA = re.compile(r"CHASM_SCHEMA\(\s*\w+\s*\)$")


def strip_comments(text: str) -> str:
    """The code without comments; string literals kept (they may hold '/*')."""
    return TOKENS.sub(lambda m: " " if m.group(0).startswith("/") else m.group(0), text)


def join_lines(code: str) -> str:
    return code.replace("\\\n", " ")


def split_top(text: str) -> list[str]:
    """Comma-separated items of text at nesting depth 0, stripped."""
    items, depth, start, i = [], 0, 0, 0
    while i < len(text):
        ch = text[i]
        if ch in "\"'":
            i = TOKENS.match(text, i).end()
            continue
        if ch in "([{":
            depth += 1
        elif ch in ")]}":
            depth -= 1
        elif ch == "," and depth == 0:
            items.append(text[start:i].strip())
            start = i + 1
        i += 1
    items.append(text[start:].strip())
    return [s for s in items if s]


def closing(text: str, open_at: int) -> int:
    """Index of the bracket closing the one at open_at."""
    pairs = {"(": ")", "{": "}", "[": "]"}
    stack, i = [], open_at
    while i < len(text):
        ch = text[i]
        if ch in "\"'":
            i = TOKENS.match(text, i).end()
            continue
        if ch in pairs:
            stack.append(pairs[ch])
        elif ch in ")]}":
            assert stack and stack.pop() == ch, f"unbalanced {ch!r} at {i}"
            if not stack:
                return i
        i += 1
    raise AssertionError("unbalanced brackets")


def line_at(code: str, i: int) -> str:
    return code[code.rfind("\n", 0, i) + 1 : (code.find("\n", i) + 1 or len(code) + 1) - 1].strip()


def tables(code: str, where: str) -> dict[str, str]:
    """name -> kind of every spec table; fails on any other use of the types."""
    found = {}
    for m in SPEC_TYPE.finditer(code):
        t = TABLE.match(code, code.rfind("static", 0, m.start()))
        assert t and t.start(1) - len("chasm_") == m.start(), (
            f"{where}: '{line_at(code, m.start())}': a behavior or test handler is an entry of"
            f" the plugin's one `static const chasm_{m.group(1)}_spec NAME[] = {{...}}` (chasm_plugin.h, Registration)"
        )
        found[t.group(2)] = t.group(1)
        body = code[t.end() - 1 : closing(code, t.end() - 1) + 1]
        for entry in split_top(body[1:-1]):
            assert entry.startswith("{") and entry.endswith("}"), f"{where}: table {t.group(2)}: entry {entry!r}"
            items = split_top(entry[1:-1])
            bad = [s for s in items if not (s.startswith(".") or SCHEMA.match(s))]
            assert not bad, f"{where}: table {t.group(2)}: items {bad} are not `.field = value` or CHASM_SCHEMA(p)"
            assert any(re.match(r"\.name\s*=", s) for s in items), f"{where}: table {t.group(2)}: an entry has no .name"
    return found


def exports(code: str, where: str, known: dict[str, str]) -> int:
    """Checks each CHASM_PLUGIN_EXPORT's tables; returns how many there are."""
    n = 0
    for m in re.finditer(r"\bCHASM_PLUGIN_EXPORT\(", code):
        if code[: m.start()].rstrip().endswith("#define"):
            continue
        n += 1
        args = split_top(code[m.end() : closing(code, m.end() - 1)])
        assert len(args) >= 3, f"{where}: CHASM_PLUGIN_EXPORT needs CHASM_BEHAVIORS(t) and/or CHASM_TESTS(t)"
        for a in args[2:]:
            t = re.fullmatch(r"CHASM_(BEHAVIORS|TESTS)\((\w+)\)", a)
            assert t, f"{where}: CHASM_PLUGIN_EXPORT argument {a!r}: use CHASM_BEHAVIORS(t) / CHASM_TESTS(t)"
            want = "behavior" if t.group(1) == "BEHAVIORS" else "test"
            assert known.get(t.group(2)) == want, f"{where}: {a} names no chasm_{want}_spec table of this plugin"
    return n


def no_own_macros(code: str, where: str) -> None:
    for m in re.finditer(r"^\s*#\s*define\s+(\w+)(.*)$", code, re.M):
        body = m.group(2)
        assert not re.search(r"chasm_(behavior|test)_spec|CHASM_SCHEMA|CHASM_COUNT|\.step\b|\.evaluate\b", body), (
            f"{where}: #define {m.group(1)} builds a behavior or test entry: write the entry out"
        )


def read(paths: list[Path]) -> str:
    return join_lines("\n".join(strip_comments(p.read_text()) for p in paths))


def shipped_plugins() -> list[Path]:
    return sorted(d for d in PLUGINS.iterdir() if d.is_dir() and d.name != "lib")


@pytest.mark.parametrize("plugin", shipped_plugins(), ids=lambda d: d.name)
def test_shipped_plugin_registers_one_way(plugin):
    files = sorted(plugin.glob("*.[ch]"))
    for f in files:
        code = read([f])
        where = str(f.relative_to(ROOT))
        assert "constructor" not in code, f"{where}: a plugin has no constructor (tables are static const)"
        no_own_macros(code, where)
        found = tables(code, where)
        assert not found or f.name == f"{plugin.name}_plugin.c", f"{where}: tables belong in {plugin.name}_plugin.c"
    main = plugin / f"{plugin.name}_plugin.c"
    code = read([main])
    assert exports(code, str(main.relative_to(ROOT)), tables(code, main.name)) == 1


def sources_of(name):
    src = TEST_PLUGINS / name
    local = [TEST_PLUGINS / h for h in re.findall(r'#include "(\w+\.h)"', src.read_text())]
    return [src, *[h for h in local if h.exists()]]


@pytest.mark.parametrize("name", sorted(p.name for p in TEST_PLUGINS.glob("*.c")))
def test_test_plugin_registers_one_way(name):
    files = sources_of(name)
    code = read(files)
    if name not in CONSTRUCTOR_TESTS:
        assert "constructor" not in code, f"{name}: a constructor in a test plugin that is not about constructors"
    no_own_macros(code, name)
    found = tables(code, name)
    n = exports(code, name, found)
    if name in HAND_DESCRIPTOR:
        desc = re.search(r"\bconst chasm_plugin_descriptor chasm_plugin = \{", code)
        assert n == 0 and desc, f"{name}: writes its descriptor by hand ({HAND_DESCRIPTOR[name]})"
        body = code[desc.end() - 1 : closing(code, desc.end() - 1) + 1]
        items = split_top(body[1:-1])
        assert all(s.startswith(".") or re.fullmatch(r"CHASM_(BEHAVIORS|TESTS)\(\w+\)", s) for s in items), (
            f"{name}: descriptor items {items}: designated, as CHASM_PLUGIN_EXPORT writes them"
        )
    elif "chasm_plugin.h" in code or found:
        assert n == 1, f"{name}: one CHASM_PLUGIN_EXPORT"


def doc_blocks() -> list[tuple[str, str]]:
    """(where, code) of every C block of the docs that registers something."""
    out = []
    for doc in DOCS:
        text = doc.read_text()
        for m in re.finditer(r"^```c\n(.*?)^```", text, re.M | re.S):
            if re.search(r"chasm_(behavior|test)_spec|CHASM_PLUGIN_EXPORT|chasm_param_spec", m.group(1)):
                line = text.count("\n", 0, m.start()) + 1
                out.append((f"{doc.name}:{line}", m.group(1)))
    return out


def include_dirs(build: Path) -> list[str]:
    """chasm_plugin.h, the generated LCM types and LCM's own headers (build/config.mk)."""
    dirs = [ROOT / "c", build / "gen" / "c"]
    config = build / "config.mk"
    if config.exists():
        dirs += [Path(v.strip()) for k, v in re.findall(r"^(\w+) := (.*)$", config.read_text(), re.M) if k == "LCM_INC"]
    return [f"-I{d}" for d in dirs]


@pytest.mark.parametrize("where,block", doc_blocks(), ids=[w for w, _ in doc_blocks()])
def test_doc_example_registers_one_way_and_compiles(where, block, tmp_path, build_dir):
    code = join_lines(strip_comments(block))
    no_own_macros(code, where)
    assert exports(code, where, tables(code, where)) == 1, f"{where}: a complete plugin, with its CHASM_PLUGIN_EXPORT"
    # Positional schema entries are what docs/contributing.md forbids: each
    # entry of a chasm_param_spec table is indexed by its slot.
    for m in re.finditer(r"\bchasm_param_spec \w+\[\w*\] = \{", code):
        body = code[m.end() - 1 : closing(code, m.end() - 1) + 1]
        bad = [s for s in split_top(body[1:-1]) if not s.startswith("[")]
        assert not bad, f"{where}: schema entries {bad} are positional: index them by slot ([SLOT] = ...)"
    src = tmp_path / "example.c"
    src.write_text(block)
    if "auv/" in block and not (build_dir / "gen" / "c").is_dir():
        pytest.skip("needs the LCM types of `make build` (build/gen/c)")
    cc = os.environ.get("CC", "cc")
    flags = ["-std=c11", "-Wall", "-Wextra", "-Werror", "-fsyntax-only"]
    p = subprocess.run([cc, *flags, *include_dirs(build_dir), str(src)], capture_output=True, text=True)
    assert p.returncode == 0, f"{where} does not compile:\n{p.stderr}"
