"""An output file made safe: checked before any work, locked, written atomically, read back.

Checks
    :func:`check_output` refuses an output that cannot be written (unknown suffix, a
    directory, a path under a regular file or in a missing directory, a directory without
    write permission); :func:`check_disk` and :func:`check_size` refuse work whose results
    cannot fit on the disk or, kept in memory, in memory.  Each need is a lower bound
    (8 bytes a value), so nothing that could fit is refused.  (The number of points itself
    is bounded where grids are made, :mod:`ropemodel.sweeps.points`.)
Lock
    :class:`OutputLock` holds an exclusive ``flock`` on ``FILE.lock`` beside the output for
    the whole run, so a second writer of the same output is refused at once.  The kernel
    releases the lock when its process ends, however it ends: a killed writer never leaves a
    stale lock (the file may stay; the next writer takes it over and removes it).
Atomic files
    :func:`write_atomic` writes under a temporary name (``.FILE.tmp``), reads the file back
    (:func:`table_shape`: rows and columns as a reader sees them), flushes it to disk (fsync)
    and renames it over ``FILE`` (``os.replace``): ``FILE`` is the complete old file or the
    complete new one, never a part of either.  A failed write removes the temporary file.
"""

from __future__ import annotations

import csv
import fcntl
import os
import re
import shutil
from pathlib import Path

import pyarrow as pa
import pyarrow.csv as pacsv
import pyarrow.parquet as pq

from ropemodel.errors import InputError, RopeModelError

SUFFIXES = (".parquet", ".pq", ".csv")
#: the sidecar beside a finished CSV sweep (:mod:`ropemodel.sweeps.store`)
SIDECAR = ".sweep.json"


class OutputError(RopeModelError):
    """An output file could not be written (disk full, I/O error); CLI exit status 1."""


def cause(exc: OSError) -> str:
    """The reason of an OSError in words, without the errno number (pyarrow's too: "Error writing
    bytes to file. Detail: [errno 28] No space left on device" is "No space left on device")."""
    text = getattr(exc, "strerror", None) or str(exc)
    return re.sub(r"^.*Detail: \[errno \d+\] ", "", text, flags=re.S)


def check_format(path: Path, suffixes=SUFFIXES) -> None:
    if path.suffix.lower() not in suffixes:
        raise InputError(f"output {shown(path)}: the file name must end in {', '.join(suffixes)}")


#: bytes that files written beside an output add to its name: the longest is a CSV sweep's sidecar
#: while it is written, ``.FILE.sweep.json.tmp`` (:mod:`ropemodel.sweeps.store`)
BESIDE = len("." + SIDECAR + ".tmp")
#: the least free space [bytes] an output needs: one file-system block (a full disk has none)
LEAST_FREE = 4096


def shown(path) -> str:
    """``path`` as a message shows it: in full up to 120 characters, else its ends and its length."""
    text = str(path)
    return text if len(text) <= 120 else f"{text[:50]}...{text[-50:]} ({len(text)} characters)"


def check_output(path, suffixes=SUFFIXES) -> Path:
    """``path`` as a Path, or :class:`InputError` if an output cannot be written there.

    The one check of every output of every command, before any work: an empty name, a NUL byte,
    a suffix nothing writes (``suffixes``: the endings accepted, default a sweep's tables,
    :data:`SUFFIXES`), a directory, a path under a regular file or in a missing directory, a name
    or path longer than the file system takes (with the names written beside it, :data:`BESIDE`),
    a directory without write permission or on a read-only file system, a read-only file in the
    way, a full disk; then a file is created beside the output and removed, so whatever else
    refuses a write (a quota, a network share) is found now.  Failures while writing are
    :class:`OutputError` (exit 1), the output left as it was (:func:`write_atomic`)."""
    text = str(path)
    if not text.strip():
        raise InputError(f"output file name is empty; name a file ending in {', '.join(suffixes)}")
    if "\x00" in text:
        raise InputError(f"output {shown(path)}: a file name cannot hold a NUL character")
    p = Path(path)
    try:
        _check_place(p, suffixes)
    except OSError as exc:   # what the probes themselves meet: a name too long, a loop of links ...
        raise InputError(f"cannot write {shown(p)}: {cause(exc)}") from None
    return p


