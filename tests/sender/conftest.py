"""Fixtures of the transport tests."""

from __future__ import annotations

import pytest

from auvlcm.chanfilter import FilteredLcm


@pytest.fixture
def rx(lcm_url):
    """A FilteredLcm that receives on a socket of its own (auvlcm/own_socket.py)."""
    lc = FilteredLcm(lcm_url)
    if lc._own is None:
        pytest.skip("no own socket here (libauvlcm_sender.so not built, or AUV_LCM_READER=0)")
    return lc
