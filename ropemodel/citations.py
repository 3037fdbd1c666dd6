"""References of the published models; submodels cite them by key."""

from __future__ import annotations

CITATIONS: dict[str, str] = {
    "krauze2025": (
        "K. Krauze, K. Mucha, T. Wydro, R. Klempka (2025). Model and analysis of rope winch "
        "operation in underground rail transport. Archives of Mining Sciences. doi:10.24425/ams.2025.156290. CC-BY 4.0."
    ),
    "hajduk1992": (
        "J. Hajduk (1992). Theoretical distribution of the tension in the rope encircling the "
        "driving disc with the elastic lining (in Polish, English summary)."
    ),
    "li_capstan": (
        "Li, Liang, Dong, Qiu. Analysis and experimental determination of cable-driven stiffness."
    ),
    "euler_eytelwein": (
        "L. Euler (1762); J. A. Eytelwein (1808). Belt friction: T1/T2 = exp(mu*alpha)."
    ),
    "en12385_4": (
        "EN 12385-4:2002+A1:2008. Steel wire ropes - Safety - Part 4: Stranded ropes for general lifting "
        "applications (rope-class factors K, W, C; rope grades)."
    ),
    "thirion1946": (
        "P. Thirion (1946). Les coefficients d'adhérence du caoutchouc. Revue Générale du Caoutchouc "
        "23, 101-106 (friction of rubber falling with contact pressure, 1/mu = a + b p)."
    ),
    "delavergne2003": (
        "J. de la Vergne (2003). Hard Rock Miner's Handbook, 3rd ed. McIntosh Engineering. Chapter 14: Koepe / "
        "Friction Hoists (the machine, its head and tail ropes)."
    ),
    "edwards1992": (
        "F. A. Edwards (1992). Hoisting systems. Chapter 17.5 in H. L. Hartman (ed.), SME Mining Engineering "
        "Handbook, 2nd ed. Society for Mining, Metallurgy, and Exploration, Littleton, CO."
    ),
    "rope_extension": (
        "Properties of extension of steel wire ropes (rope makers' technical information: Bridon, Wire Rope "
        "Technical Information; Certex, Properties of Extension of Steel Wire Ropes): constructional stretch by "
        "core and load, elastic extension, thermal expansion."
    ),
    "feyrer2015": (
        "K. Feyrer (2015). Wire Ropes: Tension, Endurance, Reliability, 2nd ed. Springer, Berlin. Section 1.3: the "
        "rope elasticity modulus, rising with the rope tensile stress."
    ),
    "antislip_cn": (
        "Anti-slip factor of multi-rope friction hoists, Chinese design practice: "
        "sigma = (exp(mu*alpha) - 1) T2/(T1 - T2). No primary text held; definition as in docs/physics.md s. 7."
    ),
}


def cite(keys) -> list[str]:
    """Full references for the given keys, in order, without repeats."""
    seen, out = set(), []
    for k in keys:
        if k not in seen:
            seen.add(k)
            out.append(CITATIONS[k])
    return out
