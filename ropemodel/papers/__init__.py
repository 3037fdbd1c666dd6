"""The published equations, one module per paper, one function per equation.

Every function works on floats, numpy arrays and CasADi expressions, in SI units,
and cites its paper and equation number.  Nothing here knows about scenes,
effects or solving: :mod:`ropemodel.effects` wires these into models.
"""
