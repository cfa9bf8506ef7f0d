"""No browser, or a broken one: a RendererError saying what to install, never a hang."""

from __future__ import annotations

import pytest
from kit.scenes import two_box_scene

from inertia_kit.view.page import render_page
from inertia_kit.view.screenshot import RendererError, capture, find_chromium


@pytest.fixture
def page(tmp_path):
    html = tmp_path / "review.html"
    html.write_text(render_page(two_box_scene()), encoding="utf-8")
    return html


def test_no_browser_says_what_to_install(page, monkeypatch, tmp_path):
    monkeypatch.delenv("INERTIA_KIT_CHROMIUM", raising=False)
    monkeypatch.setenv("PATH", str(tmp_path))
    assert find_chromium() is None
    with pytest.raises(RendererError, match=r"apt-get install chromium.*INERTIA_KIT_CHROMIUM"):
        capture(page)


def test_a_chosen_browser_that_is_not_there(page, monkeypatch, tmp_path):
    monkeypatch.setenv("INERTIA_KIT_CHROMIUM", str(tmp_path / "no-such-chromium"))
    with pytest.raises(RendererError, match=r"cannot run .*no-such-chromium.*apt-get install"):
        capture(page)


def test_a_browser_that_exits_at_once(page, monkeypatch, tmp_path):
    false = tmp_path / "fake-chromium"
    false.write_text("#!/bin/sh\necho 'fake-chromium: broken' >&2\nexit 3\n")
    false.chmod(0o755)
    monkeypatch.setenv("INERTIA_KIT_CHROMIUM", str(false))
    with pytest.raises(RendererError, match="exited early: fake-chromium: broken"):
        capture(page, timeout=20)
