"""Delta3 + conveyor tracking: K robot cells of the demo (three servo axes of a Delta3 group and a conveyor axis on
the emulated bus, each cell on its own nodes) next to N plain moving axes, fast mode, 1 ms period.

Every cell runs a pick cycle driven from this script like a PLC program would: MC_SyncLinearConveyor onto the
latest workpiece of the plant's WorkpieceSource (catch up, InSync, follow), 0.2 s of tracking, MC_SyncOut (lift and
leave), MC_MoveTimeAbsolute back to the ready point, again. Per period the controller maps each robot's Cartesian
command to joint angles (one-point inverse kinematics + workspace checks) and packs/unpacks 4 slaves per cell.
"""

from __future__ import annotations

import copy
import math
import resource
import time
from pathlib import Path
from typing import Any

from mcstudio.controller.kernel import Controller
from mcstudio.controller.mc.kinematics.point import inverse_point
from mcstudio.plant.workpieces import WorkpieceSource
from mcstudio.project.io import load_project
from mcstudio.project.models import AxisConfig, Project

from . import kernel

DEMO = Path(__file__).resolve().parents[1] / "projects" / "demo"
ROBOT_AXES = ("MC_Axis004", "MC_Axis005", "MC_Axis006")
CONVEYOR = "MC_Axis007"
READY = [0.0, 0.0, -150.0, 0.0, 0.0, 0.0]
BELT_Z = -280.0
SRC = WorkpieceSource(pitch=200.0, entry_x=-250.0, exit_x=250.0, y=20.0, z=0.0)
TRACK = {"SyncTrajType": 0, "TrajTime": [100, 300, 100], "TrajTransition": [50, 50], "TrajDistance": [30.0],
         "MaxVelocity": 5000.0, "MaxAcceleration": 1e6}
OUT = {"SyncStopType": 0, "TrajTime": [200], "TrajDistance": [50.0], "MaxVelocity": 5000.0, "MaxAcceleration": 1e6}
HOME = {"MoveTrajType": 0, "TrajTime": 300, "MaxVelocity": 5000.0, "MaxAcceleration": 1e6}


def build(cells: int, axes: int) -> tuple[Controller, list[dict[str, Any]]]:
    demo = load_project(DEMO)
    by_name = {a.name: a for a in demo.axes}
    group = next(g for g in demo.groups if g.name == "MC_Group000")
    plain = kernel.build(axes, 1000).project.axes if axes else []
    out_axes: list[AxisConfig] = list(plain)
    groups = []
    cell_names = []
    number = len(out_axes)
    node = len(out_axes) + 1
    for k in range(cells):
        names = {}
        for old in (*ROBOT_AXES, CONVEYOR):
            cfg = copy.deepcopy(by_name[old])
            cfg.name = f"MC_Axis{number:03d}"
            cfg.number = number
            cfg.node_address = node
            names[old] = cfg.name
            out_axes.append(cfg)
            number += 1
            node += 1
        g = copy.deepcopy(group)
        g.name = f"MC_Group{k:03d}"
        g.number = k
        g.axes = [names[a] for a in ROBOT_AXES]
        groups.append(g)
        cell_names.append({"group": g.name, "conveyor": names[CONVEYOR], "axes": g.axes})
    project = Project(name=f"robot-bench-{cells}", controller=demo.controller, axes=out_axes, groups=groups)
    return Controller(project), cell_names


