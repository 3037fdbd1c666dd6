"""Chunked, resumable storage of a sweep's results.

While a sweep runs, each finished chunk is written to its own Arrow file in a
parts directory beside the output (``FILE.parquet.parts/part-000012.arrow``):
written to a temporary name, then renamed, so a part is either complete or
absent whatever moment the process dies.  A ``manifest.json`` records a
signature of the sweep (scene, points, outputs, chunk size); rerunning the
same sweep finds the finished parts, computes only the missing chunks, then
streams every part in order into the output file (CSV or Parquet, one row
group per chunk) and removes the parts directory.  The output is the same,
byte for byte, as that of an uninterrupted run.

Test hook: with ``ROPEMODEL_SWEEP_KILL_AFTER=k`` in the environment the
process kills itself (SIGKILL) after committing ``k`` parts, with the next part
written but not yet renamed: the worst moment to die.
"""

from __future__ import annotations

import json
import os
import shutil
import signal
from pathlib import Path

import pyarrow as pa
import pyarrow.csv as pacsv
import pyarrow.parquet as pq

from ropemodel.errors import InputError

KILL_HOOK = "ROPEMODEL_SWEEP_KILL_AFTER"


def _write_parquet(tables, schema, path):
    with pq.ParquetWriter(path, schema) as writer:
        for t in tables:
            writer.write_table(t)


def _write_csv(tables, schema, path):
    with pacsv.CSVWriter(str(path), schema) as writer:
        for t in tables:
            writer.write_table(t)


#: output suffix → writer(tables iterator, schema, path)
FORMATS = {".parquet": _write_parquet, ".pq": _write_parquet, ".csv": _write_csv}


def check_format(path: Path) -> None:
    if path.suffix.lower() not in FORMATS:
        raise InputError(f"output {path}: the file name must end in {', '.join(FORMATS)}")


class ChunkStore:
    """The parts of one sweep's output ``path``; ``done`` holds the chunks already on disk."""

    def __init__(self, path, signature: dict, restart: bool = False):
        self.path = Path(path)
        check_format(self.path)
        self.parts = self.path.with_name(self.path.name + ".parts")
        self.signature = signature
        manifest = self.parts / "manifest.json"
        if self.parts.exists() and (restart or not manifest.exists()):
            shutil.rmtree(self.parts)
        if self.parts.exists():
            old = json.loads(manifest.read_text())
            if old != signature:
                changed = sorted(k for k in set(old) | set(signature) if old.get(k) != signature.get(k))
                raise InputError(f"{self.parts} holds an unfinished sweep with other settings "
                                 f"({', '.join(changed)} differ); rerun that sweep, or restart "
                                 f"(--restart / restart=True) to discard it")
        else:
            self.parts.mkdir(parents=True)
            tmp = manifest.with_suffix(".tmp")
            tmp.write_text(json.dumps(signature, indent=1, sort_keys=True))
            os.replace(tmp, manifest)
        self.done = {int(p.stem.split("-")[1]) for p in self.parts.glob("part-*.arrow")}
        self._committed = 0
        self._kill_after = int(os.environ.get(KILL_HOOK, "-1"))

    def _part(self, k: int) -> Path:
        return self.parts / f"part-{k:06d}.arrow"

    def write(self, k: int, table: pa.Table) -> None:
        """Commit chunk ``k`` atomically."""
        tmp = self._part(k).with_suffix(".tmp")
        with pa.OSFile(str(tmp), "wb") as sink, pa.ipc.new_file(sink, table.schema) as writer:
            writer.write_table(table)
        if self._committed == self._kill_after:
            os.kill(os.getpid(), signal.SIGKILL)
        os.replace(tmp, self._part(k))
        self.done.add(k)
        self._committed += 1

    def read(self, k: int) -> pa.Table:
        with pa.memory_map(str(self._part(k))) as source:
            return pa.ipc.open_file(source).read_all()

    def finish(self, n_chunks: int) -> None:
        """Stream every part, in order, into the output file; then remove the parts."""
        missing = [k for k in range(n_chunks) if k not in self.done]
        if missing:
            raise RuntimeError(f"chunks {missing[:5]} missing from {self.parts}")
        schema = self.read(0).schema
        tmp = self.path.with_name(self.path.name + ".tmp")
        FORMATS[self.path.suffix.lower()]((self.read(k) for k in range(n_chunks)), schema, tmp)
        os.replace(tmp, self.path)
        shutil.rmtree(self.parts)
