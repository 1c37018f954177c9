"""Every bad plan gives exactly the errors written at its end (`# expect:`),
with file:line:col, all in one run, and `chasm check` exits with 1."""

from __future__ import annotations

import pytest
from chasm_common import BAD_PLANS, run

FILES = sorted(BAD_PLANS.glob("*.chasm"))


def test_there_are_at_least_30_bad_plans():
    assert len(FILES) >= 30


@pytest.mark.parametrize("plan", FILES, ids=[f.stem for f in FILES])
def test_bad_plan(plan, variant_dir, child_env, tmp_path):
    plugins = variant_dir / "plugins"
    expected = [
        f"{plan.name}:{line[len('# expect: ') :]}".replace("{plugins}", str(plugins))
        for line in plan.read_text().splitlines()
        if line.startswith("# expect: ")
    ]
    assert expected, "the plan lists no expected error"
    child_env["TMPDIR"] = str(tmp_path)
    p = run([variant_dir / "bin" / "chasm", "check", "-P", plugins, plan.name], child_env, cwd=BAD_PLANS)
    got = [l for l in p.stderr.splitlines() if not l.endswith(" errors")]
    assert p.returncode == 1, p.stdout + p.stderr
    assert got == expected
    assert p.stdout == ""
