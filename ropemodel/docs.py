"""The documentation's reference tables, generated from the effect registry, and the output of ``ropemodel run``
the site shows (``python -m ropemodel.docs``).

A page holds each table between ``<!-- generated: NAME -->`` and ``<!-- end: NAME -->``;
:func:`render` returns the tables, :func:`update` rewrites them in a page, and a test checks
that each committed page equals what :func:`update` would write (so the tables never drift from
the code).  Tables: ``effects`` (every effect and variant of every model), per model
``parameters-MODEL`` (unit, meaning, default and why, valid range and usual range, each with its source),
``outputs-MODEL`` (unit, meaning, equation), ``variants-MODEL`` (every variant of every effect: what it
builds, its parameters, what it computes with each equation's source, its papers) and ``numerics-MODEL``
(the ``[numerics]`` options), and ``rule-sets`` and ``rules`` (every shipped rule set and rule, with its
source and status); the site's scene reference (``docs/scenes.md``) holds them all.  A page may also show
what ``ropemodel run`` prints, ``run-example`` (:data:`OUTPUTS`: a command's output, computed only for a
file that holds it).  ``python -m ropemodel.docs`` rewrites every file of :func:`files`.
"""

from __future__ import annotations

import functools
import math
import re
import sys
from pathlib import Path

from ropemodel.effects import REGISTRY, all_quantities, effects_of, models, numerics_of

_BLOCK = re.compile(r"(<!-- generated: (?P<name>[\w-]+) -->\n)(?P<body>.*?)(<!-- end: (?P=name) -->)", re.S)


def effects_table() -> str:
    """Markdown: model, effect, variants (default in bold), what the effect does."""
    rows = ["| model | effect | variants (default in bold) | what it builds |", "|---|---|---|---|"]
    for model in models():
        for name, spec in effects_of(model).items():
            variants = ", ".join(f"**`{v}`**" if v == spec.default else f"`{v}`" for v in spec.variants)
            rows.append(f"| {model} | `{name}` | {variants} | {spec.doc} |")
    return "\n".join(rows)


@functools.cache
def _roles(model: str) -> tuple[tuple[str, ...], tuple[str, ...]]:
    """(parameters, outputs) of ``model`` over every variant (a name computed by one variant and given
    to another, e.g. the sheave's Q_R, is in both).  Cached: it builds a model per variant, and the registry
    does not change after import."""
    from ropemodel.core.model import Model

    outputs: dict[str, None] = {}
    parameters: dict[str, None] = {}
    for effect, spec in effects_of(model).items():
        for variant in spec.variants:
            m = Model(model, {effect: variant})
            outputs.update(dict.fromkeys(m.outputs))
            parameters.update(dict.fromkeys(m.parameters))
    declared = list(all_quantities(model))
    return tuple(n for n in declared if n in parameters), tuple(n for n in declared if n in outputs)


def _unit(q) -> str:
    return "-" if q.display_unit in ("1", "") else q.display_unit


def parameters_table(model: str) -> str:
    """Markdown: every parameter of ``model``, with default, valid range and usual range (and source)."""
    q = all_quantities(model)
    rows = ["| name | unit | meaning | default | valid range (source) | usual range (source) |",
            "|---|---|---|---|---|---|"]
    for name in _roles(model)[0]:
        x = q[name]
        default = "required" if x.default is None else (
            f"{x.show(x.default)}: {x.default_note}" if x.default_note else x.show(x.default))
        usual = ("" if x.warn_low == -math.inf and x.warn_high == math.inf
                 else f"{x.usual_text()}" + (f" ({x.usual_source})" if x.usual_source else ""))
        valid = x.range_text() + (f" ({x.range_source})" if x.range_source else "")
        rows.append(f"| `{name}` | {_unit(x)} | {x.description} | {default} | {valid} | {usual} |")
    return "\n".join(rows)


def outputs_table(model: str) -> str:
    """Markdown: every quantity ``model`` computes, with its unit and equation."""
    q = all_quantities(model)
    rows = ["| name | unit | meaning | source |", "|---|---|---|---|"]
    for name in _roles(model)[1]:
        rows.append(f"| `{name}` | {_unit(q[name])} | {q[name].description} | {q[name].equation} |")
    return "\n".join(rows)


def run_example() -> str:
    """What ``ropemodel run`` prints (the built-in example, Krauze et al. 2025, Fig. 9), as a text block."""
    from ropemodel.problem import run
    from ropemodel.scene import load

    return f"```text\n{run(load(emit=False)).table()}\n```"


#: blocks of a command's output, computed only where a file holds them
OUTPUTS = {"run-example": run_example}


