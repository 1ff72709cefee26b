"""The process image is the bytes of the PDO mapping (little-endian, packed, in mapping order)."""

from __future__ import annotations

from mcstudio.fieldbus.network import RX_DTYPE, TX_DTYPE, Network


def test_rx_bytes_equal_hand_computed() -> None:
    net = Network([1], ["Node1"])
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
    rx_bytes, _ = net.image_bytes(0)
    # 6040h UINT | 607Ah DINT | 60FFh DINT | 6071h INT | 6060h SINT | 60B8h UINT | 607Fh UDINT | 60E0h UINT | 60E1h UINT
    assert rx_bytes == bytes([0x0F, 0x00, 0x04, 0x03, 0x02, 0x01, 0xFE, 0xFF, 0xFF, 0xFF, 0x0B, 0x0A, 0x08,
                              0x11, 0x00, 0x00, 0x00, 0x01, 0x00, 0xB8, 0x0B, 0xE8, 0x03])
    assert RX_DTYPE.itemsize == 23 and TX_DTYPE.itemsize == 29


def test_tx_bytes_follow_the_drive() -> None:
    net = Network([1, 2], ["Node1", "Node2"])
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
