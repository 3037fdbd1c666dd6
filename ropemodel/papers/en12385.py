"""Steel wire rope catalogue: construction factors K, W, C, rope grades and nominal diameters.

The data live in ``ropemodel/data/ropes.toml`` with the source of every factor
(EN 12385-4:2002+A1:2008 rope-class tables).  Catalogue relations, EN 12385-4 with
the definitions of EN 12385-2:

* minimum breaking force  F_min = K·d²·R_r  [N]  (d [m], R_r [Pa])
* nominal length mass     m_l   = W·d²      [kg/m] (W [kg/m³] in SI; catalogues print
  kg/(100 m·mm²): 1 kg/(100 m·mm²) = 10 000 kg/m³)
* metallic cross-section  A     = C·d²      [m²]

Every function works on floats, numpy arrays and CasADi symbols.
"""

from __future__ import annotations

import tomllib
from dataclasses import dataclass
from functools import lru_cache
from importlib import resources

from ropemodel.errors import InputError, suggest

#: standard acceleration of gravity [m/s²] (CGPM 1901, ISO 80000-3)
G_N = 9.80665
#: 1 kg/(100 m·mm²) in kg/m³ (the unit catalogues print W in)
W_CATALOGUE_UNIT = 1.0 / (100.0 * 1e-6)


@dataclass(frozen=True)
class Construction:
    """A rope class of EN 12385-4 with its factors, all SI: W [kg/m³], C [-], K [-]."""

    name: str
    description: str
    W: float
    C: float
    K: float
    source: str
    #: the class of EN 12385-4 (``"6x36"``) and the core (``"IWRC"``, ``"FC"``), for the rope's designation
    rope_class: str = ""
    core: str = ""


@lru_cache(maxsize=1)
def _data() -> dict:
    return tomllib.loads(resources.files("ropemodel.data").joinpath("ropes.toml").read_text())


def constructions() -> dict[str, Construction]:
    """Named constructions (``"6x36-IWRC"`` …) with SI factors."""
    out = {}
    for name, c in _data()["constructions"].items():
        out[name] = Construction(name, c["description"], c["W"] * W_CATALOGUE_UNIT, c["C"], c["K"], c["source"],
                                 c["rope_class"], c["core"])
    return out


def construction(name: str) -> Construction:
    """The construction called ``name``; :class:`InputError` naming the valid ones otherwise."""
    table = constructions()
    if name not in table:
        raise InputError(f"unknown rope construction {name!r}; valid: {', '.join(table)}{suggest(name, table)}")
    return table[name]


def grades() -> list[float]:
    """Rope grades R_r [Pa] of EN 12385-4 (1570 … 2160 N/mm²)."""
    return [g * 1e6 for g in _data()["grades"]["values"]]


def diameters() -> list[float]:
    """Nominal rope diameters [m], ascending."""
    return sorted(x * 1e-3 for x in _data()["diameters"]["values"])


def diameters_source() -> str:
    return _data()["diameters"]["source"]


def factors_status() -> tuple[str, str]:
    """(status, evidence) of the construction factors W, C, K: what the catalogue's numbers rest on."""
    s = _data()["status"]
    return s["factors"], s["evidence"]


def designation_rules() -> dict:
    """How a rope is designated (EN 12385-2, ISO 17893): standard, system, order, example, status, evidence,
    cores (abbreviation → meaning)."""
    return dict(_data()["designation"])


def designation(d_mm: float, construction: str, core: str, grade_mpa: float, finish: str = "", lay: str = "") -> str:
    """The rope's designation, its elements in the order of EN 12385-2 / ISO 17893 [-]: nominal diameter [mm],
    construction-core, grade [N/mm²], wire finish, type and direction of lay (a missing element left out).

    Examples
    --------
    >>> designation(22, "6x36WS", "IWRC", 1770, "B", "sZ")       # a 6x36-class rope, zinc coated, right regular lay
    '22 6x36WS-IWRC 1770 B sZ'
    >>> designation(42, "6x36", "IWRC", 1770)
    '42 6x36-IWRC 1770'
    """
    parts = [f"{d_mm:g}", f"{construction}-{core}" if core else construction, f"{grade_mpa:g}", finish, lay]
    return " ".join(p for p in parts if p)


def minimum_breaking_force(K, d, R_r):
    """Minimum breaking force F_min = K·d²·R_r [N] (EN 12385-4; definition EN 12385-2).

    K [-] minimum breaking force factor of the rope class; d [m] nominal diameter;
    R_r [Pa] rope grade (1570e6 … 2160e6 in EN 12385-4).

    Examples
    --------
    A 42 mm 6x19 IWRC rope of grade 1770 (K = 0.356), 1111.5 kN (makers list 1110 kN):

    >>> K = construction("6x19-IWRC").K
    >>> round(minimum_breaking_force(K, 0.042, 1770e6) / 1e3, 1)
    1111.5
    """
    return K * d**2 * R_r


def rope_mass_per_metre(W, d):
    """Nominal length mass m_l = W·d² [kg/m] (EN 12385-4).  W [kg/m³] (catalogue kg/(100 m·mm²) × 1e4); d [m].

    Examples
    --------
    The same rope, W = 0.400 kg/(100 m·mm²) = 4000 kg/m³ (makers list 7.06 kg/m):

    >>> round(rope_mass_per_metre(0.400e4, 0.042), 3)
    7.056
    """
    return W * d**2


def rope_weight_per_metre(W, d, g=G_N):
    """Weight per metre q_l = g·W·d² [N/m]: the paper's q_l from the catalogue mass factor.

    W [kg/m³]; d [m]; g [m/s²] standard gravity.
    """
    return g * rope_mass_per_metre(W, d)


def metallic_area(C, d):
    """Metallic cross-section A = C·d² [m²] (EN 12385-4).  C [-] metallic area factor; d [m]."""
    return C * d**2


def unit_elongation(L, E, C, d):
    """Unit elongation of the installed rope q_lw = L/(E·C·d²) [m/N]: Hooke's law over length L.

    The paper's q_lw (Krauze et al. 2025, eq. 19-22: elongation per unit force) for a
    rope of length L [m] (the route length L_u), modulus E [Pa] referred to the
    metallic area, metallic area factor C [-], diameter d [m].  Elastic range only;
    the constructional (bedding-in) stretch of a new rope is not included.
    """
    return L / (E * metallic_area(C, d))
