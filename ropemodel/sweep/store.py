"""Output files of sweeps: checked before any work, locked, written atomically, resumable.

Checks
    :func:`check_output` refuses an output that cannot be written (unknown suffix, a
    directory, a path under a regular file or in a missing directory, a directory without
    write permission) before anything is computed.
Lock
    :class:`OutputLock` holds an exclusive ``flock`` on ``FILE.lock`` beside the output for
    the whole run, so a second writer of the same output is refused at once.  The kernel
    releases the lock when its process ends, however it ends: a killed sweep never leaves a
    stale lock (the file may stay; the next run takes it over and removes it).
Atomic files
    The output is written under a temporary name (``.FILE.tmp``), flushed to disk (fsync),
    then renamed over ``FILE`` (``os.replace``): ``FILE`` is the complete old file or the
    complete new one, never a part of either.  A failed write removes the temporary file.
Parts
    While a sweep runs, each finished chunk goes to its own Arrow file in a parts directory
    beside the output (``FILE.parquet.parts/part-000012.arrow``), written to a temporary
    name then renamed.  ``manifest.json`` records the sweep's signature (scene, points,
    outputs, chunk size, version).  Rerunning the same sweep checks the finished parts
    (their footers and row counts), computes only the missing chunks, then streams every
    part in order into the output (one Parquet row group per chunk) and removes the parts.
    The output is the same, byte for byte, as that of an uninterrupted run.
Complete outputs
    The signature is also stored in the finished output, so a rerun of a finished sweep
    finds it complete instead of recomputing it.  Parquet holds it in the file's key-value
    metadata (``ropemodel.sweep``).  A CSV file cannot hold it without breaking its readers
    (a comment line fails ``pandas.read_csv`` unless ``comment='#'`` is passed, an extra
    column or row changes the data), so it goes to a sidecar ``FILE.csv.sweep.json`` with
    the CSV's size and SHA-256: the sidecar vouches for exactly those bytes, and an edited,
    truncated or replaced CSV is never taken as complete (it is recomputed).

Test hook: with ``ROPEMODEL_SWEEP_KILL_AFTER=k`` in the environment the process kills
itself (SIGKILL) after committing ``k`` parts, with the next part written but not yet
renamed: the worst moment to die.
"""

from __future__ import annotations

import csv
import fcntl
import hashlib
import json
import os
import shutil
import signal
from pathlib import Path

import pyarrow as pa
import pyarrow.csv as pacsv
import pyarrow.parquet as pq

from ropemodel.errors import InputError, RopeModelError

KILL_HOOK = "ROPEMODEL_SWEEP_KILL_AFTER"
META_KEY = b"ropemodel.sweep"
SIDECAR = ".sweep.json"


class OutputError(RopeModelError):
    """An output file could not be written (disk full, I/O error); CLI exit status 1."""


def cause(exc: OSError) -> str:
    """The reason of an OSError in words, without the errno number."""
    return getattr(exc, "strerror", None) or str(exc)


def _write_parquet(tables, schema, path):
    with pq.ParquetWriter(path, schema) as writer:
        for t in tables:
            writer.write_table(t)


def _write_csv(tables, schema, path):
    with pacsv.CSVWriter(str(path), schema) as writer:
        for t in tables:
            writer.write_table(t)


def _write_part(table, path):
    with pa.OSFile(str(path), "wb") as sink, pa.ipc.new_file(sink, table.schema) as writer:
        writer.write_table(table)


#: output suffix → writer(tables iterator, schema, path)
FORMATS = {".parquet": _write_parquet, ".pq": _write_parquet, ".csv": _write_csv}


def check_format(path: Path) -> None:
    if path.suffix.lower() not in FORMATS:
        raise InputError(f"output {path}: the file name must end in {', '.join(FORMATS)}")


def check_output(path) -> Path:
    """``path`` as a Path, or :class:`InputError` if an output cannot be written there."""
    p = Path(path)
    if p.is_dir():
        raise InputError(f"output {p} is a directory; name a file in it ending in {', '.join(FORMATS)}")
    check_format(p)
    parent = p.parent
    if not parent.is_dir():
        above = next((a for a in parent.parents if a.exists()), None) if not parent.exists() else parent
        if above is not None and not above.is_dir():
            raise InputError(f"cannot write {p}: {above} is a file, not a directory")
        raise InputError(f"cannot write {p}: directory {parent} does not exist")
    if not os.access(parent, os.W_OK | os.X_OK):
        raise InputError(f"cannot write {p}: no permission to create files in {parent}")
    return p


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
        for left in (self.path, self.path.with_name(self.path.name + SIDECAR)):
            _remove(_tmp_of(left))  # left by a killed writer: no writer holds them now
        return self

    def __exit__(self, *exc):
        _remove(self.file)  # while still locked: a process that opened it retries on a new file
        os.close(self.fd)
        self.fd = None


