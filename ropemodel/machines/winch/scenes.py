"""Random sizing scenes for studies and benchmarks (rigid drum, 6x36-IWRC catalogue rope)."""

from __future__ import annotations

import math

import numpy as np

from ropemodel.scene import Scene, from_dict

#: sampling ranges (SI) of the random scenes: underground rope haulages of the kind Krauze et al. (2025) treat
RANGES = {
    "G_m": (50e3, 600e3),
    "L_u": (300.0, 2000.0),
    "alpha_u": (math.radians(3), math.radians(30)),
    "mu_pm": (0.02, 0.08),
    "mu_pl": (0.02, 0.08),
    "mu_d": (0.15, 0.3),
    "alpha_d": (math.pi, 4 * math.pi),
    "n_slip": (1.1, 1.5),
    "n_rope": (3.0, 6.0),
    "F_S_min": (0.0, 10e3),
    "rope_E": (80e9, 120e9),
}
GRADES = (1570e6, 1770e6, 1960e6, 2160e6)


def random_sizing_scene(rng: np.random.Generator, name: str = "random", construction: str = "6x36-IWRC",
                        lining: str = "rigid") -> Scene:
    """One random scene; the drum is 2.5 m (generous), the starting design d = 30 mm, F_nwl = 20 kN, stroke 1 m."""
    params = {k: float(rng.uniform(*r)) for k, r in RANGES.items()}
    params["L_ul"] = float(rng.uniform(0.0, params["L_u"]))
    params.update({"rope_grade": float(rng.choice(GRADES)), "v_pj": 2.5, "eta": 0.85, "D": 2.5,
                   "d": 0.03, "F_nwl": 20e3, "stroke": 1.0})
    return from_dict({"scene": {"name": name},
                      "effects": {"rope": construction, "checks": "design", "lining": lining, "power": "drive"},
                      "parameters": params}, bare="si")
