"""The process image is the bytes of the PDO mapping (little-endian, packed, in mapping order), every period."""

from __future__ import annotations

from mcstudio.fieldbus.config import resolve_slaves
from mcstudio.fieldbus.network import Network
from mcstudio.fieldbus.pdo import PdoEntryConfig, PdoMappingConfig, SlavePdoConfig
from mcstudio.project.models import EtherCATSlaveConfig
from tests.conftest import small_project


def _net(**slave1: object) -> Network:
    p = small_project()
    if slave1:
        p.ethercat.slaves = [EtherCATSlaveConfig(node_address=1, **slave1), EtherCATSlaveConfig(node_address=2)]
    return Network(resolve_slaves(p))


def test_rx_bytes_on_the_wire_equal_hand_computed() -> None:
    net = _net()
    rx = net.rx
    rx["controlword"][0] = 0x000F
    rx["target_position"][0] = 0x01020304
    rx["target_velocity"][0] = -2
    rx["target_torque"][0] = 0x0A0B
    rx["modes_of_operation"][0] = 8
    rx["touch_probe_function"][0] = 0x0011
    rx["max_profile_velocity"][0] = 0x00010000
    rx["positive_torque_limit"][0] = 3000
    rx["negative_torque_limit"][0] = 1000
    net.exchange()
    rx_bytes, _ = net.image_bytes(0)
    # 6040h UINT | 607Ah DINT | 60FFh DINT | 6071h INT | 6060h SINT | 60B8h UINT | 607Fh UDINT | 60E0h UINT | 60E1h UINT
    assert rx_bytes == bytes([0x0F, 0x00, 0x04, 0x03, 0x02, 0x01, 0xFE, 0xFF, 0xFF, 0xFF, 0x0B, 0x0A, 0x08,
                              0x11, 0x00, 0x00, 0x00, 0x01, 0x00, 0xB8, 0x0B, 0xE8, 0x03])
    # and the drive received exactly these values
    assert int(net.drive_rx["target_position"][0]) == 0x01020304 and int(net.drive_rx["target_velocity"][0]) == -2


def test_tx_bytes_follow_the_drive() -> None:
    net = _net()
    for cw in (0x0006, 0x0007, 0x000F):
        net.rx["controlword"][1] = cw
        net.rx["modes_of_operation"][1] = 8
        net.exchange()
    net.rx["target_position"][1] = -5
    net.exchange()
    _, tx = net.image_bytes(1)
    statusword = int.from_bytes(tx[2:4], "little")
    assert statusword & 0x6F == 0x27
    assert int.from_bytes(tx[4:8], "little", signed=True) == -5
    assert tx[14] == 8  # 6061h modes of operation display (after 603Fh, 6041h, 6064h, 606Ch, 6077h)
    _, tx0 = net.image_bytes(0)
    assert int.from_bytes(tx0[4:8], "little", signed=True) == 0, "slave 0 not enabled: it does not move"


def test_only_mapped_objects_cross_the_wire() -> None:
    """A mapping without 60FFh: the master's target velocity never reaches the drive; one without 606Ch: the master
    reads 0 for the actual velocity while the drive computes it."""
    pdo = SlavePdoConfig(rx_assign=[0x1600], tx_assign=[0x1A00], mappings=[
        PdoMappingConfig(index=0x1600, entries=[PdoEntryConfig(index=0x6040, bit_len=16),
                                                PdoEntryConfig(index=0x607A, bit_len=32)]),
        PdoMappingConfig(index=0x1A00, entries=[PdoEntryConfig(index=0x6041, bit_len=16),
                                                PdoEntryConfig(index=0x6064, bit_len=32)])])
    net = _net(pdo=pdo)
    net.rx["target_velocity"][0] = 1234
    net.rx["target_position"][0] = 77
    net.exchange()
    assert int(net.drive_rx["target_velocity"][0]) == 0 and int(net.drive_rx["target_position"][0]) == 77
    rx, tx = net.image_bytes(0)
    assert len(rx) == 6 and len(tx) == 6
    assert net.mapped_objects(0) == frozenset({0x6040, 0x607A, 0x6041, 0x6064})


def test_startup_sdos_are_written_in_preop() -> None:
    net = _net(startup_sdos=[{"index": 0x6065, "value": 5000, "bit_len": 32},
                             {"index": 0x6060, "value": 9, "bit_len": 8}])
    assert int(net.drive_rx["following_error_window"][0]) == 5000
    assert net.slaves[0].state.name == "Op"
    assert any("6065h:00h ← 5000" in line for line in net.slaves[0].sdo_log)


def test_startup_sdo_abort_stops_that_slave_only() -> None:
    net = _net(startup_sdos=[{"index": 0x2999, "value": 1, "bit_len": 16}])
    assert net.slaves[0].state.name == "PreOp" and "06020000h" in net.slaves[0].error
    assert net.slaves[1].state.name == "Op"
    net2 = _net(startup_sdos=[{"index": 0x2999, "value": 1, "bit_len": 16, "abort_on_error": False}])
    assert net2.slaves[0].state.name == "Op"


def test_compiled_group_transfer_equals_pack_and_unpack() -> None:
    """The compiled transfer of a group (one gather into the image, one scatter into the records) gives the same bytes
    and values as `pack`/`unpack`, for the default mapping and for one with a padding gap."""
    import numpy as np

    from mcstudio.fieldbus.pdo import pack

    gap = SlavePdoConfig(rx_assign=[0x1600], tx_assign=[0x1A00], mappings=[
        PdoMappingConfig(index=0x1600, entries=[PdoEntryConfig(index=0x6040, subindex=0, bit_len=16),
                                                PdoEntryConfig(index=0, subindex=0, bit_len=8),
                                                PdoEntryConfig(index=0x607A, subindex=0, bit_len=32)]),
        PdoMappingConfig(index=0x1A00, entries=[PdoEntryConfig(index=0x6041, subindex=0, bit_len=16),
                                                PdoEntryConfig(index=0, subindex=0, bit_len=16),
                                                PdoEntryConfig(index=0x6064, subindex=0, bit_len=32)]),
    ])
    for net in (_net(), _net(pdo=gap)):
        rng = np.random.default_rng(7)
        net.rx.view(np.uint8)[:] = rng.integers(0, 256, net.rx.nbytes, dtype=np.uint8)
        net.rx["_zero"] = 0
        net.exchange()
        for g in net._groups:
            assert g.rx_copy is not None and g.tx_copy is not None
            assert g.rx_img.tobytes() == pack(g.rx, net.rx, g.slaves).tobytes()
            assert g.tx_img.tobytes() == pack(g.tx, net.drive_tx, g.rows).tobytes()
            for e in g.rx.entries:
                if e.field is not None:
                    assert (net.drive_rx[e.field][g.rows] == net.rx[e.field][g.slaves]).all(), e.field
            for e in g.tx.entries:
                if e.field is not None:
                    assert (net.tx[e.field][g.slaves] == net.drive_tx[e.field][g.rows]).all(), e.field
