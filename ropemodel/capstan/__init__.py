"""Capstan cable drive (Li et al.): stiffness laws, self-consistent rotation, load curves, identification,
the rotation at many points (:mod:`ropemodel.capstan.batch`)."""
