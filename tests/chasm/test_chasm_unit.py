"""The C unit tests of libchasm (semantics and plugins), one pytest per C test
and build variant (normal and ASan+UBSan)."""

from __future__ import annotations

import re

import pytest
from chasm_common import HERE, run

NAMES = sorted(
    {m for f in (HERE / "unit").glob("test_*.c") for m in re.findall(r'^\s*\{"(\w+)", \w+\},', f.read_text(), re.M)}
)


def test_the_c_test_list_is_not_empty():
    assert len(NAMES) >= 30, NAMES


@pytest.mark.parametrize("name", NAMES)
def test_c_unit(name, variant_dir, child_env, tmp_path):
    exe = variant_dir / "bin" / "chasm_unit_tests"
    if not exe.exists():
        pytest.fail(f"{exe} is not built: run `make build sanitize` first")
    child_env["TMPDIR"] = str(tmp_path)
    p = run([exe, "--plugins", variant_dir / "plugins", name], child_env)
    assert p.returncode == 0 and f"ok {name}" in p.stdout, p.stdout + p.stderr
    # plugin copies are private and removed: nothing may be left behind
    assert list(tmp_path.glob("chasm-plugins-*")) == []