def _same_file(fd, path) -> bool:
    try:
        a, b = os.fstat(fd), os.stat(path)
    except FileNotFoundError:
        return False
    return (a.st_dev, a.st_ino) == (b.st_dev, b.st_ino)


def _tmp_of(path: Path) -> Path:
    return path.with_name(f".{path.name}.tmp")


def _remove(path: Path) -> None:
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


def _verified(tmp: Path, path: Path, rows: int, columns: list[str]) -> tuple[int, list[str]]:
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
    tmp = _tmp_of(path)
    try:
        write(tmp)
        checked = check(tmp) if check is not None else None
        if durable:
            _fsync(tmp)
        os.replace(tmp, path)
    except BaseException:
        _remove(tmp)
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
        return write_atomic(path, write, lambda tmp: _verified(tmp, path, len(frame), columns))
    except OSError as exc:
        raise OutputError(f"cannot write {path}: {cause(exc)}; nothing was written") from None


def _sha256(path: Path) -> str:
    h = hashlib.sha256()
    with open(path, "rb") as f:
        for block in iter(lambda: f.read(1 << 20), b""):
            h.update(block)
    return h.hexdigest()


def _dumps(signature: dict) -> str:
    return json.dumps(signature, sort_keys=True)


def complete_rows(path: Path, signature: dict) -> int | None:
    """Rows of ``path`` if it is the finished output of the sweep ``signature``, else None."""
    try:
        if path.suffix.lower() == ".csv":
            side = json.loads(path.with_name(path.name + SIDECAR).read_text())
            if (side.get("signature") != signature or side.get("bytes") != path.stat().st_size
                    or side.get("sha256") != _sha256(path)):
                return None
            return int(side["rows"])
        meta = pq.read_metadata(path)
        stored = (meta.metadata or {}).get(META_KEY)
        if stored is None or json.loads(stored) != signature or meta.num_rows != signature["n_points"]:
            return None
        return meta.num_rows
    except (OSError, ValueError, KeyError, TypeError, pa.ArrowException):
        return None


def discard_parts(path: Path, signature: dict) -> None:
    """Remove the parts of ``path`` if they belong to the sweep ``signature`` (whose output is finished)."""
    parts = path.with_name(path.name + ".parts")
    try:
        if json.loads((parts / "manifest.json").read_text()) == signature:
            _remove(parts)
    except (OSError, ValueError):
        pass


def read_output(path: Path, types: dict) -> pa.Table:
    """A finished output back as a table; ``types`` label → Arrow type (CSV does not keep them)."""
    if path.suffix.lower() == ".csv":
        return pacsv.read_csv(path, convert_options=pacsv.ConvertOptions(column_types=types))
    return pq.read_table(path).replace_schema_metadata(None)