def variants_table(model: str) -> str:
    """Markdown: every variant of every effect of ``model``: what it builds, the parameters its equations
    use (or that it declares, for a transient variant), what it computes with each equation's source,
    and the papers it cites."""
    from ropemodel.core.model import Model

    rows = ["| effect | variant | what it builds | parameters | computes (source) | cites |",
            "|---|---|---|---|---|---|"]
    base = Model(model).parameters
    for effect, spec in effects_of(model).items():
        for variant, cls in spec.variants.items():
            m = Model(model, {effect: variant})
            eqs = [eq for eq in m.equations if m.defined_by[eq.defines] == effect]
            used = dict.fromkeys(n for eq in eqs for n in eq.names() if n in m.parameters)
            used.update(dict.fromkeys(q.name for q in cls.quantities if q.name not in m.outputs))
            used.update(dict.fromkeys(n for n in m.parameters if n not in base))   # what choosing it asks
            computes = "; ".join(f"`{eq.defines}` ({eq.source})" if eq.source else f"`{eq.defines}`" for eq in eqs)
            name = f"**`{variant}`**" if variant == spec.default else f"`{variant}`"
            rows.append(f"| `{effect}` | {name} | {cls.description or spec.doc} | "
                        f"{', '.join(f'`{n}`' for n in used) or '-'} | {computes or '-'} | "
                        f"{', '.join(cls.citations) or '-'} |")
    return "\n".join(rows)


def numerics_table(model: str) -> str:
    """Markdown: every ``[numerics]`` option of ``model`` with its default and what it sets."""
    rows = ["| option | default | what it sets |", "|---|---|---|"]
    for key, opt in numerics_of(model).items():
        rows.append(f"| `{key}` | `{opt.default!r}` | {opt.doc} |")
    return "\n".join(rows)


def rule_sets_table() -> str:
    """Markdown: every shipped rule set, the machines it is written for, its source and its status."""
    from ropemodel.rules import rule_sets

    rows = ["| rule set | written for | source | status |", "|---|---|---|---|"]
    for name, rs in rule_sets().items():
        rows.append(f"| `{name}` | {', '.join(rs.machines)} | [{rs.title}]({rs.url}) | {rs.status} |")
    return "\n".join(rows)


def rules_table() -> str:
    """Markdown: every rule of every set: what it governs, where it applies, its formula, clause and status."""
    from ropemodel.rules import rule_sets

    rows = ["| rule set | rule | governs | where | value | clause | status |", "|---|---|---|---|---|---|---|"]
    for name, rs in rule_sets().items():
        for r in rs.rules:
            where = ", ".join(f"{k} = {'/'.join(v)}" for k, v in r.where.items()) or "-"
            rows.append(f"| `{name}` | `{r.id}` | {r.governs} | {where} | {r.unicode()} | {r.clause} | {r.status} |")
    return "\n".join(rows)


def render() -> dict[str, str]:
    """Every generated block by its name."""
    out = {"effects": effects_table(), "rule-sets": rule_sets_table(), "rules": rules_table()}
    for model in REGISTRY:
        out[f"parameters-{model}"] = parameters_table(model)
        out[f"outputs-{model}"] = outputs_table(model)
    for model in REGISTRY:        # the site's scene reference (docs/scenes.md) also holds these
        out[f"variants-{model}"] = variants_table(model)
        out[f"numerics-{model}"] = numerics_table(model)
    return out


def update(text: str) -> str:
    """``text`` with every generated block replaced by its current table (unknown blocks are an error)."""
    tables = render()
    tables.update({name: block() for name, block in OUTPUTS.items() if f"<!-- generated: {name} -->" in text})

    def fill(m):
        if m["name"] not in tables:
            raise KeyError(f"no generated table {m['name']!r}; known: {', '.join(tables)}")
        return f"{m.group(1)}{tables[m['name']]}\n{m.group(4)}"

    return _BLOCK.sub(fill, text)


def pages(root: Path | str = ".") -> list[Path]:
    """README.md and every page of the site (``docs/**/*.md``; the built site and the generated gallery left out)."""
    docs = Path(root) / "docs"
    site = (p for p in docs.rglob("*.md") if not {"_build", "gallery"} & set(p.relative_to(docs).parts))
    return [Path(root) / "README.md", *sorted(site)]


def files(root: Path | str = ".") -> list[Path]:
    """The files whose generated blocks ``python -m ropemodel.docs`` rewrites by default: those of
    :func:`pages` that hold one."""
    return [p for p in pages(root) if p.exists() and "<!-- generated: " in p.read_text(encoding="utf-8")]


def main(argv=None) -> int:
    """``python -m ropemodel.docs [FILE ...]``: rewrite the generated tables in place (default: :func:`files`
    of the current folder)."""
    for name in argv or sys.argv[1:] or files():
        path = Path(name)
        path.write_text(update(path.read_text(encoding="utf-8")), encoding="utf-8")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
