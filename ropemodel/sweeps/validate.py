"""Check every point of a sweep before computing any.

* **Ranges**, vectorised: each varied input's values against its
  :class:`~ropemodel.quantity.Quantity` range; the error names the parameter,
  the value (display unit), the point and the valid range.
* **Cross-parameter rules** (a submodel's ``validate``, e.g. ``L_ul <= L_u``):
  these are scalar Python functions, so each is called once per *distinct
  combination* of the varied inputs it reads — found by recording which keys
  it looks at — not once per point.  A sweep of the inclination alone calls the
  rule ``L_ul <= L_u`` once.
"""

from __future__ import annotations

import itertools
import warnings

import numpy as np

from ropemodel.errors import InputError
from ropemodel.sweeps.points import Grid

MAX_COMBINATIONS = 2_000_000


def check_ranges(points, quantities: dict) -> None:
    """:class:`InputError` for the first value of a varied input outside its valid range."""
    for name in points.names:
        q = quantities[name]
        v = points.values_of(name)
        with np.errstate(invalid="ignore"):
            bad = ~np.isfinite(v) | (v < q.low) | (v > q.high)
            if q.low_open:
                bad |= v == q.low
            if q.high_open:
                bad |= v == q.high
        if bad.any():
            i = int(np.flatnonzero(bad)[0])
            where = f"value {i} of its axis" if isinstance(points, Grid) else f"point {i}"
            raise InputError(
                f"{name} = {q.to_display(v[i]):.6g} {q.display_unit} ({where}) is outside the valid range "
                f"{q.range_text()} ({q.description}); {int(bad.sum())} value(s) out of range"
            )
        with np.errstate(invalid="ignore"):
            beyond = (v < q.warn_low) | (v > q.warn_high)
        if beyond.any():
            from ropemodel.scene import SceneWarning

            source = f"; {q.usual_source}" if q.usual_source else ""
            warnings.warn(f"{name}: {int(beyond.sum())} value(s) outside the range usual for the field, "
                          f"{q.usual_text()} ({q.description}{source})", SceneWarning, stacklevel=3)


class _Recorder(dict):
    """A dict that remembers which keys were looked at."""

    def __init__(self, data):
        super().__init__(data)
        self.seen = set()

    def __getitem__(self, key):
        self.seen.add(key)
        return super().__getitem__(key)

    def __contains__(self, key):
        self.seen.add(key)
        return super().__contains__(key)

    def get(self, key, default=None):
        self.seen.add(key)
        return super().get(key, default)


def check_rules(model, points, base: dict) -> None:
    """Each submodel's cross-parameter rule at every distinct combination of what it reads."""
    params = set(model.parameters)
    base = {k: v for k, v in base.items() if k in params}
    varied = [n for n in points.names if n in params]
    for sm in model.submodels:
        probe = _Recorder({**base, **{n: float(points.values_of(n)[0]) for n in varied}})
        _call(sm, probe, points, "at the first point")
        reads = [n for n in varied if n in probe.seen]
        if not reads:
            continue
        for combo, where in _combinations(points, reads):
            rec = _Recorder({**base, **combo})
            _call(sm, rec, points, where)
            if any(n in rec.seen and n not in reads for n in varied):
                # the rule reads other inputs at other values: check every point
                _check_each(sm, points, base, varied)
                break


def _call(sm, values, points, where):
    broken = sm.rules(values)
    if broken:
        raise InputError(problems=[f"{where}: {b}" if where else b for b in broken])


def _combinations(points, reads):
    if isinstance(points, Grid):
        axes = [points.values_of(n) for n in reads]
        count = int(np.prod([len(a) for a in axes]))
        _limit(count, reads)
        for vals in itertools.product(*axes):
            combo = dict(zip(reads, map(float, vals)))
            yield combo, "at " + ", ".join(f"{k} = {v:.6g}" for k, v in combo.items())
        return
    stacked = np.column_stack([points.values_of(n) for n in reads])
    uniq, first = np.unique(stacked, axis=0, return_index=True)
    _limit(len(uniq), reads)
    for row, i in zip(uniq, first):
        yield dict(zip(reads, map(float, row))), f"point {int(i)}"


def _check_each(sm, points, base, varied):
    _limit(points.n, varied)
    for start in range(0, points.n, 65536):
        chunk = points.chunk(start, min(points.n, start + 65536))
        for i in range(len(chunk[varied[0]])):
            _call(sm, {**base, **{n: float(chunk[n][i]) for n in varied}}, points, f"point {start + i}")


def _limit(count, names):
    if count > MAX_COMBINATIONS:
        raise InputError(f"{count} distinct combinations of {', '.join(names)} to check against the "
                         f"model's cross-parameter rules; sweep fewer values of them at once")


def idle(model, names, outputs, cases=frozenset()) -> None:
    """A :class:`~ropemodel.scene.SceneWarning` naming the varied inputs no output of the sweep depends on,
    neither through the equations nor through the worst case's places and manoeuvres (``cases``)."""
    from ropemodel.scene import SceneWarning

    reads = model.inputs_of(outputs) | set(cases)
    idle = [n for n in names if n not in reads]
    if idle:
        which = ", ".join(outputs) if len(outputs) <= 4 else "the outputs asked for"
        warnings.warn(f"{', '.join(idle)} varied, but no output of this sweep ({which}) depends on "
                      f"{'it' if len(idle) == 1 else 'them'}: the results do not change along "
                      f"{'its' if len(idle) == 1 else 'their'} column", SceneWarning, stacklevel=3)
