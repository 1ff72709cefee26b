"""Fixtures of the kinematics tests: the example robot of `omron-robot-delta3.md` §12.9 and its workspace."""

from __future__ import annotations

import pytest

from mcstudio.controller.mc.kinematics import Delta3Params, Delta3Workspace


@pytest.fixture
def robot() -> Delta3Params:
    """§12.9: Rf = 200, Rm = 50, Lf = 350, Lm = 800 mm, θ = 0°, zero-pose MCS origin (Z0 = −624.4998 mm)."""
    return Delta3Params(Rf=200.0, Lf=350.0, Rm=50.0, Lm=800.0, theta=0.0)


@pytest.fixture
def ws() -> Delta3Workspace:
    """The §12.9 script's workspace: Zu −50, Rcy 300, Hcy 250, Rco 150, Hco 150 (cone half-angle 45°)."""
    return Delta3Workspace(Zu=-50.0, Rcy=300.0, Hcy=250.0, Rco=150.0, Hco=150.0)
