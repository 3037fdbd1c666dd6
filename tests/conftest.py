"""Shared fixtures."""

import pytest

import ropemodel as rm


@pytest.fixture(scope="session")
def fig9():
    """The built-in example: Krauze et al. (2025), Fig. 9."""
    return rm.load_scene()
