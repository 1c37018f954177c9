"""The C unit tests of the behavior plugins (the files in tests/plugins/NAME,
built as build/bin/test_plugin_NAME on the shared harness tests/harness, helpers in tests/plugins/common):
one pytest per C test and build variant (normal and ASan+UBSan). Tests are
found as `{"name", function},` lines of the C test lists."""

from __future__ import annotations

import re
import subprocess
from pathlib import Path

import pytest

HERE = Path(__file__).resolve().parent
PLUGINS = sorted(p.name for p in HERE.iterdir() if p.is_dir() and p.name not in ("common", "__pycache__"))
CASES = [
    (plugin, name)
    for plugin in PLUGINS
    for f in sorted((HERE / plugin).glob("*.c"))
    for name in re.findall(r'^\s*\{"(\w+)", \w+\},', f.read_text(), re.M)
]


def test_the_c_test_lists_are_found():
    for plugin in ("pilot", "checks"):
        assert sum(1 for p, _ in CASES if p == plugin) >= 5, plugin


@pytest.mark.parametrize("plugin,name", CASES, ids=[f"{p}:{n}" for p, n in CASES])
def test_plugin_c_unit(plugin, name, variant_dir, child_env):
    exe = variant_dir / "bin" / f"test_plugin_{plugin}"
    if not exe.exists():
        pytest.fail(f"{exe} is not built: run `make build sanitize` first")
    p = subprocess.run(
        [str(exe), "--plugins", str(variant_dir / "plugins"), name],
        env=child_env,
        capture_output=True,
        text=True,
        timeout=120,
    )
    assert p.returncode not in (86, 87), f"sanitizer report:\n{p.stderr}"
    assert p.returncode == 0 and f"ok {name}" in p.stdout, p.stdout + p.stderr
