"""Li et al. capstan stiffness, eq. (6)-(27), against docs/physics.md §5, limits and hand derivations."""

import math

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from ropemodel.numerics.capstan_laws import LAWS, regime_number
from ropemodel.papers import li_capstan as li

MU, EA, R, L, F_P = 0.25, 5e4, 0.075, 0.36, 60.0
A0 = math.radians(64.0)


def test_stiffness_at_zero_load_is_twice_the_free_span():
    # K(0) = 2 EA/L: both slip zones have zero length, the two free spans act in parallel.
    k = li.drive_stiffness(0.0, F_P, MU, EA, R, L, A0, A0)
    assert k == pytest.approx(2 * EA / L, rel=4e-16)
    assert li.tight_side_stiffness_slipping(0.0, F_P, MU, EA, R, L) == pytest.approx(
        li.free_length_stiffness(EA, L), rel=4e-16)


def test_combined_forms_equal_the_series_sum_of_the_published_parts():
    # eq. (24)/(25) with (12)/(18) and (22), evaluated from the parts, at loads where K_1, K_2 exist
    for F in (0.5, 5.0, 12.0):
        k1 = li.tight_slip_zone_stiffness(F, F_P, MU, EA, R)
        k2 = li.slack_slip_zone_stiffness(F, F_P, MU, EA, R)
        k0 = li.free_length_stiffness(EA, L)
        assert li.tight_side_stiffness_slipping(F, F_P, MU, EA, R, L) == pytest.approx(
            li.series_stiffness(k1, k0, k1), rel=1e-13)
        assert li.slack_side_stiffness_slipping(F, F_P, MU, EA, R, L) == pytest.approx(
            li.series_stiffness(k2, k0, k2), rel=1e-13)
    k1s = li.tight_saturated_stiffness(MU, EA, R, A0)
    assert li.tight_side_stiffness_saturated(MU, EA, R, L, A0) == pytest.approx(
        li.series_stiffness(k1s, li.free_length_stiffness(EA, L), k1s), rel=1e-13)


def test_tight_side_is_continuous_at_its_switch():
    for a1 in (A0, 1.5, 3.0):
        F_sw = li.tight_switch_load(F_P, MU, a1)
        below = li.tight_side_stiffness(F_sw * (1 - 1e-12), F_P, MU, EA, R, L, a1)
        above = li.tight_side_stiffness(F_sw * (1 + 1e-12), F_P, MU, EA, R, L, a1)
        assert above == pytest.approx(below, rel=1e-10)
        # and the slip angle equals the wrap there (eq. 6 with eq. 13)
        assert li.tight_slip_angle(F_sw, F_P, MU) == pytest.approx(a1, rel=1e-13)


def test_slack_side_published_jump_reproduced():
    # docs/physics.md §5: F_p = 60 N, alpha_2 = 64 deg: the slack term jumps 90 369 -> 98 777 N/m at F_T = 14.62 N
    F_sw = li.slack_switch_load(F_P, MU, A0)
    assert F_sw == pytest.approx(14.62, abs=0.005)
    assert li.slack_slip_angle(F_sw, F_P, MU) == pytest.approx(A0, rel=1e-13)
    below = li.slack_side_stiffness(F_sw * (1 - 1e-12), F_P, MU, EA, R, L, A0)
    above = li.slack_side_stiffness(F_sw * (1 + 1e-12), F_P, MU, EA, R, L, A0)
    assert round(float(below)) == 90369
    assert round(float(above)) == 98777
    # the cause: eq. (18) at the switch is e^{-mu alpha_2} times eq. (21)
    assert li.slack_slip_zone_stiffness(F_sw, F_P, MU, EA, R) == pytest.approx(
        math.exp(-MU * A0) * li.slack_saturated_stiffness(MU, EA, R, A0), rel=1e-12)


