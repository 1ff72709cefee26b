"""The normalised laws of `_eMC_CAM_CURVE` (docs/cams.md): boundary values, derivatives and the dimensionless
characteristic values Vm, Am, Jm against published cam-design tables.

Published values: Makino's standard cam curves as tabulated by Japanese cam makers (e.g. the characteristic-value
table of the universal cam curve: PB 2.000/4.000/∞, SH 1.571/4.935/∞ (15.50 inside), CY 2.000/6.283/39.48,
MT 2.000/4.888/61.43, MS 1.760/5.528/69.47, MCV50 1.275/8.013/201.4) and the 3-4-5 polynomial 1.875/5.774/60
(Rothbart, Cam Design Handbook, ch. 3; Mitsubishi motion controller manuals, "Cam curves" appendix).
"""

from __future__ import annotations

import math

import numpy as np
import pytest

from mcstudio.controller.mc.cam.curves import LAWS, characteristics, evaluate
from mcstudio.controller.mc.enums import ENUMS, _eMC_CAM_CURVE

C = _eMC_CAM_CURVE
RISING = [c for c in C if c != C._mcConstantLine]

# curve: (Vm, Am, Jm inside the smooth pieces, Jm when used between dwells)
PUBLISHED = {
    C._mcStraightLine: (1.0, 0.0, 0.0, 0.0),
    C._mcParabolic: (2.000, 4.000, 0.0, math.inf),
    C._mcModifiedConstantVel: (1.275, 8.013, 201.4, 201.4),
    C._mcModifiedTrapezoid: (2.000, 4.888, 61.43, 61.43),
    C._mcModifiedSine: (1.760, 5.528, 69.47, 69.47),
    C._mcCycloidal: (2.000, 6.283, 39.48, 39.48),
    C._mcSimpleHarmonic: (1.571, 4.935, 15.50, math.inf),
    C._mcPolynomic5: (1.875, 5.774, 60.0, 60.0),
    C._mcPolynomic3: (1.500, 6.000, 12.0, math.inf),
}
# Not in a table we could consult: values of the laws chosen in D31–D33, computed here by hand (docs/cams.md).
MT_JM = 8 * math.pi / (math.pi + 2) * 4 * math.pi  # 61.43
DERIVED = {
    C._mcTrapeclloid: (2.000, 2 * math.pi, MT_JM, MT_JM),
    C._mcReverseTrapeclloid: (2.000, 2 * math.pi, MT_JM, MT_JM),
    C._mcDoubleHarmonic: (2.040, math.pi**2, 42.41, math.inf),
    C._mcReverseDoubleHarmonic: (2.040, math.pi**2, 42.41, math.inf),
    C._mcNC2Curve: (1.718, 4.199, 26.38, math.inf),
}


def test_enum_spellings_and_registry() -> None:
    """§5.4.2 / seed 000 line 17948: the 15 enumerators with the manual's spellings (Trapeclloid), in ENUMS."""
    assert [c.name for c in C] == [
        "_mcConstantLine", "_mcStraightLine", "_mcParabolic", "_mcModifiedConstantVel", "_mcModifiedTrapezoid",
        "_mcModifiedSine", "_mcCycloidal", "_mcTrapeclloid", "_mcReverseTrapeclloid", "_mcSimpleHarmonic",
        "_mcDoubleHarmonic", "_mcReverseDoubleHarmonic", "_mcNC2Curve", "_mcPolynomic3", "_mcPolynomic5"]
    assert [int(c) for c in C] == list(range(15))
    assert ENUMS["_eMC_CAM_CURVE"] is C


@pytest.mark.parametrize("curve", RISING, ids=lambda c: c.name)
def test_rise_from_0_to_1(curve: C) -> None:
    """Every rising law: f(0) = 0, f(1) = 1, monotonic rise, f continuous."""
    x = np.linspace(0.0, 1.0, 4001)
    f = evaluate(curve, x)
    assert f[0] == pytest.approx(0.0, abs=1e-12) and f[-1] == pytest.approx(1.0, abs=1e-12)
    assert np.all(np.diff(f) >= -1e-12)


def test_constant_line_is_a_dwell() -> None:
    """`_mcConstantLine`: no rise, all values 0 (§5.4.2 *3: the distance is the previous node's)."""
    assert np.all(evaluate(C._mcConstantLine, np.linspace(0, 1, 11)) == 0)
    assert characteristics(C._mcConstantLine).Vm == 0.0


@pytest.mark.parametrize("curve", RISING, ids=lambda c: c.name)
def test_derivatives_agree_with_differences(curve: C) -> None:
    """f', f'', f''' are the derivatives of f, f', f'' (central differences away from piece borders)."""
    x = np.linspace(0.013, 0.987, 61)
    x = x[np.min(np.abs(x[:, None] - np.array([1 / 16, 1 / 8, 1 / 4, 3 / 8, 0.5, 5 / 8, 3 / 4, 7 / 8, 15 / 16])),
                 axis=1) > 1e-3]
    h = 1e-6
    for order in range(3):
        num = (evaluate(curve, x + h, order) - evaluate(curve, x - h, order)) / (2 * h)
        assert np.allclose(num, evaluate(curve, x, order + 1), rtol=1e-5, atol=1e-4), order


