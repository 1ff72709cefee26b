"""Data trace engine (controller/trace.py) on the paused controller.

What Sysmac Studio's data trace promises, checked cycle by cycle: samples taken at the end of the period and stamped
with its cycle; the trigger sample sits exactly at the pre-trigger position; a single record holds exactly `samples`
samples; the continuous ring keeps the last N; sampling every N periods; the trace of an MC_MoveAbsolute shows the
trapezoid its inputs imply (omron-axis-instructions.md "MC_MoveAbsolute", seed 000 line 3491).
"""

from __future__ import annotations

import copy

import numpy as np
import pytest

from mcstudio.controller.kernel import Controller
from mcstudio.controller.trace import MEMORY_BUDGET_BYTES, TraceError
from mcstudio.project.models import AxisConfig, Project
from mcstudio.project.trace_models import MAX_TRACES, TraceSettings
from tests.conftest import MM_AXIS, power_on


def _settings(variables: list[tuple[str, str, str]], **kw: object) -> TraceSettings:
    return TraceSettings.model_validate({
        "variables": [{"kind": k, "target": t, "name": n} for k, t, n in variables], **kw})


def _trig(kind: str, target: str, name: str, condition: str = "rising", level: float = 0.5,
          pre: float = 10.0) -> dict[str, object]:
    return {"variable": {"kind": kind, "target": target, "name": name}, "condition": condition, "level": level,
            "pre_trigger_percent": pre}


def test_move_absolute_trace_shows_the_trapezoid(ctrl: Controller) -> None:
    """0 → 100 at Velocity 50, Acceleration = Deceleration 500, Jerk 0: the 2.1 s trapezoid. Triggered on the
    instance's Busy↑ with 10 % pre-trigger of 3000 samples: the trigger sample is sample 300, stamped with the cycle of
    Execute↑; Cmd.Vel peaks at exactly Velocity, Cmd.AccDec is +Acceleration then −Deceleration; the record is done
    after 3000 samples."""
    power_on(ctrl)
    mv = ctrl.fb("MC_MoveAbsolute", Axis="MC_Axis000", Execute=False, Position=100.0, Velocity=50.0,
                 Acceleration=500.0, Deceleration=500.0, Jerk=0.0)
    t = ctrl.traces.configure(_settings(
        [("axis", "MC_Axis000", "Cmd.Pos"), ("axis", "MC_Axis000", "Cmd.Vel"), ("axis", "MC_Axis000", "Cmd.AccDec"),
         ("fb", str(mv.id), "Busy")],
        samples=3000, trigger=_trig("fb", str(mv.id), "Busy", pre=10.0)))
    ctrl.step(500)  # well over the 300 pre-trigger samples
    assert t.state == "waiting"
    execute_cycle = ctrl.cycle
    mv.Execute = True
    ctrl.step(1)
    assert t.state == "triggered"
    ctrl.step(2698)
    assert t.state == "triggered"
    ctrl.step(1)  # the 3000th sample of the record
    assert t.state == "done" and not ctrl.traces.running
    data = t.read()
    assert data["sample_count"] == 3000
    assert data["trigger_index"] == 300 == data["pre_trigger_samples"]
    assert data["trigger_cycle"] == execute_cycle
    cycles = data["cycles"]
    assert cycles[300] == execute_cycle and np.all(np.diff(cycles) == 1)
    pos, vel, acc, busy = (s["values"] for s in data["series"])
    assert busy[299] == 0 and busy[300] == 1
    assert vel.max() == pytest.approx(50.0, abs=1e-9)
    assert acc.max() == pytest.approx(500.0, abs=1e-6) and acc.min() == pytest.approx(-500.0, abs=1e-6)
    # cruise at Velocity between the ramps (0.1 s each), position on target at the end
    k0 = 300
    assert np.allclose(vel[k0 + 110:k0 + 1990], 50.0, atol=1e-9)
    assert pos[-1] == 100.0 and pos[299] == 0.0
    assert [s["unit"] for s in data["series"]] == ["mm", "mm/s", "mm/s²", "bool"]
    # the samples are the period's end values: the kernel's arrays after that cycle
    assert pos[-1] == ctrl.mc.cmd_pos[0]


