"""Write a scene's SI parameter values as TOML lines, each dimensional value with its SI unit."""

from __future__ import annotations


def parameters_toml(scene) -> str:
    """``name = "value unit"`` lines (``name = value`` for pure numbers) of every parameter of ``scene``."""
    q = scene.built.quantities
    lines = []
    for k, v in scene.parameters.items():
        lines.append(f"{k} = {v!r}" if q[k].dimensionless else f'{k} = "{v!r} {q[k].unit}"')
    return "\n".join(lines)
