"""LCM URLs: traffic stays on this host unless a test made a namespace for it."""

import pytest

from auvlcm.url import DEFAULT_URL, check_local, default_url


def test_default_url_stays_local(monkeypatch):
    monkeypatch.delenv("LCM_DEFAULT_URL", raising=False)
    assert default_url() == DEFAULT_URL and "ttl=0" in DEFAULT_URL
    monkeypatch.setenv("LCM_DEFAULT_URL", "udpm://239.255.76.67:7700?ttl=0")
    assert default_url().endswith(":7700?ttl=0")


@pytest.mark.parametrize(
    "url", ["udpm://239.255.76.67:7667?ttl=0", "udpm://239.255.76.67:7667", "memq://", "file:///tmp/x.lcmlog?mode=w"]
)
def test_local_urls_pass(url):
    assert check_local(url) == url


@pytest.mark.parametrize(
    "url", ["udpm://239.255.76.67:7667?ttl=1", "udpm://239.255.76.67:7667?ttl=32", "udpm://239.255.76.67:7667?ttl=x"]
)
def test_urls_that_would_leave_the_host_are_refused(url):
    with pytest.raises(ValueError):
        check_local(url)


def test_ttl1_only_inside_a_namespace():
    assert check_local("udpm://239.255.76.67:7667?ttl=1", inside_netns=True)
    with pytest.raises(ValueError):
        check_local("udpm://239.255.76.67:7667?ttl=2", inside_netns=True)
