"""Delta3 kinematics parameters (`omron-robot-delta3.md` §3.1, §8.2 `_sMC_KIN_REF`; seed 003 L1931–1967, L2840–2870).

A plain value: construction never validates, so the MC layer can build one from any user input and ask
`restrictions.check_kin_transform` for the manual's ErrorID. Everything derived (the zero-pose height Z0, the arm
azimuths) is computed once per instance (cached_property writes the instance __dict__, so ==/hash see only the
five parameters)."""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass
from functools import cached_property
from typing import TYPE_CHECKING

import numpy as np
from numpy.typing import NDArray

if TYPE_CHECKING:
    from .restrictions import KinCheck
    from .workspace import Delta3Workspace

# Azimuths of the arms A0, A1, A2 at θ = 0, counter-clockwise from +Xm seen from above (§12.1; decision D30.1).
# One constant: the manual's top-view figure is lost, so this is the single place to change if it is ever found.
ARM_AZIMUTH0_DEG: tuple[float, float, float] = (0.0, 120.0, 240.0)

KIN_TYPE_DELTA3 = 100  # _eMC_KIN_TYPE._mcDelta3Type1
WORKSPACE_TYPE_DELTA3 = 100  # _eMC_WORKSPACE_TYPE._mcDelta3Workspace


@dataclass(frozen=True, kw_only=True)
class Delta3Params:
    """Rf, Lf, Rm, Lm in mm; θ (`theta`) in degrees.

    Rf: fixed-frame centre → motor axis; Lf: upper arm (link 1); Rm: moving-frame centre → forearm joint;
    Lm: forearm (link 2); θ: rotation of the arm layout about the MCS Z axis (ExpansionParam[0], 0–360)."""

    Rf: float
    Lf: float
    Rm: float
    Lm: float
    theta: float = 0.0

    @classmethod
    def from_kin_param(cls, KinParam: Sequence[float], ExpansionParam: Sequence[float] = ()) -> Delta3Params:
        """From `_sMC_KIN_REF` arrays in the manual's order **Rf, Lf, Rm, Lm** (not Rf, Rm, Lf, Lm; §3.1)."""
        kp = [float(v) for v in KinParam] + [0.0] * max(0, 4 - len(KinParam))
        theta = float(ExpansionParam[0]) if len(ExpansionParam) else 0.0
        return cls(Rf=kp[0], Lf=kp[1], Rm=kp[2], Lm=kp[3], theta=theta)

    def kin_param(self) -> list[float]:
        """`KinParam[0..7]` as MC_SetKinTransform takes it."""
        return [self.Rf, self.Lf, self.Rm, self.Lm, 0.0, 0.0, 0.0, 0.0]

    def expansion_param(self) -> list[float]:
        """`ExpansionParam[0..7]`."""
        return [self.theta, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0]

    def check(self, workspace: Delta3Workspace) -> KinCheck:
        """The geometric restrictions of §3.3 with this workspace (571F); ranges are `check_kin_transform`'s."""
        from .restrictions import check_restrictions  # restrictions imports this module

        return check_restrictions(self, workspace)

    @cached_property
    def Z0(self) -> float:
        """Motor-plane z of the MCS origin (mm, negative): the TCP height at A0 = A1 = A2 = 0 (§12.2, D30.2).

        NaN when the zero pose does not exist (Lm ≤ Rf − Rm + Lf: the forearms cannot reach the axis with the
        upper arms horizontal); such parameters fail `check_kin_transform` with 571F."""
        reach = self.Rf - self.Rm + self.Lf
        if not (math.isfinite(reach) and math.isfinite(self.Lm)) or self.Lm <= abs(reach):
            return math.nan
        return -math.sqrt(self.Lm * self.Lm - reach * reach)

    @cached_property
    def motor_plane_z(self) -> float:
        """z of the plane of the three motor axes in the MCS (mm, positive): −Z0."""
        return -self.Z0

    @cached_property
    def azimuths_rad(self) -> NDArray[np.float64]:
        """φᵢ = φᵢ⁰ + θ of the arms A0, A1, A2 (rad), counter-clockwise from +Xm."""
        return np.radians(np.asarray(ARM_AZIMUTH0_DEG) + self.theta)

    @cached_property
    def cos_phi(self) -> NDArray[np.float64]:
        return np.cos(self.azimuths_rad)

    @cached_property
    def sin_phi(self) -> NDArray[np.float64]:
        return np.sin(self.azimuths_rad)

    @cached_property
    def cs_phi(self) -> tuple[tuple[float, float], ...]:
        """(cos φᵢ, sin φᵢ) per arm as Python floats, for the one-point functions of `point.py`."""
        return tuple((float(c), float(s)) for c, s in zip(self.cos_phi, self.sin_phi, strict=True))

    @cached_property
    def radial(self) -> NDArray[np.float64]:
        """uᵢ = (cos φᵢ, sin φᵢ, 0) per arm, shape (3, 3): row i is arm i's outward horizontal unit vector."""
        phi = self.azimuths_rad
        return np.stack([np.cos(phi), np.sin(phi), np.zeros(3)], axis=-1)

    @cached_property
    def tangential(self) -> NDArray[np.float64]:
        """tᵢ = ẑ × uᵢ per arm, shape (3, 3): the motor axis direction; +qᵢ is a right-hand turn about it."""
        phi = self.azimuths_rad
        return np.stack([-np.sin(phi), np.cos(phi), np.zeros(3)], axis=-1)
