"""The jar lcm-spy loads holds a class for every type, with the fingerprint
Python computes (lcm-spy matches messages to classes by fingerprint)."""

from __future__ import annotations

import shutil
import subprocess

import lcm
import pytest
from conftest import BUILD, ROOT

from auvlcm.types import all_types, fingerprint, full_name

JAR = BUILD / "java" / "auv_types.jar"


def test_types_jar_matches_python_fingerprints(tmp_path):
    if not (shutil.which("javac") and shutil.which("java")):
        pytest.skip("no JDK (javac/java) on this machine: the lcm-spy types jar is not built")
    assert JAR.exists(), "build/java/auv_types.jar missing although javac exists"
    lcm_jar = (ROOT / lcm.LCM_BIN_DIR / ".." / "share" / "java" / "lcm.jar").resolve()
    subprocess.run(["javac", "-d", tmp_path, ROOT / "tests" / "java" / "FingerprintDump.java"], check=True, timeout=120)
    run = subprocess.run(
        ["java", "-cp", f"{tmp_path}:{JAR}:{lcm_jar}", "FingerprintDump", JAR],
        capture_output=True,
        text=True,
        timeout=120,
    )
    assert run.returncode == 0, run.stderr
    in_jar = dict(line.split() for line in run.stdout.splitlines())
    expected = {full_name(cls): str(fingerprint(cls)) for cls in all_types()}
    assert in_jar == expected
