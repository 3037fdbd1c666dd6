"""The sections of a report: each a function ``ctx -> HTML fragment`` and a predicate saying when it applies.

Sections are registered with :func:`section` when their module is imported; the modules are imported
in the order of :data:`ropemodel.reports.sections.MODULES`, so the page shows the sections in that
order (and, within a module, in the order they are defined).  A section a machine declares
(:attr:`ropemodel.machines.Machine.sections`) is a section of that machine's scenes only (:func:`declared`);
a section no machine declares is every scene's.
"""

from __future__ import annotations

from dataclasses import dataclass
from collections.abc import Callable

from ropemodel.machines import MACHINES


def always(ctx) -> bool:
    """The predicate of a section every report has."""
    return True


@dataclass(frozen=True)
class Section:
    """One section of the report.

    name: a short identifier, also the fragment the table of contents links to (``#name``).
    title: the heading shown on the page.
    render: ``render(ctx) -> str``, the section's HTML (a fragment: no ``<html>``, no ``<section>``); text
        from the scene must be escaped (the helpers of :mod:`ropemodel.reports.page` do).
    applies: ``applies(ctx) -> bool``; a section whose predicate is false is left out of the page.
    reads: ``reads(ctx) -> set of parameter names`` its numbers are computed from beyond the inputs of the
        equations every report shows (a trip, the sizing, a transient), or None for none beyond them: the
        report relies on a default only where one of its sections reads it (:attr:`Context.reads
        <ropemodel.reports.context.Context.reads>`).
    """

    name: str
    title: str
    render: Callable
    applies: Callable = always
    reads: Callable | None = None


#: every registered section, in page order
SECTIONS: list[Section] = []


def declared(name: str, scene) -> bool:
    """Whether section ``name`` may show for ``scene``: a section some machine declares, for a scene of such a
    machine; any other section, for every scene."""
    owners = [m.model for m in MACHINES.values() if name in m.sections]
    return not owners or scene.model in owners


def section(name: str, title: str, when: Callable = always, reads: Callable | None = None):
    """Decorator: register ``render(ctx) -> HTML`` as the section ``name`` shown when ``when(ctx)`` holds, its
    numbers computed from the equations' inputs and ``reads(ctx)`` (:class:`Section`)."""

    def deco(render: Callable) -> Callable:
        if any(s.name == name for s in SECTIONS):
            raise RuntimeError(f"report section {name!r} registered twice")
        SECTIONS.append(Section(name, title, render, when, reads))
        return render

    return deco


def sections() -> list[Section]:
    """Every registered section, in page order (their modules imported first)."""
    from ropemodel.reports.sections import load_all

    load_all()
    return list(SECTIONS)
