"""Kernel scaling: N servo axes on the emulated EtherCAT bus, all moving: positioning back and forth, velocity
control, and (with `cam_share`, default ¼) periodic MC_CamIn slaves following a velocity axis through a 361-point
cam table; the controller runs as fast as it can (fast mode), publishing snapshots at 120 Hz of wall time as the
runner does in fast mode (checked every 8 periods). With `trace` (default 8) a continuous data trace records that many
variables every period into a 100,000-sample ring (docs/trace.md): axis variables of several axes, an instance output
and a PDO entry, as a commissioning engineer would."""

from __future__ import annotations

import resource
import time
from typing import Any

from mcstudio.controller.kernel import Controller
from mcstudio.controller.mc.cam.table import CamTable
from mcstudio.controller.runner import PUBLISH_INTERVAL_S
from mcstudio.project.models import AxisConfig, ControllerSettings, Project

PARAMS = {
    "UnitConversion": {"UnitDisplay": "_mcMm", "CmdPlsCountPerMotorRotation": 1048576,
                       "WorkTravelDistancePerMotorRotation": 10.0},
    "Operation": {"MaxVel": 1000.0, "MaxJogVel": 100.0, "MaxAcc": 20000.0, "MaxDec": 20000.0},
    "Limit": {"PosiSwLimit": 100000.0, "NegaSwLimit": -100000.0},
    "Homing": {"Vel": 50.0, "ApproachVel": 5.0, "CompensationVel": 10.0},
}


def cam_table() -> CamTable:
    """A rise–dwell–return cam over 360 units of master travel, 1-unit pitch (cycloidal rise and return)."""
    import numpy as np

    x = np.arange(361.0)
    rise = 50.0 * (x / 120.0 - np.sin(2 * np.pi * x / 120.0) / (2 * np.pi))
    ret = 50.0 * (1 - ((x - 240.0) / 120.0 - np.sin(2 * np.pi * (x - 240.0) / 120.0) / (2 * np.pi)))
    d = np.where(x < 120, rise, np.where(x < 240, 50.0, ret))
    return CamTable.from_points(x, d)


def build(axes: int, period_us: int) -> Controller:
    project = Project(
        name=f"bench-{axes}",
        controller=ControllerSettings(primary_period_us=period_us),
        axes=[AxisConfig(name=f"MC_Axis{i:03d}", number=i, type="_mcServo", node_address=i + 1, parameters=PARAMS)
              for i in range(axes)],
    )
    return Controller(project, cams={"Cam": cam_table()})


TRACE_MEMBERS = ("Cmd.Pos", "Cmd.Vel", "Act.Pos", "Act.Vel", "Cmd.AccDec", "Act.Trq")


def add_trace(c: Controller, n: int, busy_fb: int | None) -> None:
    """A continuous trace of `n` variables: axis members over the axes, then an instance's Busy and a PDO entry."""
    from mcstudio.project.trace_models import TraceSettings, TraceVariable

    axes = len(c.mc.axes)
    extra: list[TraceVariable] = [TraceVariable(kind="pdo", target="1", name="6064:00")]
    if busy_fb is not None:
        extra.insert(0, TraceVariable(kind="fb", target=str(busy_fb), name="Busy"))
    k_axis = max(0, n - len(extra))
    variables = [TraceVariable(kind="axis", target=f"MC_Axis{k % axes:03d}", name=TRACE_MEMBERS[k % 6])
                 for k in range(k_axis)] + extra[:n - k_axis]
    c.traces.configure(TraceSettings(name="bench", variables=variables, samples=100_000, mode="continuous"))


def run(*, axes: int, sim_seconds: float, period_us: int, cam_share: float = 0.25, trace: int = 8
        ) -> dict[str, Any]:
    c = build(axes, period_us)
    n_cam = round(axes * cam_share) if axes >= 4 else 0
    cam_slaves = {i for i in range(3, axes, 4)}
    cam_slaves = set(sorted(cam_slaves)[:n_cam])
    for i in range(axes):
        c.fb("MC_Power", Axis=f"MC_Axis{i:03d}", Enable=True)
    c.step(10)
    moves = []
    cams = []
    for i in range(axes):
        name = f"MC_Axis{i:03d}"
        if i in cam_slaves:  # follows the velocity axis i − 2 through the cam, periodically
            cams.append(c.fb("MC_CamIn", Master=f"MC_Axis{i - 2:03d}", Slave=name, CamTable="Cam", Execute=True,
                             Periodic=True, ReferenceType="_mcLatestCommand"))
        elif i % 2 == 0:
            moves.append(c.fb("MC_MoveAbsolute", Axis=name, Execute=True, Position=50.0 + i, Velocity=200.0,
                              Acceleration=2000.0, Deceleration=2000.0, Jerk=50000.0))
        else:
            c.fb("MC_MoveVelocity", Axis=name, Execute=True, Velocity=25.0 + i % 7, Acceleration=500.0,
                 Deceleration=500.0)
    if trace:
        add_trace(c, trace, moves[0].id if moves else None)
    cycles = round(sim_seconds / c.period_s)
    publish_s = PUBLISH_INTERVAL_S  # snapshots as the runner publishes them in fast mode: at 120 Hz of wall time
    publications = 0
    t0 = next_publish = time.perf_counter()
    for k in range(cycles):
        if k % 400 == 0:  # keep the positioning axes busy: new targets back and forth
            for mv in moves:
                mv.Execute = False
            c.step(1, publish=False)
            for j, mv in enumerate(moves):
                mv.Position = (50.0 + j) * (1 if (k // 400) % 2 else -1)
                mv.Execute = True
        c.step(1, publish=False)
        if k % 8 == 0 and (now := time.perf_counter()) >= next_publish:
            c.publish()
            publications += 1
            next_publish = now + publish_s
    wall = time.perf_counter() - t0
    sim = cycles * c.period_s
    peak_mb = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024
    return {
        "scenario": "kernel",
        "axes": axes,
        "cam_followers": len(cam_slaves),
        "cam_followers_in_sync": sum(1 for fb in cams if fb.InSync and not fb.Error),
        "period_us": period_us,
        "sim_s": sim,
        "wall_s": round(wall, 3),
        "rtf": round(sim / wall, 3),
        "us_per_period": round(wall / cycles * 1e6, 2),
        "us_per_axis_period": round(wall / cycles / axes * 1e6, 3),
        "peak_mb": round(peak_mb, 1),
        "snapshots_per_s": round(publications / wall, 1),
        "traced_variables": trace,
    }