class ChunkStore:
    """The parts of one sweep's output ``path``; the caller holds its :class:`OutputLock`.

    bounds: (start, stop) of every chunk; ``done`` holds the chunks already on disk.
    """

    def __init__(self, path, signature: dict, bounds, restart: bool = False):
        self.path = Path(path)
        self.parts = self.path.with_name(self.path.name + ".parts")
        self.signature, self.bounds = signature, list(bounds)
        self._committed = 0
        self._kill_after = int(os.environ.get(KILL_HOOK, "-1"))
        try:
            self.done = self._open(restart)
        except OSError as exc:
            raise OutputError(f"cannot use {self.parts}: {cause(exc)}") from None

    def _open(self, restart) -> set[int]:
        manifest = self.parts / "manifest.json"
        old = None
        if self.parts.is_dir() and not restart:
            try:
                old = json.loads(manifest.read_text())
            except (OSError, ValueError):  # no manifest, or a torn one: nothing to resume
                old = None
        if old is not None and old != self.signature:
            changed = sorted(k for k in set(old) | set(self.signature) if old.get(k) != self.signature.get(k))
            raise InputError(f"{self.parts} holds an unfinished sweep with other settings "
                             f"({', '.join(changed)} differ); rerun that sweep, or restart "
                             f"(--restart / restart=True) to discard it")
        if old is None:  # the parts directory is made when the first chunk is committed
            _remove(self.parts)
            return set()
        for tmp in self.parts.glob("*.tmp"):  # a part being written when its writer died
            tmp.unlink()
        return {k for k in range(len(self.bounds)) if self._intact(k)}

    def _start(self) -> None:
        self.parts.mkdir()
        write_atomic(self.parts / "manifest.json",
                     lambda tmp: tmp.write_text(json.dumps(self.signature, indent=1, sort_keys=True)), durable=False)

    @property
    def resumable(self) -> bool:
        """Finished chunks are on disk: a rerun of the same sweep resumes from them."""
        return self.parts.is_dir()

    def _intact(self, k: int) -> bool:
        """Part ``k`` is on disk, readable and holds its chunk's rows (else it is removed: recomputed)."""
        part = self._part(k)
        if not part.exists():
            return False
        try:
            with pa.memory_map(str(part)) as source:
                reader = pa.ipc.open_file(source)
                rows = sum(reader.get_batch(i).num_rows for i in range(reader.num_record_batches))
        except (OSError, pa.ArrowException):
            rows = -1
        start, stop = self.bounds[k]
        if rows != stop - start:
            part.unlink()
            return False
        return True

    @property
    def done_points(self) -> int:
        return sum(self.bounds[k][1] - self.bounds[k][0] for k in self.done)

    def _part(self, k: int) -> Path:
        return self.parts / f"part-{k:06d}.arrow"

    def _failed(self, exc: OSError, what: Path) -> OutputError:
        if not self.done:
            return OutputError(f"cannot write {what}: {cause(exc)}; nothing was written")
        return OutputError(f"cannot write {what}: {cause(exc)}; {self.done_points} of {self.bounds[-1][1]} "
                           f"points are done and kept in {self.parts}: rerun the same command to resume")

    def write(self, k: int, table: pa.Table) -> None:
        """Commit chunk ``k`` atomically; :class:`OutputError` if it cannot be written."""
        part = self._part(k)
        tmp = part.with_suffix(".tmp")
        try:
            if not self.parts.is_dir():
                self._start()
            _write_part(table, tmp)
            if self._committed == self._kill_after:
                os.kill(os.getpid(), signal.SIGKILL)
            os.replace(tmp, part)
        except OSError as exc:
            _remove(self.parts if not self.done else tmp)
            raise self._failed(exc, part) from None
        except BaseException:
            _remove(tmp)
            raise
        self.done.add(k)
        self._committed += 1

    def read(self, k: int) -> pa.Table:
        with pa.memory_map(str(self._part(k))) as source:
            return pa.ipc.open_file(source).read_all()

    def finish(self) -> tuple[int, list[str]]:
        """Stream every part, in order, into the output file (with the sweep's signature), read it
        back, put it in place; remove the parts.  The file's (rows, columns); :class:`OutputError`
        (parts kept) if it cannot be written."""
        missing = [k for k in range(len(self.bounds)) if k not in self.done]
        if missing:
            raise RuntimeError(f"chunks {missing[:5]} missing from {self.parts}")
        text = _dumps(self.signature)
        schema = self.read(0).schema.with_metadata({META_KEY: text.encode()})
        writer = FORMATS[self.path.suffix.lower()]  # looked up now: tests replace it
        rows = self.bounds[-1][1]
        try:
            shape = write_atomic(self.path, lambda tmp: writer((self.read(k) for k in range(len(self.bounds))),
                                                               schema, tmp),
                                 lambda tmp: _verified(tmp, self.path, rows, schema.names))
            if self.path.suffix.lower() == ".csv":
                side = {"signature": self.signature, "rows": rows,
                        "bytes": self.path.stat().st_size, "sha256": _sha256(self.path)}
                write_atomic(self.path.with_name(self.path.name + SIDECAR),
                             lambda tmp: tmp.write_text(json.dumps(side, indent=1, sort_keys=True)), durable=False)
        except OSError as exc:
            raise self._failed(exc, self.path) from None
        _remove(self.parts)
        return shape
