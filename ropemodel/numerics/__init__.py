"""Numerical methods that the effects build their equations with (below the effects layer).

* :mod:`.hajduk_ode` — the Voigt-lining tension ODE (Hajduk 1992) in a stretched angle;
* :mod:`.hajduk_integrators` — its integrators as differentiable CasADi Functions;
* :mod:`.capstan_laws` — the stiffness-law variants of the capstan drive (Li et al. eq. 26);
* :mod:`.capstan_rotation` — the self-consistent rotation of the capstan under load.

Nothing here knows about scenes, effects or solving; these modules import only
:mod:`ropemodel.papers` and the foundation modules.
"""