@pytest.mark.parametrize("curve", [c for c in RISING if c != C._mcStraightLine], ids=lambda c: c.name)
def test_zero_velocity_at_both_ends(curve: C) -> None:
    """All but the straight line start and end at rest: f'(0) = f'(1) = 0."""
    ch = characteristics(curve)
    assert abs(ch.V0) < 1e-9 and abs(ch.V1) < 1e-9


def test_end_accelerations() -> None:
    """Two-dwell laws have A = 0 at both ends; double harmonic is smooth at the start only (D32) and the reverse
    at the end only; simple harmonic, parabolic, NC2 and the cubic jump against a dwell."""
    for c in (C._mcModifiedConstantVel, C._mcModifiedTrapezoid, C._mcModifiedSine, C._mcCycloidal,
              C._mcTrapeclloid, C._mcReverseTrapeclloid, C._mcPolynomic5):
        ch = characteristics(c)
        assert abs(ch.A0) < 1e-9 and abs(ch.A1) < 1e-9, c.name
    dh, rdh = characteristics(C._mcDoubleHarmonic), characteristics(C._mcReverseDoubleHarmonic)
    assert abs(dh.A0) < 1e-9 and math.isclose(dh.A1, -math.pi**2)
    assert math.isclose(rdh.A0, math.pi**2) and abs(rdh.A1) < 1e-9
    for c in (C._mcSimpleHarmonic, C._mcParabolic, C._mcNC2Curve, C._mcPolynomic3):
        assert characteristics(c).Jm_dwell == math.inf, c.name
    assert characteristics(C._mcParabolic).accel_jump_inside


@pytest.mark.parametrize("curve", list(PUBLISHED), ids=lambda c: c.name)
def test_characteristic_values_match_published_tables(curve: C) -> None:
    """Vm, Am, Jm computed from the laws agree with the published tables to their printed digits."""
    vm, am, jm, jm_dwell = PUBLISHED[curve]
    ch = characteristics(curve)
    assert ch.Vm == pytest.approx(vm, abs=6e-4)
    assert ch.Am == pytest.approx(am, abs=6e-4)
    assert ch.Jm == pytest.approx(jm, abs=0.06)
    assert ch.Jm_dwell == (math.inf if jm_dwell == math.inf else pytest.approx(jm_dwell, abs=0.06))


@pytest.mark.parametrize("curve", list(DERIVED), ids=lambda c: c.name)
def test_characteristic_values_of_the_chosen_laws(curve: C) -> None:
    """Trapecloid = MT's first half + cycloid's second half (D32): Vm 2, Am 2π (deceleration), Jm 61.43 (MT);
    double harmonic ½[(1 − cos πx) − ¼(1 − cos 2πx)]: Vm 2.040 at x = ⅔, Am π² at x = 1, Jm 42.41;
    NC2 (D33): Am = 1/(3/16 + 1/(2π²)) = 4.199, Vm = Am(¼ + 1/(2π)) = 1.718, Jm = 2π·Am = 26.38."""
    vm, am, jm, jm_dwell = DERIVED[curve]
    ch = characteristics(curve)
    assert (ch.Vm, ch.Am) == (pytest.approx(vm, abs=6e-4), pytest.approx(am, abs=6e-4))
    assert ch.Jm == pytest.approx(jm, abs=0.06)
    assert ch.Jm_dwell == (math.inf if jm_dwell == math.inf else pytest.approx(jm_dwell, abs=0.06))


def test_reverse_laws_are_mirrors() -> None:
    """"Reverse" = point mirror: f_r(x) = 1 − f(1 − x), so f_r' (x) = f'(1 − x), f_r'' (x) = −f''(1 − x)."""
    x = np.linspace(0, 1, 101)
    for fwd, rev in ((C._mcTrapeclloid, C._mcReverseTrapeclloid), (C._mcDoubleHarmonic, C._mcReverseDoubleHarmonic)):
        assert np.allclose(evaluate(rev, x), 1 - evaluate(fwd, 1 - x), atol=1e-12)
        assert np.allclose(evaluate(rev, x, 1), evaluate(fwd, 1 - x, 1), atol=1e-12)
        assert np.allclose(evaluate(rev, x, 2), -evaluate(fwd, 1 - x, 2), atol=1e-9)


def test_closed_forms_of_the_classical_laws() -> None:
    """Cycloid x − sin(2πx)/2π, simple harmonic (1 − cos πx)/2, modified sine (docs/cams.md) in closed form."""
    x = np.linspace(0, 1, 257)
    assert np.allclose(evaluate(C._mcCycloidal, x), x - np.sin(2 * np.pi * x) / (2 * np.pi), atol=1e-12)
    assert np.allclose(evaluate(C._mcSimpleHarmonic, x), (1 - np.cos(np.pi * x)) / 2, atol=1e-12)
    ms = np.where(x <= 1 / 8, np.pi * x - np.sin(4 * np.pi * x) / 4,
                  np.where(x <= 7 / 8, 2 + np.pi * x - 9 / 4 * np.sin(4 * np.pi * x / 3 + np.pi / 3),
                           4 + np.pi * x - np.sin(4 * np.pi * x) / 4)) / (4 + np.pi)
    assert np.allclose(evaluate(C._mcModifiedSine, x), ms, atol=1e-12)
    assert set(LAWS) == set(C) - {C._mcConstantLine, C._mcPolynomic3, C._mcPolynomic5}