def run(*, cells: int = 4, axes: int = 0, sim_seconds: float = 5.0) -> dict[str, Any]:
    c, names = build(cells, axes)
    c.step(2)
    for a in c.project.axes:
        c.fb("MC_Power", Axis=a.name, Enable=True)
    c.step(30)
    if axes:
        for i in range(axes):
            c.fb("MC_MoveVelocity", Axis=f"MC_Axis{i:03d}", Execute=True, Velocity=20.0 + i % 7, Acceleration=500.0,
                 Deceleration=500.0)
    cells_state = []
    for cell in names:
        g = c.mc.groups_by_name[cell["group"]]
        assert g.kinematics is not None
        _, q = inverse_point(g.kinematics.params(), *READY[:3])
        moves = [c.fb("MC_MoveAbsolute", Axis=a, Execute=True, Position=q[j], Velocity=200.0, Acceleration=2000.0,
                      Deceleration=2000.0) for j, a in enumerate(cell["axes"])]
        c.step(2000)
        assert all(mv.Done for mv in moves), "the robot reached the ready pose"
        c.fb("MC_DefineCoordSystem", AxesGroup=cell["group"], Execute=True,
             CoordTransform={"CSID": 0, "Pose": [0.0, 0.0, BELT_Z, 0.0, 0.0, 0.0]})
        c.fb("MC_GroupEnable", AxesGroup=cell["group"], Execute=True)
        c.fb("MC_MoveVelocity", Axis=cell["conveyor"], Execute=True, Velocity=100.0, Acceleration=1000.0,
             Deceleration=1000.0)
        cells_state.append({"cell": cell, "state": "idle", "since": 0, "picks": 0, "fb": None})
    c.step(300)
    cycles = round(sim_seconds / c.period_s)
    errors = 0
    t0 = time.perf_counter()
    for k in range(cycles):
        if k % 5 == 0:
            for st in cells_state:
                errors += _sequence(c, st, k)
        c.step(1, publish=False)
    wall = time.perf_counter() - t0
    n_axes = len(c.project.axes)
    return {
        "scenario": "robot",
        "cells": cells,
        "plain_axes": axes,
        "axes": n_axes,
        "sim_s": cycles * c.period_s,
        "wall_s": round(wall, 3),
        "rtf": round(cycles * c.period_s / wall, 3),
        "us_per_period": round(wall / cycles * 1e6, 2),
        "us_per_axis_period": round(wall / cycles / n_axes * 1e6, 3),
        "picks": sum(st["picks"] for st in cells_state),
        "instruction_errors": errors,
        "peak_mb": round(resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024, 1),
    }


def _sequence(c: Controller, st: dict[str, Any], k: int) -> int:
    """One step of a cell's pick cycle; returns 1 when an instruction ended in Error (counted, then restarted)."""
    cell = st["cell"]
    fb = st["fb"]
    if fb is not None and fb.Error:
        c.delete_fb(fb.id)
        st["reset"] = c.fb("MC_GroupReset", AxesGroup=cell["group"], Execute=True)
        st.update(state="idle", fb=None)
        return 1
    reset = st.get("reset")
    if reset is not None:
        if not (reset.Done or reset.Error):
            return 0
        c.delete_fb(reset.id)
        st["reset"] = None
    grp = cell["group"]
    if st["state"] == "idle":
        conv = c.mc.by_name[cell["conveyor"]]
        pos = float(c.mc.act_pos[conv.i])
        n = math.floor(pos / SRC.pitch)
        init = list(SRC.workpiece(n, pos))
        st["fb"] = c.fb("MC_SyncLinearConveyor", AxesGroup=grp, ConveyorAxis=cell["conveyor"], Execute=True,
                        InitWorkpiecePosition=init, TrajData=TRACK, CoordSystem="_mcRBT_UCS", CSID=0)
        st.update(state="sync", since=k)
    elif st["state"] == "sync" and fb.InSync and k - st["since"] > 700:
        c.delete_fb(fb.id)  # MC_SyncOut aborts it; the program keeps one instance per step (bounded)
        st["fb"] = c.fb("MC_SyncOut", AxesGroup=grp, Execute=True, TrajData=OUT)
        st.update(state="out", since=k)
    elif st["state"] == "out" and fb.Done:
        c.delete_fb(fb.id)
        st["fb"] = c.fb("MC_MoveTimeAbsolute", AxesGroup=grp, Execute=True, Position=READY, TrajData=HOME)
        st.update(state="home", since=k)
    elif st["state"] == "home" and fb.Done:
        c.delete_fb(fb.id)
        st["picks"] += 1
        st.update(state="idle", fb=None)
    return 0
