"""Which cases the hybrid simulator judges when dynamic sizing verifies its design
(:func:`optimisation.dynamic.verify.verified`), on verdicts made up here (the simulations and integrations
themselves: the slow sizing tests).

Truth: the rule written out — every case within EXEMPT of a limit and each manoeuvre's least place (of any check)
are simulated; a check's least place that keeps EXEMPT is not; the others are left to the NLP's integration only
when the simulated cases agree with it to AGREE and every part that can leave its smooth mode is one a check keeps
in it; else every case is simulated.
"""

from __future__ import annotations

from types import SimpleNamespace

import pytest

from optimisation.dynamic import verify
from optimisation.dynamic.verify import AGREE, EXEMPT, INTEGRATED, SIMULATED, Verdict

#: the winch's parts with more than one mode (effect, modes), as a simulation of the shipped scene lists them
PARTS = (("tensioner", ("free", "at_end", "at_start")), ("drive", ("profile",)),
         ("drum_contact", ("stick", "slip_fwd", "slip_back")))


def _case(label: str, x: float, scaled: dict) -> Verdict:
    return Verdict(label, x, f"x_m = {x} m", False, True, scaled=dict(scaled), by=INTEGRATED)


def _integrated():
    """Two manoeuvres, three places each.  start: a least at 0 (within EXEMPT), within EXEMPT at 50 too, b least
    at 100 (keeping EXEMPT); stop: nothing within EXEMPT, the least of all a at 50, b least at 0 (far)."""
    far = 10 * EXEMPT
    return [_case("start", 0.0, {"a": 0.01, "b": far}), _case("start", 50.0, {"a": 0.5 * EXEMPT, "b": far}),
            _case("start", 100.0, {"a": far, "b": 0.2}), _case("stop", 0.0, {"a": far, "b": far}),
            _case("stop", 50.0, {"a": 2 * EXEMPT, "b": far + 1}), _case("stop", 100.0, {"a": far + 1, "b": far})]


def test_the_simulator_judges_every_case_within_reach_and_each_manoeuvres_least_place():
    # within EXEMPT: 0 and 1 (start); the least place of start: 0, of stop: 4 (a at 2 EXEMPT); b's least places,
    # 2 in start and 3 in stop, keep EXEMPT: left to the integration
    assert verify.to_simulate(_integrated()) == [0, 1, 4]


def _run(monkeypatch, shift: float, parts=PARTS):
    """``verified`` on made-up cases, the simulator's margins ``shift`` (scaled) below the integration's."""
    monkeypatch.setattr(verify, "integrated", lambda problem, xs, dt: _integrated())
    monkeypatch.setattr(verify, "declared", lambda scene: SimpleNamespace(CHECKED_MODES=("drum_contact", "tensioner")))

    def simulated(problem, xs, values=None, which=None):
        out = []
        for i in which:
            v = _integrated()[i]
            out.append(Verdict(v.manoeuvre, v.x_m, v.where, False, True, parts=parts, by=SIMULATED,
                               scaled={c: m - shift for c, m in v.scaled.items()}))
        return out

    monkeypatch.setattr(verify, "verify", simulated)
    return [v.by for v in verify.verified(_problem(_integrated()), None)]


def _problem(verdicts):
    """The cases of ``verdicts`` (manoeuvre label), each path with the checks a and b."""
    return SimpleNamespace(cases=[SimpleNamespace(label=v.manoeuvre) for v in verdicts], scene=None,
                           all_paths=[SimpleNamespace(checks=["a", "b"])] * len(verdicts))


def test_the_cases_far_from_every_limit_are_left_to_the_integration_when_both_agree(monkeypatch):
    by = _run(monkeypatch, 0.5 * AGREE)
    assert by == [SIMULATED, SIMULATED, INTEGRATED, INTEGRATED, SIMULATED, INTEGRATED]


def test_every_case_is_simulated_when_the_simulator_and_the_integration_disagree(monkeypatch):
    assert _run(monkeypatch, 2 * AGREE) == [SIMULATED] * 6


def test_every_case_is_simulated_when_a_part_can_leave_its_smooth_mode_unchecked(monkeypatch):
    torque_limited = (*PARTS[:1], ("drive", ("profile", "torque_pos", "torque_neg")), *PARTS[2:])
    assert _run(monkeypatch, 0.0, torque_limited) == [SIMULATED] * 6


def test_the_worst_peaks_are_the_simulated_cases():
    """by_manoeuvre takes each peak over the cases that have one (the simulated ones)."""
    a = Verdict("start", 0.0, "here", True, True, scaled={"a": 1.0}, peaks={"F": 2.0}, worst={"F": max})
    b = _case("start", 9.0, {"a": 5.0})
    (m,) = verify.by_manoeuvre([a, b])
    assert m["peaks"] == {"F": 2.0, "x_m_F": 0.0} and [p["judged_by"] for p in m["positions"]] == [SIMULATED,
                                                                                                   INTEGRATED]
    assert pytest.approx(m["x_m"]) == 0.0
