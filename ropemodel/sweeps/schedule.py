"""Chunks of a sweep to their evaluation: in this process, in order, or on an executor with a bounded
window of chunks in flight (memory stays bounded however many chunks there are)."""

from __future__ import annotations

from collections import deque

from ropemodel.sweeps.chunk import run_chunk


def results(job, pts, bounds, todo, executor, run=None):
    """(chunk index, table) in chunk order; with an executor, a bounded window of chunks in flight.  ``run(job,
    start, inputs)`` computes one chunk's table (default :func:`~ropemodel.sweeps.chunk.run_chunk`; it and
    ``job`` must pickle to travel to an executor)."""
    run = run_chunk if run is None else run
    if executor is None:
        for k in todo:
            start, stop = bounds[k]
            yield k, run(job, start, pts.chunk(start, stop))
        return
    window = max(2, 2 * workers(executor))
    pending: deque = deque()
    it = iter(todo)
    try:
        for k in it:
            start, stop = bounds[k]
            pending.append((k, executor.submit(run, job, start, pts.chunk(start, stop))))
            if len(pending) >= window:
                break
        while pending:
            k, fut = pending.popleft()
            result = fut.result()
            nxt = next(it, None)
            if nxt is not None:
                start, stop = bounds[nxt]
                pending.append((nxt, executor.submit(run, job, start, pts.chunk(start, stop))))
            yield k, result
    finally:  # interrupted or failed: chunks not started are not started
        for _, fut in pending:
            fut.cancel()


def workers(executor) -> int:
    """Best guess of the executor's parallelism (only sizes the window of chunks in flight)."""
    n = getattr(executor, "_max_workers", None)
    if n:
        return int(n)
    info = getattr(executor, "nthreads", None)  # dask.distributed.Client
    if callable(info):
        try:
            return max(1, sum(info().values()))
        except Exception:  # a client that cannot answer: assume a small cluster
            return 4
    return 4
