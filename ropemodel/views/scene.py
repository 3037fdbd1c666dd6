"""What a :class:`ropemodel.scene.Scene` shows: one line in a repr, its inputs as a table in Jupyter."""

from __future__ import annotations

from typing import Any

from ropemodel.views import html


class SceneViews:
    """A one-line ``repr`` and a ``_repr_html_`` table of a :class:`~ropemodel.scene.Scene`."""

    name: str
    model: str
    effects: dict[str, str]
    parameters: dict[str, float]
    source: str | None
    origin: dict[str, str]
    defaults: dict[str, str]

    def _chosen(self) -> dict[str, str]:
        """The effects whose variant is not the default."""
        from ropemodel.effects import effects_of

        specs = effects_of(self.model)
        return {e: v for e, v in self.effects.items() if e not in specs or v != specs[e].default}

    def __repr__(self) -> str:
        chosen = " ".join(f"{e}={v}" for e, v in self._chosen().items())
        where = f", from {self.source}" if self.source else ""
        return (f"<Scene {self.name!r}: {self.model}, {len(self.parameters)} parameters"
                + (f", {chosen}" if chosen else "") + f"{where}>")

    def _repr_html_(self) -> str:
        r: Any = self         # a Scene: its built model declares every quantity
        q = r.built.quantities
        rows = [(n, q[n].to_display(v), html.unit_text(q[n].display_unit), self.origin.get(n, ""))
                for n, v in self.parameters.items()]
        effects = ", ".join(f"{e}={v}" for e, v in self.effects.items())
        return html.page(f"{self.name} (model {self.model})", html.table(("name", "value", "unit", "from"), rows,
                                                                          "parameters"),
                         notes=[f"effects: {effects}", f"file: {self.source}" if self.source else ""])
