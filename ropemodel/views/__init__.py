"""How results show themselves: HTML tables in Jupyter, pandas forms and matplotlib pictures.

Each result class takes its mixin from here: :class:`~ropemodel.views.result.ResultViews`
(:class:`ropemodel.result.Result`), :class:`~ropemodel.views.records.TripViews`
(:class:`ropemodel.trips.Trip`), :class:`~ropemodel.views.records.SimulationViews`
(:class:`ropemodel.dynamics.Simulation`), :class:`~ropemodel.views.design.DesignViews`
(:class:`optimisation.design.Design`), :class:`~ropemodel.views.records.SweepFileViews`
(:class:`ropemodel.sweeps.runner.SweepFile`) and :class:`~ropemodel.views.scene.SceneViews`
(:class:`ropemodel.scene.Scene`).  The mixins read only the attributes of the object they are mixed
into, so this layer sits below every class that uses it; :mod:`.html` writes the tables and
:mod:`.plotting` imports matplotlib only when a picture is drawn (the ``plots`` extra).
"""
