"""The one check of every output path (``ropemodel.sweeps.files.check_output``): its limits at their edges.

Truths: the file system's own limit (``os.pathconf``'s NAME_MAX) and the names written beside an output
(its lock ``FILE.lock``, its temporary ``.FILE.tmp``, a CSV sweep's sidecar ``.FILE.sweep.json.tmp``);
the fuzz (``tests/_fuzz_classes.py``) runs every command's outputs through the same cases.
"""

from __future__ import annotations

import os
import shutil
from collections import namedtuple

import pytest

from ropemodel.errors import InputError
from ropemodel.sweeps import files
from ropemodel.sweeps.files import check_output


def test_the_longest_name_that_fits_with_what_is_written_beside_it(tmp_path):
    """A name fits when its longest companion, the sidecar's temporary file, fits NAME_MAX: one byte more is
    refused before any work, and the refusal names the limit."""
    longest = os.pathconf(tmp_path, "PC_NAME_MAX") - len(".") - len(".sweep.json") - len(".tmp")
    fits = "n" * (longest - len(".csv")) + ".csv"
    assert check_output(tmp_path / fits) == tmp_path / fits
    (tmp_path / ("." + fits + ".sweep.json.tmp")).write_text("x")      # the file system takes the companion
    with pytest.raises(InputError, match=rf"the file name is {longest + 1} bytes long.*at most {longest} bytes"):
        check_output(tmp_path / ("n" + fits))
    assert sorted(p.name for p in tmp_path.iterdir()) == ["." + fits + ".sweep.json.tmp"]   # the probe is gone


def test_a_full_disk_is_refused_before_any_work(tmp_path, monkeypatch):
    usage = namedtuple("usage", "total used free")
    monkeypatch.setattr(shutil, "disk_usage", lambda path: usage(10**9, 10**9, 0))
    with pytest.raises(InputError, match=r"the disk is full \(0 bytes free"):
        check_output(tmp_path / "o.csv")
    monkeypatch.setattr(shutil, "disk_usage", lambda path: usage(10**9, 10**9 - files.LEAST_FREE, files.LEAST_FREE))
    assert check_output(tmp_path / "o.csv") == tmp_path / "o.csv"


def test_a_read_only_file_is_not_replaced(tmp_path):
    old = tmp_path / "o.csv"
    old.write_text("kept")
    old.chmod(0o444)
    with pytest.raises(InputError, match="read-only"):
        check_output(old)
    assert old.read_text() == "kept"


def test_a_long_path_is_shortened_in_the_message(tmp_path):
    with pytest.raises(InputError) as err:
        check_output("x" * 5000 + ".csv")
    message = str(err.value)
    assert "(5004 characters)" in message and len(message) < 300 and "\n" not in message


@pytest.mark.parametrize("name", ["", "   ", "a\x00b.csv"])
def test_an_empty_name_or_a_nul_is_refused(name):
    with pytest.raises(InputError, match="empty|NUL"):
        check_output(name)
