"""Chunked, resumable storage of a sweep's results, and finished outputs found again.

The output itself is checked, locked and written atomically by :mod:`ropemodel.sweeps.files`.

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
    metadata (``ropemodel.sweeps``).  A CSV file cannot hold it without breaking its readers
    (a comment line fails ``pandas.read_csv`` unless ``comment='#'`` is passed, an extra
    column or row changes the data), so it goes to a sidecar ``FILE.csv.sweep.json`` with
    the CSV's size and SHA-256: the sidecar vouches for exactly those bytes, and an edited,
    truncated or replaced CSV is never taken as complete (it is recomputed).

Test hook: with ``ROPEMODEL_SWEEP_KILL_AFTER=k`` in the environment the process kills
itself (SIGKILL) after committing ``k`` parts, with the next part written but not yet
renamed: the worst moment to die.
"""

from __future__ import annotations

import hashlib
import json
import os
import signal
from pathlib import Path

import pyarrow as pa
import pyarrow.csv as pacsv
import pyarrow.parquet as pq

from ropemodel.errors import InputError
from ropemodel.sweeps.files import SIDECAR, OutputError, cause, remove, tmp_of, verified, write_atomic

KILL_HOOK = "ROPEMODEL_SWEEP_KILL_AFTER"
META_KEY = b"ropemodel.sweeps"


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


#: output suffix (:data:`ropemodel.sweeps.files.SUFFIXES`) → writer(tables iterator, schema, path)
FORMATS = {".parquet": _write_parquet, ".pq": _write_parquet, ".csv": _write_csv}


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
            remove(parts)
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
        remove(tmp_of(self.path.with_name(self.path.name + SIDECAR)))  # left by a killed writer
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
            remove(self.parts)
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
            remove(self.parts if not self.done else tmp)
            raise self._failed(exc, part) from None
        except BaseException:
            remove(tmp)
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
                                 lambda tmp: verified(tmp, self.path, rows, schema.names))
            if self.path.suffix.lower() == ".csv":
                side = {"signature": self.signature, "rows": rows,
                        "bytes": self.path.stat().st_size, "sha256": _sha256(self.path)}
                write_atomic(self.path.with_name(self.path.name + SIDECAR),
                             lambda tmp: tmp.write_text(json.dumps(side, indent=1, sort_keys=True)), durable=False)
        except OSError as exc:
            raise self._failed(exc, self.path) from None
        remove(self.parts)
        return shape