def test_pre_trigger_share_is_exact_when_the_condition_holds_at_once(ctrl: Controller) -> None:
    """A level condition that is TRUE from the start fires only once the pre-trigger samples are recorded (the
    trigger is armed then), so the trigger is sample `round(samples × share)`."""
    t = ctrl.traces.configure(_settings([("axis", "MC_Axis000", "Cmd.Pos")], samples=200,
                                        trigger=_trig("axis", "MC_Axis000", "Cmd.Pos", "gt", -1.0, pre=25.0)))
    start = ctrl.cycle
    ctrl.step(199)
    assert t.state == "triggered"
    ctrl.step(1)
    d = t.read()
    assert t.state == "done" and d["trigger_index"] == 50 and d["trigger_cycle"] == start + 50
    assert list(d["cycles"]) == list(range(start, start + 200))


def test_continuous_ring_keeps_the_last_samples(ctrl: Controller) -> None:
    t = ctrl.traces.configure(_settings([("axis", "MC_Axis002", "Cmd.Pos")], samples=100, mode="continuous"))
    ctrl.step(250)
    assert t.state == "running"
    d = t.read()
    assert d["sample_count"] == 100 and d["trigger_index"] is None
    assert list(d["cycles"]) == list(range(150, 250))
    ctrl.traces.stop(t.id)
    ctrl.step(10)
    assert list(t.read()["cycles"]) == list(range(150, 250)), "a stopped trace records nothing more"


def test_sampling_every_n_periods_and_decimated_reading(ctrl: Controller) -> None:
    t = ctrl.traces.configure(_settings([("axis", "MC_Axis000", "Act.Pos")], samples=1000, sampling_periods=4,
                                        mode="continuous"))
    ctrl.step(400)
    d = t.read()
    assert d["sample_count"] == 100 and list(d["cycles"][:3]) == [0, 4, 8]
    d = t.read(max_points=30)
    assert d["decimation"] == 4 and len(d["cycles"]) == 25 and list(d["cycles"][:2]) == [0, 16]


def test_single_without_trigger_records_from_the_start(ctrl: Controller) -> None:
    ctrl.step(7)
    t = ctrl.traces.configure(_settings([("axis", "MC_Axis000", "Cmd.Vel")], samples=50))
    ctrl.step(60)
    d = t.read()
    assert t.state == "done" and d["trigger_index"] == 0 and d["cycles"][0] == 7 and d["cycles"][-1] == 56


def test_repeat_rearms_and_keeps_the_last_complete_record(ctrl: Controller) -> None:
    """Repeat mode: each record is complete when its post-trigger samples are in; reading shows the last complete
    record while the next one fills."""
    t = ctrl.traces.configure(_settings([("axis", "MC_Axis000", "Cmd.Pos")], samples=10, mode="repeat",
                                        trigger=_trig("axis", "MC_Axis000", "Cmd.Pos", "gt", -1.0,
                                                      pre=20.0)))
    ctrl.step(10)
    assert t.records == 1 and t.state == "waiting"
    first = list(t.read()["cycles"])
    assert first == list(range(0, 10))
    ctrl.step(15)
    assert t.records == 2
    assert list(t.read()["cycles"]) == list(range(10, 20))
    assert t.read()["trigger_index"] == 2


def test_falling_edge_of_a_bool_and_pdo_entries(ctrl: Controller) -> None:
    """PDO entries are read from the master's records (what crossed the wire this period); a falling edge of a
    BOOL triggers on TRUE → FALSE whatever the level."""
    pw = power_on(ctrl)
    t = ctrl.traces.configure(_settings(
        [("pdo", "1", "6041:00"), ("pdo", "1", "Position actual value"), ("pdo", "1", "0x607A"),
         ("fb", str(pw.id), "Status")],
        samples=20, trigger=_trig("fb", str(pw.id), "Status", "falling", 0.0, pre=50.0)))
    ctrl.step(30)
    assert t.state == "waiting"
    pw.Enable = False
    ctrl.step(30)
    d = t.read()
    assert t.state == "done" and d["trigger_index"] == 10
    sw, _pos, target, status = (s["values"] for s in d["series"])
    assert status[9] == 1 and status[10] == 0
    assert sw[-1] == ctrl.network.tx["statusword"][0]
    assert target[-1] == ctrl.network.rx["target_position"][0]
    assert d["series"][0]["label"] == "Node1.6041:00" and d["series"][0]["type"] == "INT"


