"""Shared fixtures: where the build is, its message types, LCM URLs.

The build folder comes from $AUV_BUILD (default build/), so a second build
tree (e.g. `make BUILD=.build-x`) can be tested without touching the first.
The project's Python is installed in .venv (editable); only the generated
message types are taken from the build under test, here and in children.
"""

from __future__ import annotations

import itertools
import os
import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parent.parent
BUILD = Path(os.environ.get("AUV_BUILD", ROOT / "build"))
if not BUILD.is_absolute():
    BUILD = ROOT / BUILD

if str(BUILD / "gen" / "python") not in sys.path:
    sys.path.insert(0, str(BUILD / "gen" / "python"))

# Every test gets its own multicast port, so tests never hear each other even
# when the suite runs on a host network instead of a private namespace.
_ports = itertools.count(7700 + (os.getpid() % 200) * 10)


@pytest.fixture
def build_dir() -> Path:
    return BUILD


@pytest.fixture(params=["normal", "sanitized"])
def variant_dir(request) -> Path:
    """Run a C test once per build variant: build/ and build/san/ (ASan+UBSan)."""
    return BUILD if request.param == "normal" else BUILD / "san"


def c_program(name: str, sanitized: bool = False) -> Path:
    """Path of a built C program or plugin, e.g. c_program('bin/chasm')."""
    path = (BUILD / "san" if sanitized else BUILD) / name
    if not path.exists():
        pytest.fail(f"{path} is not built: run `make build sanitize` first")
    return path


def manager_cmd(
    plan,
    bind,
    url: str,
    *extra,
    sanitized: bool = False,
    vehicle: str = "AUV1",
    name: str = "NAVIGATOR",
    rate: int = 10,
) -> list:
    """A chasm-manager on the simulation clock (SIM.CLOCK), as the tests start one."""
    return [c_program("bin/chasm-manager", sanitized), "--plan", plan, "--bind", bind, "--vehicle", vehicle,
            "--name", name, "--rate", str(rate), "--clock", "sim", "--url", url, *extra]  # fmt: skip


def fresh_url() -> str:
    """A fresh udpm URL on this host only (ttl=0); for module-scoped runs."""
    return f"udpm://239.255.76.67:{next(_ports)}?ttl=0"


@pytest.fixture
def lcm_url() -> str:
    """A fresh udpm URL on this host only (ttl=0)."""
    return fresh_url()


@pytest.fixture
def own_lcm(lcm_url):
    """A FilteredLcm on lcm_url that receives on a socket of its own (auvlcm/own_socket.py)."""
    from auvlcm.chanfilter import FilteredLcm

    lc = FilteredLcm(lcm_url)
    if lc._own is None:
        pytest.skip("no own socket here (libauvlcm_sender.so not built, or AUV_LCM_READER=0)")
    return lc


def child_environment() -> dict[str, str]:
    """Environment for child processes: the build's message types, sanitizer options."""
    env = dict(os.environ)
    env["PYTHONPATH"] = str(BUILD / "gen" / "python")
    env.setdefault("ASAN_OPTIONS", "detect_leaks=1:abort_on_error=0:exitcode=86")
    env.setdefault("UBSAN_OPTIONS", "print_stacktrace=1:halt_on_error=1:exitcode=87")
    return env


@pytest.fixture
def child_env() -> dict[str, str]:
    return child_environment()
