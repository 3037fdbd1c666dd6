"""Section "rules": the rule set the checks apply (source, status), the length its formulas are taken at,
each factor with its provenance (rule, override and its reason, default or user-given), and every rule of
the set with what it does for this machine."""

from __future__ import annotations

from ropemodel.reports import page
from ropemodel.reports.registry import section
from ropemodel.rules import registry
from ropemodel.rules.describe import factors, lengths, rule_rows
from ropemodel.rules.vocabulary import STATUSES

HEAD = """<dl class="head">
<dt>rule set</dt><dd><code>{{ rs.name }}</code>: {{ rs.title }}</dd>
<dt>authority</dt><dd>{{ rs.authority }}</dd>
<dt>source</dt><dd>{{ rs.source }}</dd>
<dt>where to read it</dt><dd>{{ rs.url }}</dd>
<dt>status</dt><dd>{{ rs.status }} (the weakest of its rules)</dd>
{% if choices %}<dt>chosen</dt><dd>{{ choices }}</dd>{% endif %}
</dl>{% if rs.notes %}<p class="note">{{ rs.notes }}</p>{% endif %}"""


def _applies(ctx) -> bool:
    return bool(factors(ctx.scene))


@section("rules", "Rules", when=_applies)
def rules(ctx):
    scene = ctx.scene
    applied = scene.rules
    if applied is None:
        machine = scene.built.name
        fits = [n for n, s in registry.rule_sets().items() if machine in s.machines]
        html = page.fragment("<p>No rule set: each factor below is user-given or a default, with no source. A "
                             "scene picks one with <code>[rules] set = \"...\"</code>; rule sets written for this "
                             "machine: {{ fits }}.</p>", fits=", ".join(fits) or "none")
    else:
        rs = applied.ruleset
        html = page.fragment(HEAD, rs=rs, choices=", ".join(f"{k} = {v}" for k, v in applied.choices.items()))
        html += _lengths(scene)
    html += page.fragment("<h3>Factors of the checks</h3>")
    q = scene.built.quantities
    rows = [[p, page.show(q[p], e["value"]), e["basis"], e["text"], ", ".join(e["checks"])]
            for p, e in factors(scene).items()]
    html += page.table(["parameter", "value", "from", "what it rests on", "checks"], rows,
                       kinds=["name", "num", "", "", ""], cls="factors")
    if applied is not None:
        html += page.fragment("<h3>Every rule of the set</h3>")
        rows = [[r["rule"], r["governs"], r["clause"], r["formula"], r["status"], r["here"], r["evidence"]]
                for r in rule_rows(scene)]
        html += page.table(["rule", "governs", "clause", "formula", "status", "here", "evidence"], rows,
                           kinds=["name", "", "", "", "", "", ""], cls="rules")
    html += page.fragment("<p class=\"note\">Statuses: {{ s }}.</p>",
                          s="; ".join(f"{k}: {v}" for k, v in STATUSES.items()))
    return html


def _lengths(scene):
    found = lengths(scene)
    if not found:
        return ""
    rows = [[name, "-" if e["value"] is None else f"{e['value']:.6g} m ({e['value'] / 0.3048:.6g} ft)",
             e["definition"], e["status"]] for name, e in found.items()]
    return page.fragment("<h3>Lengths the rules are taken at</h3>") + page.table(
        ["length", "value", "what it is for this machine", "status"], rows, kinds=["name", "num", "", ""],
        cls="lengths")
