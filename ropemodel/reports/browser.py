"""Headless Chromium: print a page to PDF, take a screenshot.

The PDF of a report is the page as a real browser engine lays it out and prints it, not a second
layout.  Chromium runs with a fresh profile in a temporary directory, no network services of its
own (no sync, updates, background requests), and is ended (its whole process group) if it takes
longer than :data:`TIMEOUT`.
"""

from __future__ import annotations

import os
import shutil
import signal
import subprocess
import tempfile
from pathlib import Path

from ropemodel.errors import InputError
from ropemodel.sweeps.files import OutputError

#: names Chromium goes by on PATH, in the order tried
NAMES = ("chromium", "chromium-browser", "google-chrome", "google-chrome-stable")
FLAGS = ("--headless", "--no-sandbox", "--disable-gpu", "--disable-quic", "--no-first-run",
         "--disable-background-networking", "--disable-component-update", "--disable-sync")
#: seconds Chromium may take for one page
TIMEOUT = 120.0
INSTALL = "install it (Debian/Ubuntu: apt-get install chromium) or put chromium on PATH"


def find() -> str:
    """The Chromium executable, or :class:`InputError` saying how to install it."""
    for name in NAMES:
        path = shutil.which(name)
        if path:
            return path
    raise InputError(f"--pdf needs Chromium to print the page and none was found on PATH "
                     f"(looked for {', '.join(NAMES)}): {INSTALL}")


def run(html: Path, args, what: str, browser: str | None = None) -> None:
    """Chromium on the page ``html`` with ``args``; :class:`OutputError` with its last words if it fails."""
    exe = browser or find()
    with tempfile.TemporaryDirectory(prefix="ropemodel-chromium-") as profile:
        cmd = [exe, *FLAGS, f"--user-data-dir={profile}", *args, Path(html).resolve().as_uri()]
        proc = subprocess.Popen(cmd, stdin=subprocess.DEVNULL, stdout=subprocess.PIPE, stderr=subprocess.PIPE,
                                start_new_session=True)
        try:
            out, err = proc.communicate(timeout=TIMEOUT)
        except subprocess.TimeoutExpired:
            _end(proc)
            raise OutputError(f"Chromium did not finish {what} within {TIMEOUT:g} s") from None
        except BaseException:   # Ctrl-C: Chromium runs in its own session and would not see it
            _end(proc)
            raise
    if proc.returncode != 0:
        raise OutputError(f"Chromium failed {what} (exit status {proc.returncode}): {_last_words(err)}")


def _end(proc) -> None:
    """End Chromium and the helpers it started (the process group it leads) and reap it."""
    try:
        os.killpg(proc.pid, signal.SIGKILL)
    except ProcessLookupError:
        pass
    proc.communicate()


def _last_words(err: bytes) -> str:
    lines = [ln.strip() for ln in err.decode(errors="replace").splitlines()
             if ln.strip() and "dbus" not in ln and "unexpected operator" not in ln]
    return lines[-1] if lines else "no message"


def print_pdf(html: Path, pdf: Path, browser: str | None = None) -> None:
    """Print the page ``html`` to ``pdf`` (A4, as the page's ``@page`` rule says; no browser header)."""
    run(html, ["--no-pdf-header-footer", f"--print-to-pdf={Path(pdf).resolve()}"], "printing the page", browser)
    if not Path(pdf).exists():
        raise OutputError("Chromium printed nothing")


def screenshot(html: Path, png: Path, width: int = 1100, height: int = 1500, browser: str | None = None) -> None:
    """A PNG of the top ``width`` x ``height`` pixels of the page ``html``."""
    run(html, ["--hide-scrollbars", f"--window-size={width},{height}", f"--screenshot={Path(png).resolve()}"],
        "taking a screenshot of the page", browser)
