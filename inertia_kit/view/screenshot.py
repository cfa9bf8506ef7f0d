"""
The review page as a PNG, through a headless Chromium: found on PATH (``chromium``,
``chromium-browser``, ``google-chrome``) or at ``$INERTIA_KIT_CHROMIUM``, driven over the
DevTools protocol on a pipe (``--remote-debugging-pipe``: no port, no network) so that the
picture is taken once the page says it has drawn its first frame, at exactly the size asked for.
The network is off: every host resolves to nothing and every request goes to a dead proxy.
"""

from __future__ import annotations

import base64
import contextlib
import json
import os
import select
import shutil
import subprocess
import tempfile
import time
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

from inertia_kit.errors import InertiaKitError

CANDIDATES = ("chromium", "chromium-browser", "google-chrome", "google-chrome-stable")
INSTALL = (
    "install Chromium (Debian/Ubuntu: `apt-get install chromium`) or set INERTIA_KIT_CHROMIUM "
    "to a Chrome or Chromium executable"
)

FLAGS = (
    "--headless",
    "--no-sandbox",
    "--disable-gpu",
    "--no-first-run",
    "--disable-background-networking",
    "--disable-component-update",
    "--disable-sync",
    "--disable-extensions",
    "--hide-scrollbars",
    "--mute-audio",
    # WebGL without a GPU: SwiftShader, which headless Chromium only uses when told to
    "--enable-unsafe-swiftshader",
    "--use-angle=swiftshader",
    # the network is off: nothing resolves, and every request goes to a closed port
    "--host-resolver-rules=MAP * ~NOTFOUND",
    "--proxy-server=127.0.0.1:9",
    "--remote-debugging-pipe",
)

# what the page records for us (inertia_kit/view/assets/page.js): read once it is ready
_STATE = """JSON.stringify({
  ready: document.body ? document.body.dataset.ready === "1" : false,
  errors: (document.getElementById("page-errors") || {}).textContent || "",
  projected: JSON.parse((document.getElementById("projected") || {}).textContent || "[]"),
  panel: (document.getElementById("panel") || {}).innerText || "",
  firstFrameMs: Number(document.body ? document.body.dataset.firstFrameMs : NaN)
})"""


class RendererError(InertiaKitError):
    """No browser to render with, or it failed: the message says what to install or what broke."""


@dataclass
class Capture:
    """What one headless load of the page gave: the picture and what the page recorded."""

    png: bytes
    errors: str  # the page's captured errors (window.onerror, console.error): "" when none
    projected: list[dict[str, Any]] = field(default_factory=list)  # box centres, CSS pixels
    first_frame_ms: float = float("nan")  # from navigation start, the page's own clock
    panel: str = ""  # the side panel's text
    result: Any = None  # what ``then`` gave
    requests: list[str] = field(default_factory=list)  # every URL the page asked for, itself too


def find_chromium() -> str | None:
    """``$INERTIA_KIT_CHROMIUM`` if set, else the first of :data:`CANDIDATES` on PATH."""
    chosen = os.environ.get("INERTIA_KIT_CHROMIUM")
    if chosen:
        return chosen
    for name in CANDIDATES:
        found = shutil.which(name)
        if found:
            return found
    return None


def capture(
    html: str | Path,
    *,
    width: int = 1280,
    height: int = 800,
    timeout: float = 60,
    then: str | None = None,
) -> Capture:
    """
    Open ``html`` (a file) in headless Chromium at ``width``×``height`` CSS pixels. ``then``:
    a JavaScript expression run once the page is ready (a click, a slider moved: the tests),
    its value kept; the picture and the page's records are taken two frames after it.
    """
    if os.name != "posix":
        raise RendererError("a PNG of the page needs Linux or macOS here (Chromium on a pipe)")
    browser = find_chromium()
    if browser is None:
        raise RendererError(f"no Chromium or Chrome found to render the page: {INSTALL}")
    url = Path(html).resolve().as_uri()
    with tempfile.TemporaryDirectory(prefix="inertia-kit-chromium-") as profile:
        command = [browser, *FLAGS, f"--user-data-dir={profile}", f"--window-size={width},{height}"]
        with _DevTools(command, timeout) as devtools:
            return devtools.load(url, width, height, then)


def screenshot(
    html: str | Path,
    png: str | Path,
    *,
    width: int = 1280,
    height: int = 800,
    follow_symlinks: bool = False,
) -> Capture:
    """
    Render ``html`` to the PNG file ``png`` (written atomically); ``RendererError`` if not.
    ``InputError`` for a ``png`` that is or passes through a symbolic link, unless
    ``follow_symlinks`` (:mod:`~inertia_kit.description.output_paths`).
    """
    from inertia_kit.description.edits import write_atomic
    from inertia_kit.description.output_paths import refuse_links

    refuse_links(png, follow_symlinks)
    result = capture(html, width=width, height=height)
    if result.errors:
        raise RendererError(f"the page reported errors in Chromium: {result.errors.strip()}")
    write_atomic(png, result.png, create=True, follow_symlinks=follow_symlinks)
    return result