def _check_place(p: Path, suffixes) -> None:
    if p.is_dir():
        raise InputError(f"output {shown(p)} is a directory; name a file in it ending in {', '.join(suffixes)}")
    check_format(p, suffixes)
    parent = p.parent
    if not parent.is_dir():
        above = next((a for a in parent.parents if a.exists()), None) if not parent.exists() else parent
        if above is not None and not above.is_dir():
            raise InputError(f"cannot write {shown(p)}: {shown(above)} is a file, not a directory")
        raise InputError(f"cannot write {shown(p)}: directory {shown(parent)} does not exist")
    longest = os.pathconf(parent, "PC_NAME_MAX") - BESIDE
    if len(os.fsencode(p.name)) > longest:
        raise InputError(f"cannot write {shown(p)}: the file name is {len(os.fsencode(p.name))} bytes long, and this "
                         f"file system takes names of at most {longest} bytes for an output (with the files "
                         f"written beside it)")
    if not os.access(parent, os.W_OK | os.X_OK):
        raise InputError(f"cannot write {shown(p)}: no permission to create files in {shown(parent)}")
    if p.exists() and (not os.access(p, os.W_OK) or not p.stat().st_mode & 0o222):   # the bits: root too
        raise InputError(f"cannot write {shown(p)}: the file is read-only; make it writable or name another file")
    probe = parent / f".{p.name}.{os.getpid()}"   # shorter than BESIDE adds; a stale one is taken over
    os.close(os.open(probe, os.O_WRONLY | os.O_CREAT | os.O_CLOEXEC, 0o644))
    os.unlink(probe)
    free = shutil.disk_usage(parent).free
    if free < LEAST_FREE:
        raise InputError(f"cannot write {shown(p)}: the disk is full ({free} bytes free in {shown(parent)})")


class OutputLock:
    """Exclusive lock on ``path`` for one writer: ``with OutputLock(path): ...``."""

    def __init__(self, path):
        self.path = Path(path)
        self.file = self.path.with_name(self.path.name + ".lock")
        self.fd = None

    def __enter__(self):
        while self.fd is None:
            try:
                fd = os.open(self.file, os.O_RDWR | os.O_CREAT | os.O_CLOEXEC, 0o644)
            except OSError as exc:
                raise InputError(f"cannot write {self.path}: {cause(exc)} ({self.file})") from None
            try:
                fcntl.flock(fd, fcntl.LOCK_EX | fcntl.LOCK_NB)
            except OSError as exc:
                holder = os.pread(fd, 32, 0).decode(errors="replace").strip()
                os.close(fd)
                if isinstance(exc, BlockingIOError):
                    raise InputError(f"{self.path} is being written by another process"
                                     f"{f' (pid {holder})' if holder.isdigit() else ''}; wait for it "
                                     f"to finish, or write to another file") from None
                raise InputError(f"cannot lock {self.file}: {cause(exc)}") from None
            if _same_file(fd, self.file):
                self.fd = fd
            else:  # its previous holder removed it between our open and flock: take the new one
                os.close(fd)
        try:
            os.ftruncate(self.fd, 0)
            os.pwrite(self.fd, f"{os.getpid()}\n".encode(), 0)
        except OSError:  # the pid is only for the message of a refused writer
            pass
        remove(tmp_of(self.path))  # left by a killed writer: no writer holds it now
        return self

    def __exit__(self, *exc):
        remove(self.file)  # while still locked: a process that opened it retries on a new file
        os.close(self.fd)
        self.fd = None


def _same_file(fd, path) -> bool:
    try:
        a, b = os.fstat(fd), os.stat(path)
    except FileNotFoundError:
        return False
    return (a.st_dev, a.st_ino) == (b.st_dev, b.st_ino)


def tmp_of(path: Path) -> Path:
    return path.with_name(f".{path.name}.tmp")


def remove(path: Path) -> None:
    try:
        if path.is_dir() and not path.is_symlink():
            shutil.rmtree(path)
        else:
            path.unlink()
    except FileNotFoundError:
        pass


def _fsync(path: Path) -> None:
    fd = os.open(path, os.O_RDONLY)
    try:
        os.fsync(fd)
    except OSError:  # a directory on a file system that cannot sync one
        if not path.is_dir():
            raise
    finally:
        os.close(fd)


def table_shape(path: Path, suffix: str | None = None) -> tuple[int, list[str]]:
    """(rows, column names) of a CSV or Parquet file, read from the file itself: a Parquet footer;
    a CSV's header as a CSV row (quoted names, commas inside them) and then every row parsed, so
    a torn or ragged file raises (``pyarrow.ArrowInvalid``).  ``suffix``: the format, if not the path's."""
    if (suffix or path.suffix).lower() != ".csv":
        meta = pq.read_metadata(path)
        return meta.num_rows, meta.schema.to_arrow_schema().names
    with open(path, newline="", encoding="utf-8") as f:
        columns = next(csv.reader(f), [])
    # every row is split into its fields (a ragged row raises); one column is kept, as text
    first = columns[:1] if len(set(columns)) == len(columns) else []
    as_text = pacsv.ConvertOptions(include_columns=first, column_types={c: pa.string() for c in columns})
    with pacsv.open_csv(path, convert_options=as_text) as reader:
        rows = sum(batch.num_rows for batch in reader)
    return rows, columns


