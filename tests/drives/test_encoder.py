"""Encoder input slaves (GX-EC02xx style): counting at the external mechanism's speed, latches like a touch probe."""

from __future__ import annotations

import numpy as np

from mcstudio.drives.cia402 import DI_EXT1, TP1_ENABLE, TP1_NEG_EDGE, TP1_POS_EDGE, TS1_NEG_STORED, TS1_STORED
from mcstudio.drives.encoder import EncoderInputs
from mcstudio.drives.sensing import SensorLayout
from mcstudio.fieldbus.objects import RX_DTYPE, TX_DTYPE


def _enc(n: int = 2) -> tuple[EncoderInputs, np.ndarray, np.ndarray, np.ndarray]:
    s = SensorLayout(n)
    s.ext1[0] = (1000.0, 1100.0)
    return EncoderInputs(n, s, 0.001), np.zeros(n, dtype=RX_DTYPE), np.zeros(n, dtype=TX_DTYPE), np.ones(n, bool)


def test_encoder_counts_at_the_mechanism_speed() -> None:
    enc, rx, tx, online = _enc()
    tx["statusword"] = 0x1234  # stale: every field is rewritten
    enc.velocity[:] = [250_250.0, -1000.0]  # 250.25 pulses per period: the fraction is kept
    for _ in range(4):
        enc.cycle(rx, tx, online)
    assert tx["position_actual"].tolist() == [1001, -4]
    assert tx["velocity_actual"].tolist() == [250_000, -1000]  # 750.75 → 751 → 1001
    assert int(tx["statusword"][0]) == 0
    enc.position[0] = 2**31 - 1
    enc.cycle(rx, tx, online)
    assert int(tx["position_actual"][0]) < 0, "32-bit wrap-around of 4010h"


def test_encoder_latches_the_edges_of_ext1() -> None:
    enc, rx, tx, online = _enc()
    enc.velocity[0] = 70_000.0  # 70 pulses per period: the latches hold the edges, not the samples
    rx["touch_probe_function"][0] = TP1_ENABLE | TP1_POS_EDGE | TP1_NEG_EDGE
    seen_di = 0
    for _ in range(20):
        enc.cycle(rx, tx, online)
        seen_di |= int(tx["digital_inputs"][0])
    st = int(tx["touch_probe_status"][0])
    assert st & TS1_STORED and st & TS1_NEG_STORED and seen_di & DI_EXT1
    assert int(tx["touch_probe_pos1"][0]) == 1000 and int(tx["touch_probe_neg1"][0]) == 1100


def test_offline_encoder_keeps_its_latch_function_and_still_counts() -> None:
    enc, rx, tx, online = _enc(1)
    enc.velocity[0] = 300_000.0
    rx["touch_probe_function"][0] = TP1_ENABLE | TP1_POS_EDGE
    enc.cycle(rx, tx, online)
    online[0] = False
    rx["touch_probe_function"][0] = 0  # not delivered
    for _ in range(4):
        enc.cycle(rx, tx, online)
    assert int(enc.position[0]) == 1500 and int(enc.probe_pos1[0]) == 1000