class _DevTools:
    """A Chromium process and the DevTools protocol over its pipe (fd 3 in, fd 4 out)."""

    def __init__(self, command: list[str], timeout: float):
        self.command = command
        self.deadline = time.monotonic() + timeout
        self.next_id = 0
        self.buffer = b""
        self.requests: list[str] = []  # Network.requestWillBeSent, as they come

    def __enter__(self) -> _DevTools:
        to_browser, self.writer = os.pipe()
        self.reader, from_browser = os.pipe()

        import fcntl  # POSIX: capture() refuses other systems first

        def pipes_at_3_and_4() -> None:  # in the child, before exec: where Chromium expects them
            # out of the way first: either pipe may itself be fd 3 or 4
            reading = fcntl.fcntl(to_browser, fcntl.F_DUPFD, 10)
            writing = fcntl.fcntl(from_browser, fcntl.F_DUPFD, 10)
            os.dup2(reading, 3)
            os.dup2(writing, 4)

        # Chromium's log (GL driver messages on every read-back) to a file: a pipe nobody reads
        # while we wait for the page would fill and stop the browser
        self.log = tempfile.TemporaryFile()
        try:
            self.process = subprocess.Popen(
                self.command,
                stdin=subprocess.DEVNULL,
                stdout=subprocess.DEVNULL,
                stderr=self.log,
                preexec_fn=pipes_at_3_and_4,  # the pipes must be fds 3 and 4
                close_fds=False,
            )
        except OSError as error:
            self.log.close()
            raise RendererError(
                f"cannot run {self.command[0]}: {error.strerror}; {INSTALL}"
            ) from None
        finally:
            os.close(to_browser)
            os.close(from_browser)
        return self

    def __exit__(self, *exc: object) -> None:
        with contextlib.suppress(RendererError):  # it may be gone already
            self._send("Browser.close")
        try:
            self.process.wait(timeout=5)
        except subprocess.TimeoutExpired:
            self.process.kill()
            self.process.wait()
        self.log.close()
        os.close(self.writer)
        os.close(self.reader)

    def load(self, url: str, width: int, height: int, then: str | None) -> Capture:
        target = self._send("Target.createTarget", {"url": "about:blank"})["targetId"]
        session = self._send("Target.attachToTarget", {"targetId": target, "flatten": True})
        session_id = session["sessionId"]
        metrics = {"width": width, "height": height, "deviceScaleFactor": 1, "mobile": False}
        self._send("Emulation.setDeviceMetricsOverride", metrics, session_id)
        self._send("Network.enable", {}, session_id)
        self._send("Page.navigate", {"url": url}, session_id)
        while True:
            state = json.loads(self._evaluate(_STATE, session_id))
            if state["ready"] or state["errors"]:
                break
            if time.monotonic() > self.deadline:
                raise RendererError(f"the page did not draw its first frame in Chromium ({url})")
            time.sleep(0.05)
        result = None
        if then is not None and not state["errors"]:
            result = self._evaluate(then, session_id)
            two_frames = "new Promise(r => requestAnimationFrame(() => requestAnimationFrame(r)))"
            self._evaluate(two_frames, session_id)
            state = json.loads(self._evaluate(_STATE, session_id))
        shot = self._send("Page.captureScreenshot", {"format": "png"}, session_id)
        return Capture(
            png=base64.b64decode(shot["data"]),
            errors=state["errors"],
            projected=state["projected"],
            first_frame_ms=state["firstFrameMs"],
            panel=state["panel"],
            result=result,
            requests=list(self.requests),
        )

    def _evaluate(self, expression: str, session: str) -> Any:
        asked = {"expression": expression, "returnByValue": True, "awaitPromise": True}
        result = self._send("Runtime.evaluate", asked, session)
        if "exceptionDetails" in result:
            details = result["exceptionDetails"]
            text = details.get("exception", {}).get("description") or details.get("text")
            raise RendererError(f"Chromium: {text}")
        return result.get("result", {}).get("value")

    def _send(self, method: str, params: dict | None = None, session: str | None = None) -> dict:
        self.next_id += 1
        message: dict[str, Any] = {"id": self.next_id, "method": method, "params": params or {}}
        if session:
            message["sessionId"] = session
        try:
            os.write(self.writer, json.dumps(message).encode() + b"\0")
        except BrokenPipeError:
            raise RendererError(f"{self.command[0]} exited early: {self._stderr()}") from None
        while True:
            reply = self._receive()
            if reply.get("method") == "Network.requestWillBeSent":
                self.requests.append(reply["params"]["request"]["url"])
            if reply.get("id") == self.next_id:
                if "error" in reply:
                    raise RendererError(f"Chromium: {method}: {reply['error'].get('message')}")
                return reply.get("result", {})

    def _receive(self) -> dict:
        while b"\0" not in self.buffer:
            left = self.deadline - time.monotonic()
            if left <= 0:
                raise RendererError(f"{self.command[0]} did not answer in time")
            readable, _, _ = select.select([self.reader], [], [], left)
            if readable:
                chunk = os.read(self.reader, 1 << 20)
                if not chunk:
                    raise RendererError(f"{self.command[0]} exited early: {self._stderr()}")
                self.buffer += chunk
        message, _, self.buffer = self.buffer.partition(b"\0")
        return json.loads(message)

    def _stderr(self) -> str:
        try:
            self.process.wait(timeout=2)  # it closed the pipe: it is exiting
        except subprocess.TimeoutExpired:
            return "no message"
        self.log.seek(0)
        lines = self.log.read().decode(errors="replace").strip().splitlines()
        return lines[-1] if lines else f"exit code {self.process.returncode}"
