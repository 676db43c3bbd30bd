"""Shared fixtures of the Python suite (ctest python_module sets PYTHONPATH to build/python and
SVMP_SOURCE_DIR, SVMP_SOLVE_REFERENCE)."""
import os

import numpy as np
import pytest

import svmp

SOURCE = os.environ.get("SVMP_SOURCE_DIR", os.path.join(os.path.dirname(__file__), "..", ".."))


def scenario_path(name):
    return os.path.join(SOURCE, "bench", "scenarios", name)


@pytest.fixture(scope="session")
def two_rings():
    """A seeded 2-D problem no line separates: +1 inside radius 1, -1 on a ring around it."""
    rng = np.random.default_rng(7)
    angle = rng.uniform(0, 2 * np.pi, 160)
    radius = np.concatenate([rng.uniform(0, 0.9, 80), rng.uniform(1.1, 2.0, 80)])
    X = np.column_stack([radius * np.cos(angle), radius * np.sin(angle)])
    y = np.concatenate([np.ones(80), -np.ones(80)])
    return X, y


@pytest.fixture(scope="session")
def model(two_rings):
    X, y = two_rings
    return svmp.train(X, y, C=10.0, gamma=2.0)


@pytest.fixture(scope="session")
def fig35():
    return svmp.load_scenario(scenario_path("thesis_fig3_5.yaml"))