def test_rotary_positions_read_on_the_ring_counter() -> None:
    params = copy.deepcopy(MM_AXIS)
    params["PosCount"] = {"CountMode": "_mcCountModeRotary", "ModuloMinPosVal": 0.0, "ModuloMaxPosVal": 360.0}
    c = Controller(Project(name="rot", axes=[AxisConfig(name="A", number=0, type="_mcVirServo", parameters=params)]))
    power_on(c, "A")
    c.fb("MC_MoveVelocity", Axis="A", Execute=True, Velocity=400.0, Acceleration=0.0, Deceleration=0.0)
    t = c.traces.configure(_settings([("axis", "A", "Cmd.Pos"), ("axis", "A", "Status.Continuous")],
                                     samples=2000))
    c.step(2000)
    pos, cont = (s["values"] for s in t.read()["series"])
    assert pos.min() >= 0.0 and pos.max() < 360.0 and cont[-1] == 1
    assert pos[-1] == c.publish().mc["cmd_pos"][0], "as the snapshot reports it"


def test_unknown_names_are_refused_naming_the_field(ctrl: Controller) -> None:
    cases = [
        ([("axis", "Nope", "Cmd.Pos")], "variables[0].target", "no axis named 'Nope'"),
        ([("axis", "MC_Axis000", "Cmd.Speed")], "variables[0].name", "Cmd.Speed"),
        ([("axis", "MC_Axis000", "Cmd.Pos"), ("fb", "99", "Busy")], "variables[1].target", "instance 99"),
        ([("pdo", "7", "6064:00")], "variables[0].target", "node address 7"),
        ([("pdo", "1", "2000:00")], "variables[0].name", "not in the PDO mapping"),
        ([("group", "G", "Cmd.Vel")], "variables[0].target", "no axes group"),
    ]
    for variables, field, text in cases:
        with pytest.raises(TraceError) as err:
            ctrl.traces.configure(_settings(variables))
        assert err.value.field == field and text in err.value.message, (field, err.value)
    mv = ctrl.fb("MC_MoveAbsolute", Axis="MC_Axis000")
    with pytest.raises(TraceError) as err:
        ctrl.traces.configure(_settings([("fb", str(mv.id), "Axis")]))
    assert err.value.field == "variables[0].name"
    with pytest.raises(TraceError) as err:
        ctrl.traces.configure(_settings([("axis", "MC_Axis000", "Cmd.Pos")],
                                        trigger=_trig("axis", "X", "Cmd.Pos")))
    assert err.value.field == "trigger.variable.target"
    assert not ctrl.traces.traces


def test_bounded_number_and_memory(ctrl: Controller) -> None:
    for _ in range(MAX_TRACES):
        ctrl.traces.configure(_settings([("axis", "MC_Axis000", "Cmd.Pos")], samples=100))
    with pytest.raises(TraceError) as err:
        ctrl.traces.configure(_settings([("axis", "MC_Axis000", "Cmd.Pos")], samples=100))
    assert err.value.status == 409
    for tid in list(ctrl.traces.traces):
        ctrl.traces.delete(tid)
    big = _settings([("axis", "MC_Axis000", "Cmd.Pos")] * 32, samples=1_000_000, mode="repeat",
                    trigger=_trig("axis", "MC_Axis000", "Cmd.Pos"))
    assert MEMORY_BUDGET_BYTES < 2 * 33 * 8 * 1_000_000
    with pytest.raises(TraceError) as err:
        ctrl.traces.configure(big)
    assert err.value.field == "samples" and "MiB" in err.value.message


def test_a_trace_does_not_change_the_motion(ctrl: Controller) -> None:
    """Tracing only reads: the same commands with and without 8 traced variables give bit-identical positions."""
    def run(c: Controller, trace: bool) -> np.ndarray:
        power_on(c)
        if trace:
            names = ["Cmd.Pos", "Cmd.Vel", "Cmd.AccDec", "Cmd.Jerk", "Cmd.Trq", "Act.Pos", "Act.Vel", "Act.Trq"]
            c.traces.configure(_settings([("axis", "MC_Axis000", n) for n in names], samples=1000,
                                         mode="continuous"))
        c.fb("MC_MoveAbsolute", Axis="MC_Axis000", Execute=True, Position=12.0, Velocity=40.0, Acceleration=400.0,
             Deceleration=400.0, Jerk=10000.0)
        out = []
        for _ in range(600):
            c.step(1, publish=False)
            out.append(c.mc.act_pos[0])
        return np.array(out)

    from tests.conftest import small_project
    assert np.array_equal(run(ctrl, True), run(Controller(small_project()), False))
