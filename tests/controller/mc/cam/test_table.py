"""The cam table model: end point and MC_SetCamTableProperty (§5.1, seed 000 lines 17380–17470), REAL storage,
evaluation by linear interpolation between cam data (seed 000 line 6736), and the many-axes evaluator."""

from __future__ import annotations

import numpy as np
import pytest

from mcstudio.controller.mc.cam.table import CamTable, CamTableSet, find_end_point


def my_cam1() -> CamTable:
    """`MyCam1 : ARRAY[0..4999]`: phases 0 … 360.0 in steps of 0.36 up to [999], Phase 0 from [1000] on."""
    t = CamTable(5000)
    t.phase[:1000] = np.linspace(0.0, 360.0, 1000)
    t.distance[:1000] = np.linspace(0.0, 10.0, 1000)
    t.phase[995:1000] = [359.6, 359.7, 359.8, 359.9, 360.0]
    t.distance[995:1000] = [5, 4, 2, 1, 0]
    return t


def test_set_cam_table_property_worked_examples() -> None:
    """§5.1 worked examples: EndPointIndex 999 (MaxDataNumber 5000); [997].Phase := 0 and [996] := (360.0, 0)
    → 996; phases written into [1000]…[4997] with [4997] = 360.00 → 4997."""
    t = my_cam1()
    ep = t.set_cam_table_property()
    assert (ep.error_id, ep.end_point_index, ep.max_data_number) == (0, 999, 5000)
    assert t.end_point_index == 999

    t.phase[997] = 0.0
    t.phase[996], t.distance[996] = 360.0, 0.0
    assert t.set_cam_table_property().end_point_index == 996

    t = my_cam1()
    t.set_cam_table_property()
    # the figure shows [998] = (100.3, 20.3) … [4996] = (359.99, 0.01), [4997] = (360.00, 0.0): the whole table
    # rewritten with 4997 finer steps (only the tail of it is printed)
    t.phase[1:4998] = np.linspace(0.0, 360.0, 4998)[1:]
    t.phase[4996], t.phase[4997] = 359.99, 360.00
    t.phase[4998:] = 0.0
    # "same rewrite but instruction not executed": the cam still runs over [0]..[999]
    assert t.end_point_index == 999 and t.valid()[0].size == 1000
    ep = t.set_cam_table_property()
    assert ep.ok and ep.end_point_index == 4997 and t.valid()[0][-1] == pytest.approx(360.0)


def test_5480_not_ascending_or_no_valid_data() -> None:
    """5480: a phase not above the previous one before the first Phase 0 (NaN too), or no data after the start
    point; the end point in force is kept (A-1: no effect)."""
    t = my_cam1()
    t.set_cam_table_property()
    t.phase[500] = t.phase[499]
    ep = t.set_cam_table_property()
    assert (ep.error_id, ep.end_point_index) == (0x5480, 0) and t.end_point_index == 999
    t.phase[500] = np.nan
    assert t.set_cam_table_property().error_id == 0x5480
    t.phase[500] = -1.0  # negative is not a terminator: a descending phase
    assert t.set_cam_table_property().error_id == 0x5480
    assert find_end_point(np.zeros(10)).error_id == 0x5480  # [1].Phase = 0: only the start point
    assert find_end_point(np.zeros(1)).error_id == 0x5480
    assert find_end_point([]).error_id == 0x5480
    # non-ascending data *after* the terminator do not matter
    assert find_end_point([0, 1, 2, 0, 5, 3]).end_point_index == 2
    # no terminator: the last element is the end point
    assert find_end_point([0, 1, 2, 3]).end_point_index == 3


def test_real_storage() -> None:
    """D35: values are stored as REAL (float32): 100000.001 and 100000.002 are the same REAL → 5480."""
    t = CamTable.from_points([0.0, 100000.001, 100000.002], [0.0, 1.0, 2.0], size=4)
    assert t.phase.dtype == np.float32 and t.end_point_index is None
    assert CamTable.from_points([0, 0.1], [0, 0.1]).phase[1] == np.float32(0.1)
    with pytest.raises(ValueError):
        CamTable(0)
    with pytest.raises(ValueError):
        CamTable.from_points([0, 1, 2], [0, 1], size=4)


def test_evaluate_interpolates_linearly() -> None:
    """Seed 000 line 6736: the slave position is interpolated linearly between two cam data points; outside the
    table the nearer end holds."""
    t = CamTable.from_points([0, 10, 20, 40], [0, 5, 5, -5], size=10)
    assert t.end_point_index == 3 and t.max_data_number == 10
    d = t.evaluate(np.array([-1, 0, 5, 10, 15, 30, 40, 50]))
    assert np.allclose(d, [0, 0, 2.5, 5, 5, 0, -5, -5])
    with pytest.raises(ValueError):
        CamTable(5).evaluate(1.0)


def test_table_set_evaluates_many_axes_like_each_table() -> None:
    """CamTableSet: one vector search for all axes over several tables gives each table's own interpolation."""
    rng = np.random.default_rng(1)
    tables = []
    for k in range(5):
        n = int(rng.integers(2, 400))
        p = np.concatenate([[0.0], np.cumsum(rng.uniform(0.001, 3.0, n - 1))])
        tables.append(CamTable.from_points(p, rng.normal(0, 50, n) * (k + 1), size=n + k))
    s = CamTableSet(tables)
    which = rng.integers(0, 5, 300)
    for _ in range(3):
        ends = np.array([tables[k].valid()[0][-1] for k in which], dtype=float)
        phase = rng.uniform(-5, 1.05, 300) * ends
        expect = np.array([tables[k].evaluate(ph) for k, ph in zip(which, phase, strict=True)])
        assert np.allclose(s.evaluate(which, phase), expect, rtol=1e-12, atol=1e-9)
    # exactly on cam data
    p0, d0 = tables[0].valid()
    assert np.allclose(s.evaluate(np.zeros(p0.size, dtype=int), p0.astype(float)), d0, atol=1e-9)
    with pytest.raises(ValueError):
        CamTableSet([CamTable(3)])