def test_continuous_variant_has_no_jump_at_the_slack_switch():
    F_sw = li.slack_switch_load(F_P, MU, A0)
    below = li.slack_side_stiffness(F_sw * (1 - 1e-12), F_P, MU, EA, R, L, A0, continuous=True)
    above = li.slack_side_stiffness(F_sw * (1 + 1e-12), F_P, MU, EA, R, L, A0, continuous=True)
    assert above == pytest.approx(below, rel=1e-10)
    # its saturated value follows from continuing the slip zone's tension over the wrap (finite difference)
    def shortening(F):  # delta_2 = (R/EA)[F_p a2 - (F_p - F)(e^{mu a2} - 1)/mu]
        return R / EA * (F_P * A0 - (F_P - F) * math.expm1(MU * A0) / MU)
    h = 1e-3
    k_fd = 2 * h / (shortening(20 + h) - shortening(20 - h))
    assert li.slack_saturated_stiffness_continuous(MU, EA, R, A0) == pytest.approx(k_fd, rel=1e-8)


def test_slack_side_unloaded_beyond_the_preload():
    for F in (F_P, 1.5 * F_P, 10 * F_P):
        assert li.slack_side_stiffness(F, F_P, MU, EA, R, L, A0) == 0.0
        assert li.slack_side_stiffness(F, F_P, MU, EA, R, L, A0, continuous=True) == 0.0


def test_the_four_printed_rows():
    F_sw2 = li.slack_switch_load(F_P, MU, A0)
    F_sw1 = li.tight_switch_load(F_P, MU, A0)
    assert F_sw2 < F_sw1 < F_P  # the paper's order: slack saturates first, then tight, then unloads
    row1 = lambda F: (MU * EA * (F_P + F) / (2 * R * F + MU * L * (F_P + F))  # noqa: E731
                      + MU * EA * (F_P - F) / (2 * R * F + MU * L * (F_P - F)))
    sat = lambda a: MU * EA / (2 * R * (1 - math.exp(-MU * a)) + MU * L)  # noqa: E731
    row2 = lambda F: MU * EA * (F_P + F) / (2 * R * F + MU * L * (F_P + F)) + sat(A0)  # noqa: E731
    for F, expected, regime in ((10.0, row1(10.0), 1), (17.0, row2(17.0), 2), (30.0, 2 * sat(A0), 3),
                                (80.0, sat(A0), 4)):
        assert li.drive_stiffness(F, F_P, MU, EA, R, L, A0, A0) == pytest.approx(expected, rel=1e-13)
        assert regime_number(F, F_P, MU, A0, A0) == regime


def test_completed_case_tight_saturated_slack_not():
    # possible only if alpha_1 < alpha_2: tight saturates at F_p(e^{mu a1}-1) below F_p(1-e^{-mu a2})
    a1, a2 = 0.5, 3.0
    F = 0.5 * (li.tight_switch_load(F_P, MU, a1) + li.slack_switch_load(F_P, MU, a2))
    assert li.tight_switch_load(F_P, MU, a1) < F < li.slack_switch_load(F_P, MU, a2)
    expected = (MU * EA / (2 * R * (1 - math.exp(-MU * a1)) + MU * L)
                + MU * EA * (F_P - F) / (2 * R * F + MU * L * (F_P - F)))
    assert li.drive_stiffness(F, F_P, MU, EA, R, L, a1, a2) == pytest.approx(expected, rel=1e-13)
    assert regime_number(F, F_P, MU, a1, a2) == 5


def test_completed_case_unloaded_before_tight_saturates():
    # row 4 as printed assumes the tight side saturated; with a large wrap it is not
    a = 4.0
    F = 1.5 * F_P
    assert F < li.tight_switch_load(F_P, MU, a)
    expected = MU * EA * (F_P + F) / (2 * R * F + MU * L * (F_P + F))
    assert li.drive_stiffness(F, F_P, MU, EA, R, L, a, a) == pytest.approx(expected, rel=1e-13)
    assert regime_number(F, F_P, MU, a, a) == 6


