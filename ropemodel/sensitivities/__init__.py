"""Which inputs matter: local elasticities by AD, global Sobol indices with SALib, tornado charts.

::

    import ropemodel as rm
    import ropemodel.sensitivities
    e = rm.elasticities(rm.load_scene())        # tidy: output, parameter, elasticity, ...
    print(rm.sensitivities.table(e))             # outputs x parameters
    rm.tornado(e, ["F_C_up", "dF_up"], path="tornado.png")
    s = rm.sobol(rm.load_scene(), {"alpha_u": "10deg:20deg", "G_m": "300kN:500kN"})

Modules: :mod:`.local` (elasticities ∂ln y/∂ln p from the Jacobian of the
compiled Function), :mod:`.sobol` (Sobol indices; any vectorised function, a
scene, or the sizing optimum), :mod:`.plot` (tornado charts).
"""

from ropemodel.sensitivities.local import elasticities, jacobian, matrix, table
from ropemodel.sensitivities.plot import tornado
from ropemodel.sensitivities.sobol import parse_range, sobol, sobol_indices

__all__ = ["elasticities", "jacobian", "matrix", "parse_range", "sobol", "sobol_indices", "table", "tornado"]
