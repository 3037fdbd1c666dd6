"""Every machine's declaration is whole: each part a generic driver reads is there, and its parts agree with each
other (CONTRIBUTING.md, "Adding a machine", whose checklist names this test).

The drivers read a declaration without asking which machine it is, so a part left out fails only when a scene of
that machine reaches the driver; these tests fail at once instead.  What each part must hold is written out here,
from CONTRIBUTING's table, not read from the winch: a new machine's declaration is checked against the same list.
"""

from __future__ import annotations

import inspect

import pytest

from ropemodel.effects.base import models
from ropemodel.machines import MACHINES, machine_of
from ropemodel.machines.base import DesignBox, ManoeuvreCheck, machines
from ropemodel.machines.sizing import Declaration
from ropemodel.reports.registry import sections
from ropemodel.views.checks import Vocabulary, Words

#: a sizing given as a module (one NLP, :class:`optimisation.problem.SizingProblem`): what the driver reads
SIZING_MODULE = ("VARIABLES", "D_OPTIONAL", "prepare", "rope_problem", "frees", "force_scale", "x_scale", "bounds",
                 "start", "PRIMARY", "WEIGHTS", "nlp_form", "unit", "rounded_up", "UNITS", "CHOOSES", "INTRO",
                 "ROUNDED", "SCENE_TEXT", "ELONGATION", "NOT_LEXICOGRAPHIC")
#: the manoeuvres of dynamic sizing (:mod:`optimisation.dynamic`): what the drivers read
MANOEUVRES = ("ORDER", "CHECKS", "CHECK", "EVENTS", "OBJECTIVE", "TEXT", "SIDES", "values", "completed", "BOX",
              "SLIP_FACTORS", "series", "peaks", "PEAKS", "peak_text", "PEAK_COLUMNS")
#: what a machine's trips give :mod:`ropemodel.trips`
TRIPS = ("length", "joints", "take_up", "summary", "lines", "remedy", "ROWS", "SUMMARY", "OUTPUTS")

ALL = sorted(MACHINES)


def test_every_machine_is_a_model_of_the_effect_registry_and_the_default_is_first():
    assert ALL and set(ALL) <= set(models())
    assert machines()[0].model == "winch" and {m.model for m in machines()} == set(ALL)
    assert all(machine_of(m).model == m for m in ALL)


@pytest.mark.parametrize("model", ALL)
def test_checks_keep_the_margins_in_an_order(model):
    """``checks(names)``: the margin outputs among ``names``, no other output, none twice."""
    machine = MACHINES[model]
    names = ["F_C_up", "safety_margin_up", "slip_margin_down", "m_l", "drum_margin", "sigma_static"]
    kept = machine.checks(names)
    assert set(kept) <= {n for n in names if "_margin" in n} and len(kept) == len(set(kept))


@pytest.mark.parametrize("model", ALL)
def test_sections_are_report_sections(model):
    known = {s.name for s in sections()}
    assert set(MACHINES[model].sections) <= known, set(MACHINES[model].sections) - known


@pytest.mark.parametrize("model", [m for m in ALL if MACHINES[m].sizing is not None])
def test_a_sizing_is_a_declaration_or_a_whole_module(model):
    sizing = MACHINES[model].sizing
    if isinstance(sizing, Declaration):
        assert sizing.model == model and sizing.integer and sizing.variables
        return
    missing = [name for name in SIZING_MODULE if not hasattr(sizing, name)]
    assert not missing, f"{model}'s sizing lacks {missing}"
    assert len(sizing.WEIGHTS) == len(sizing.VARIABLES) - 1


@pytest.mark.parametrize("model", [m for m in ALL if MACHINES[m].manoeuvres is not None])
def test_manoeuvres_are_whole_and_agree_with_the_sizing_and_the_words(model):
    """A machine with manoeuvres is sized (the box and the NLP's variables are the sizing's), declares every
    part, and has each check in words (:class:`~ropemodel.views.checks.Vocabulary`)."""
    machine = MACHINES[model]
    man = machine.manoeuvres
    missing = [name for name in MANOEUVRES if not hasattr(man, name)]
    assert not missing, f"{model}'s manoeuvres lack {missing}"
    assert all(isinstance(c, ManoeuvreCheck) for c in man.CHECKS)
    assert man.CHECK == {c.name: c for c in man.CHECKS} and set(man.SIDES) <= set(man.CHECK)
    assert all(c.unit in ("N", "m") for c in man.CHECKS)
    assert all(len(pair) == 2 for pair in man.ORDER) and man.ORDER
    assert set(man.TEXT) == {"all", "kinds", "through"} and all(man.TEXT.values())
    # the scan's box covers the design, each variable once
    assert machine.sizing is not None and isinstance(man.BOX, DesignBox)
    box = [man.BOX.catalogue, man.BOX.grid, *man.BOX.held]
    assert sorted(box) == sorted(machine.sizing.VARIABLES)
    assert {k for k, pick in man.PEAKS} and all(pick in (max, min) for _, pick in man.PEAKS)
    # every check in words, the words' kinds known
    words = machine.words
    assert isinstance(words, Vocabulary) and set(words.manoeuvre) == set(man.CHECK)
    assert all(isinstance(w, Words) and w.kind in ("ratio", "force", "length")
               for w in (*words.manoeuvre.values(), *words.static.values()))
    assert all(set(alt) <= set(man.CHECK) for alt in words.with_factor.values())
    assert [name for name, _ in man.SLIP_FACTORS] and all(isinstance(what, str) for _, what in man.SLIP_FACTORS)


@pytest.mark.parametrize("model", [m for m in ALL if MACHINES[m].transient is not None])
def test_a_transient_names_its_profile_and_scales(model):
    t = MACHINES[model].transient
    assert inspect.isclass(t.profile) and callable(t.scale) and callable(t.length) and callable(t.numbers)
    assert t.result is None or inspect.isclass(t.result)


@pytest.mark.parametrize("model", [m for m in ALL if MACHINES[m].trips is not None])
def test_trips_are_whole(model):
    missing = [name for name in TRIPS if not hasattr(MACHINES[model].trips, name)]
    assert not missing, f"{model}'s trips lack {missing}"