def test_limited_slip_angles_are_finite_beyond_the_preload():
    with np.errstate(all="raise"):
        for F in (0.0, F_P, 2 * F_P):
            t2 = li.slack_slip_angle_limited(F, F_P, MU, A0)
            assert math.isfinite(t2) and t2 <= A0 * (1 + 1e-15)
        assert li.slack_slip_angle_limited(2 * F_P, F_P, MU, A0) == pytest.approx(A0, rel=1e-14)
        assert li.tight_slip_angle_limited(1e4, F_P, MU, A0) == pytest.approx(A0, rel=1e-14)
        assert li.tight_slip_angle_limited(5.0, F_P, MU, A0) == pytest.approx(li.tight_slip_angle(5.0, F_P, MU))


def test_stiffness_is_proportional_to_EA_at_fixed_wraps():
    F = np.linspace(0, 100, 11)
    for law in LAWS.values():
        k1 = sum(law.parts(F, F_P, MU, EA, R, L, A0, A0))
        k2 = sum(law.parts(F, F_P, MU, 2 * EA, R, L, A0, A0))
        np.testing.assert_allclose(k2, 2 * k1, rtol=1e-14)


def test_identification_formulas_of_section_4():
    # eq. (27) inverts the capstan equation F = F_p e^{mu alpha}; EA = F L / dL inverts Hooke's law
    alpha = 2.0
    F_T = F_P * math.expm1(MU * alpha)
    assert li.friction_coefficient_from_test(F_T, F_P, alpha) == pytest.approx(MU, rel=1e-14)
    assert li.axial_stiffness_from_test(100.0, 1.0, 100.0 / EA) == pytest.approx(EA, rel=1e-14)


positive = st.floats(0.2, 5.0)


@settings(max_examples=200, deadline=None)
@given(F=st.floats(0.0, 200.0), f=st.floats(1.01, 3.0), mu=st.floats(0.05, 0.6), a=st.floats(0.3, 6.0),
       Fp=st.floats(5.0, 150.0))
def test_property_trends_within_a_regime(F, f, mu, a, Fp):
    """K falls with L and R and rises with F_p and EA, whenever both points are in the same regime
    (across the published slack jump it need not: see the next test); the continuous law always."""
    base = dict(F_p=Fp, mu=mu, EA=EA, R=R, L=L)

    def k(law, **kw):
        p = {**base, **kw}
        return float(sum(LAWS[law].parts(F, p["F_p"], p["mu"], p["EA"], p["R"], p["L"], a, a)))

    def same_regime(**kw):
        p = {**base, **kw}
        return regime_number(F, p["F_p"], mu, a, a) == regime_number(F, Fp, mu, a, a)

    for law in ("li", "continuous"):
        check = law == "continuous"
        if check or same_regime(L=L * f):
            assert k(law, L=L * f) <= k(law) * (1 + 1e-12)
        if check or same_regime(R=R * f):
            assert k(law, R=R * f) <= k(law) * (1 + 1e-12)
        if check or same_regime(F_p=Fp * f):
            assert k(law, F_p=Fp * f) >= k(law) * (1 - 1e-12)
        assert k(law, EA=EA * f) > k(law)


def test_published_jump_breaks_the_preload_trend_locally():
    # just past the slack switch of F_p = 60 N, a larger preload is still slipping (lower) and K is smaller
    F = li.slack_switch_load(F_P, MU, A0) + 0.01
    k60 = li.drive_stiffness(F, F_P, MU, EA, R, L, A0, A0)
    k61 = li.drive_stiffness(F, 61.0, MU, EA, R, L, A0, A0)
    assert k61 < k60
    assert li.drive_stiffness(F, 61.0, MU, EA, R, L, A0, A0, True) > li.drive_stiffness(F, F_P, MU, EA, R, L, A0,
                                                                                         A0, True)
