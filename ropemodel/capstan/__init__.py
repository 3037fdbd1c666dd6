"""Capstan cable drive (Li et al.): stiffness laws, self-consistent rotation, load curves, identification."""
