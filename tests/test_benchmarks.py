"""The benchmark harness runs (tiny durations): every scenario returns its figures with the keys docs/performance.md
and `make bench` rely on. Nothing here asserts on time (the figures are measured, not tested)."""

from __future__ import annotations

import json
import subprocess
import sys

import pytest
from benchmarks import kernel, realtime, sidebyside

from tests.conftest import ROOT

KEYS = {"rtf", "us_per_axis_period", "peak_mb"}


def test_kernel_scenario() -> None:
    r = kernel.run(axes=4, sim_seconds=0.2, period_us=1000)
    assert set(r) >= KEYS and r["axes"] == 4 and r["sim_s"] == pytest.approx(0.2)


def test_side_by_side_runs_the_same_moves() -> None:
    r = sidebyside.run(axes=4, sim_seconds=1.5)
    assert set(r) >= KEYS
    bus, virtual, ref = r["rows"]
    assert bus["moves"] == virtual["moves"] > 0, "MC Studio completes the same back-and-forth moves on both"
    if "skipped" not in ref:
        assert ref["moves"] == bus["moves"], "pyplcopen ran the same number of moves"


def test_realtime_scenario_moves_the_demo() -> None:
    r = realtime.run(seconds=1.0)
    assert set(r) >= KEYS and r["cycles"] > 0 and "completion_margin_us" in r and "overruns" in r


def test_cli_prints_one_json_object_last() -> None:
    out = subprocess.run([sys.executable, "-m", "benchmarks", "kernel", "--axes", "2", "--sim-seconds", "0.1"],
                         cwd=ROOT, capture_output=True, text=True, check=True)
    assert set(json.loads(out.stdout.strip().splitlines()[-1])) >= KEYS


def test_rest_scenario_against_a_server_process() -> None:
    from benchmarks import api

    r = api.run_rest(repetitions=3)
    assert set(r) >= KEYS and r["patch_to_output_ms"]["n"] == 3 and r["patch_to_websocket_ms"]["n"] == 3


def test_kernel_scenario_with_cam_followers() -> None:
    """The kernel scenario's cam followers really cam: ¼ of 8 axes follow a velocity axis through MC_CamIn."""
    r = kernel.run(axes=8, sim_seconds=0.3, period_us=1000)
    assert r["cam_followers"] == 2 and r["cam_followers_in_sync"] == 2


@pytest.mark.parametrize("scenario", [["cams", "--points", "2000"], ["kinematics", "--points", "2000"]])
def test_cam_and_kinematics_sub_commands(scenario: list[str]) -> None:
    out = subprocess.run([sys.executable, "-m", "benchmarks", *scenario], cwd=ROOT, capture_output=True, text=True,
                         check=True)
    assert set(json.loads(out.stdout.strip().splitlines()[-1])) >= KEYS


def test_robot_scenario_runs_pick_cycles() -> None:
    """One Delta3 + conveyor cell: the pick cycle (track, sync out, back) runs without instruction errors."""
    from benchmarks import robot

    r = robot.run(cells=1, axes=2, sim_seconds=2.5)
    assert set(r) >= KEYS and r["axes"] == 6 and r["instruction_errors"] == 0 and r["picks"] >= 1
