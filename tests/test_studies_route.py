"""The route-trip study: a route of segments against its equivalent slope, numbers checked by hand."""

import math

import pytest
from _studies import load_study

Q, G_M, F_NWL, MU = 80.0, 467e3, 30e3, 0.05    # route_segments.toml
SEGMENTS = [(400.0, 22.0, 0.06), (650.0, 9.0, 0.05), (300.0, 3.0, 0.05)]


def _F_C_up(alpha_load):
    """Steady F_C upward with the load on a segment inclined at alpha_load (docs/physics.md §4)."""
    rope = sum(Q * L * math.sin(math.radians(a)) + m * Q * L * math.cos(math.radians(a)) for L, a, m in SEGMENTS)
    a = math.radians(alpha_load)
    return 0.5 * F_NWL + rope + G_M * (math.sin(a) + MU * math.cos(a))


def test_route_trip_study(tmp_path):
    table = load_study("route_trip").main(tmp_path, fast=True).set_index(["route", "direction"])
    assert (tmp_path / "route_trip.png").stat().st_size > 0
    # the route's peak: the steady force with the load on the 22 deg segment (the stop at the drive slows it)
    assert table.loc[("route", "up"), "F_C_max"] == pytest.approx(_F_C_up(22.0), rel=1e-12)
    # the equivalent slope (same length and rise) hides it: 22 % lower here
    ratio = table.loc[("route", "up"), "F_C_max"] / table.loc[("equivalent slope", "up"), "F_C_max"]
    assert ratio == pytest.approx(1.280, abs=0.001)
    # the same rise: the energy of an upward trip differs only by the rope's resistance on the slopes
    assert table.loc[("route", "up"), "E_trip"] == pytest.approx(table.loc[("equivalent slope", "up"), "E_trip"],
                                                                 rel=0.02)
    # lowering, the route's drive brakes on the steep segments and motors on the 3 deg one; the equivalent
    # slope (about 11.4 deg, steeper than the load's resistance holds) brakes all the way
    assert table.loc[("route", "down"), "E_trip"] > 0 and table.loc[("route", "down"), "E_regen"] > 0
    assert table.loc[("equivalent slope", "down"), "E_trip"] == 0.0
    assert table.loc[("equivalent slope", "down"), "P_brake_max"] < 0