def verified(tmp: Path, path: Path, rows: int, columns: list[str]) -> tuple[int, list[str]]:
    """The shape of ``tmp`` just written for ``path``; it must be ``rows`` x ``columns`` (else OSError)."""
    try:
        shape = table_shape(tmp, path.suffix)
    except (ValueError, pa.ArrowException) as exc:
        raise OSError(f"the file written cannot be read back ({exc})") from None
    if shape != (rows, list(columns)):
        raise OSError(f"the file written holds {shape[0]} rows x {len(shape[1])} columns, "
                      f"not {rows} x {len(columns)}")
    return shape


def write_atomic(path: Path, write, check=None, durable: bool = True):
    """``write(tmp)`` writes the file, ``check(tmp)`` (if given) reads it back; then it is renamed to
    ``path``, flushed to disk first if ``durable`` (the output, so that a file reported written
    survives a power cut; not the bookkeeping files, whose loss only costs a recompute).  Returns
    what ``check`` returned.  OSError propagates, the temporary file removed."""
    tmp = tmp_of(path)
    try:
        write(tmp)
        checked = check(tmp) if check is not None else None
        if durable:
            _fsync(tmp)
        os.replace(tmp, path)
    except BaseException:
        remove(tmp)
        raise
    if durable:
        _fsync(path.parent)
    return checked


def write_frame(frame, path: Path) -> tuple[int, list[str]]:
    """A pandas DataFrame to CSV or Parquet, atomically, checked by reading it back; its (rows,
    columns); :class:`OutputError` if it cannot be written."""
    if path.suffix.lower() == ".csv":
        def write(tmp):
            frame.to_csv(tmp, index=False)
    else:
        def write(tmp):
            frame.to_parquet(tmp, index=False)
    columns = [str(c) for c in frame.columns]
    try:
        return write_atomic(path, write, lambda tmp: verified(tmp, path, len(frame), columns))
    except OSError as exc:
        raise OutputError(f"cannot write {path}: {cause(exc)}; nothing was written") from None


def _size(nbytes: float) -> str:
    """Bytes in GiB, or MiB below 1 GiB."""
    return f"{nbytes / 2**30:,.1f} GiB" if nbytes >= 2**30 else f"{nbytes / 2**20:,.1f} MiB"


def available_memory() -> int | None:
    """Bytes of memory this process can still take (Linux: MemAvailable, within a cgroup limit)."""
    avail = None
    try:
        with open("/proc/meminfo") as f:
            for line in f:
                if line.startswith("MemAvailable:"):
                    avail = int(line.split()[1]) * 1024
    except (OSError, ValueError, IndexError):
        return None
    try:
        limit = Path("/sys/fs/cgroup/memory.max").read_text().strip()
        used = int(Path("/sys/fs/cgroup/memory.current").read_text())
        if limit != "max" and avail is not None:
            avail = min(avail, int(limit) - used)
    except (OSError, ValueError):
        pass
    return avail


def check_size(n: int, columns: int, *, out=None, collect: bool = True,
               what: str = "collect=True keeps every result in memory") -> None:
    """:class:`InputError` if ``collect`` results (8 bytes a value) cannot fit in memory."""
    mem = available_memory() if collect else None
    if mem is not None and n * columns * 8 > mem:
        where = "" if out is None else f"; its file {out} is written either way, collect=False returns only its path"
        raise InputError(f"{what}: {n:,} points x {columns} columns need "
                         f"{_size(n * columns * 8)}, {_size(mem)} of memory is available{where}")


def check_disk(todo: int, columns: int, out: Path) -> None:
    """:class:`InputError` if ``todo`` points still to compute cannot fit on the disk of ``out``."""
    need = todo * 8 * columns  # the parts alone (uncompressed Arrow, 8 bytes a value): a lower bound
    free = shutil.disk_usage(out.parent).free
    if need > free:
        raise InputError(f"{todo:,} points x {columns} columns need at least {_size(need)} of disk "
                         f"for the sweep's parts beside {out}; {_size(free)} is free there")
