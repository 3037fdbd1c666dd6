"""Section "sensitivity": what matters most, as tornado charts of the elasticities of a few headline results.

Headline results are the ones a designer sizes with: the rope force F_C, the tensioner's stroke need
ΔF and the drive power N_p of a winch (the direction with the larger magnitude), the tension S of a
sheave, the stiffness K and the rotation of a capstan drive, the largest rope pull T_max, the static
anti-slip factor and the slip limit of an emergency stop lowering the load of a Koepe hoist.  A model
with none of them shows the results that depend on the most inputs.
"""

from __future__ import annotations

from ropemodel.reports import figures, page
from ropemodel.reports.registry import section

#: headline results, by name (``base`` matches ``base``, ``base_up`` and ``base_down``), in order
HEADLINE = ("F_C", "dF", "N_p", "S", "K", "delta_alpha", "T_max", "sigma_static", "a_slip_lower_decel")
#: how many outputs, and how many inputs per chart
OUTPUTS, TOP = 3, 8


def headline(model, values: dict) -> list[str]:
    """The few outputs the sensitivity charts show (see the module docstring)."""
    chosen = []
    for base in HEADLINE:
        pair = [n for n in (f"{base}_up", f"{base}_down") if n in model.outputs]
        if pair:
            chosen.append(max(pair, key=lambda n: abs(values.get(n, 0.0))))
        elif base in model.outputs:
            chosen.append(base)
    if not chosen:
        plain = [o for o in model.outputs if "_margin" not in o and not o.endswith("_error") and o != "regime"]
        chosen = sorted(plain, key=lambda o: -len(model.inputs_of([o])))
    return chosen[:OUTPUTS]


@section("sensitivity", "What matters most")
def sensitivity(ctx):
    from ropemodel.sensitivities import elasticities

    result = ctx.result
    outputs = headline(result.model, result.values)
    frame = elasticities(ctx.point, outputs=outputs)
    html = page.fragment("<p>Elasticities ∂ln y/∂ln p{{ at }}: the percentage change of a result per percent change "
                         "of an input (exact derivatives of the model), the {{ top }} largest of each. Red: the result "
                         "rises with the input; blue: it falls.</p>", top=TOP,
                         at=" at the recommended design" if ctx.at_design else "")
    pictures = [(o, figures.tornado(frame, o, TOP)) for o in outputs]
    html += page.fragment('<div class="figures">{% for o, u in pics %}{% if u %}<figure><img src="{{ u }}" '
                          'alt="elasticities of {{ o }}"></figure>{% endif %}{% endfor %}</div>', pics=pictures)
    missing = [o for o, u in pictures if u is None]
    if missing:
        html += page.fragment('<p class="note">No defined, nonzero elasticity of {{ m }} at this point '
                              "(a result equal to 0).</p>", m=", ".join(missing))
    return html
