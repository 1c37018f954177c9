"""docs/architecture.md names every top-level folder and every package with its idea,
and docs/README.md indexes every page: a folder or page added without its row fails."""

from __future__ import annotations

import re
import subprocess

from conftest import ROOT

ROW = re.compile(r"^\| `([^`]+)/` \|", re.M)


def _tracked_dirs() -> set[str]:
    files = subprocess.run(["git", "ls-files"], cwd=ROOT, capture_output=True, text=True, check=True).stdout.split()
    return {f.split("/")[0] for f in files if "/" in f}


def _expected() -> set[str]:
    want = _tracked_dirs()
    want |= {f"c/{p.name}" for p in (ROOT / "c").iterdir() if p.is_dir()}
    want |= {f"missions/{p.name}" for p in (ROOT / "missions").iterdir() if p.is_dir()}
    # Python packages two levels down (python/sim, python/sim/modem, python/tools/launch, ...)
    for init in (ROOT / "python").glob("*/__init__.py"):
        want.add(str(init.parent.relative_to(ROOT)))
    for init in (ROOT / "python").glob("*/*/__init__.py"):
        want.add(str(init.parent.relative_to(ROOT)))
    return want


def test_every_folder_and_package_has_a_row():
    rows = set(ROW.findall((ROOT / "docs" / "architecture.md").read_text()))
    want = _expected()
    assert {"c/chasm", "python/tools/launch", "missions/pilot", "lcmtypes"} <= want
    missing = sorted(want - rows)
    assert not missing, f"docs/architecture.md has no row for: {missing}"
    stale = sorted(r for r in rows if not (ROOT / r).is_dir())
    assert not stale, f"docs/architecture.md has rows for folders that do not exist: {stale}"


def test_docs_index_links_every_page():
    index = (ROOT / "docs" / "README.md").read_text()
    linked = set(re.findall(r"\]\(([\w.-]+\.md)\)", index))
    pages = {p.name for p in (ROOT / "docs").glob("*.md")} - {"README.md"}
    assert pages - linked == set(), f"docs/README.md does not link: {sorted(pages - linked)}"
    assert linked - pages == set(), f"docs/README.md links pages that do not exist: {sorted(linked - pages)}"
