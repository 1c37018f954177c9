"""A device on a TCP port: one client at a time, the next accepted when it
leaves, what a client writes handed to the simulator, nothing kept for nobody."""

from __future__ import annotations

import socket

import pytest
from wire_helpers import wait_until

from sim.devices.clocks import StepClock
from sim.devices.line import Line
from sim.devices.port import Port
from sim.devices.transport import TcpTransport


def recv_all(sock: socket.socket, n: int, timeout: float = 5.0) -> bytes:
    sock.settimeout(timeout)
    out = b""
    while len(out) < n:
        data = sock.recv(4096)
        if not data:
            break
        out += data
    return out


def nothing_on(sock: socket.socket, wait_s: float = 0.2) -> bool:
    sock.settimeout(wait_s)
    try:
        return sock.recv(4096) == b""
    except TimeoutError:
        return True


@pytest.fixture
def port():
    p = Port(TcpTransport("127.0.0.1", 0), Line(115200), StepClock())
    yield p
    p.close()


def send_at(port: Port, data: bytes, t: float) -> None:
    """Queue data at sim time t and step the clock past its end."""
    port.write(data, t)
    port.clock.advance(t + 1.0)
    port.wake()


def test_clients_come_and_go(port):
    addr = port.transport.address
    send_at(port, b"before anyone", 0.0)
    wait_until(lambda: port.unheard == 13, what="bytes for nobody counted")

    first = socket.create_connection(addr)
    wait_until(lambda: port.transport.connects == 1, what="the first client accepted")
    second = socket.create_connection(addr)  # waits in the backlog: one client at a time
    send_at(port, b"$GPGGA,one\r\n", 2.0)
    assert recv_all(first, 12) == b"$GPGGA,one\r\n"  # nothing stale from before it came
    assert nothing_on(second)

    first.sendall(b"$CCCMD,1*00\r\n")  # a commanded device reads what the client writes
    wait_until(lambda: port.received == 13, what="the client's bytes read")
    assert port.take_input() == b"$CCCMD,1*00\r\n" and port.take_input() == b""

    first.close()
    wait_until(lambda: port.transport.connects == 2, what="the second client accepted after the first left")
    assert port.transport.disconnects == 1
    send_at(port, b"two\r\n", 4.0)
    assert recv_all(second, 5) == b"two\r\n"
    second.close()

    wait_until(lambda: port.transport.disconnects == 2, what="the second client gone")
    third = socket.create_connection(addr)  # a driver that reconnects gets the stream again
    wait_until(lambda: port.transport.connects == 3, what="a reconnect accepted")
    send_at(port, b"three\r\n", 6.0)
    assert recv_all(third, 7) == b"three\r\n"
    third.close()
    assert port.overflows == 0 and port.lost == 0


def test_the_bytes_keep_the_lines_pace_on_tcp_too(port):
    """115200 baud: 1152 bytes take 0.1 s of sim time; at a step 0.05 s in, half are out."""
    client = socket.create_connection(port.transport.address)
    wait_until(lambda: port.transport.connects == 1, what="the client accepted")
    port.write(bytes(1152), 0.0)
    port.clock.advance(0.05)
    port.wake()
    assert recv_all(client, 576) == bytes(576)
    assert nothing_on(client)
    port.clock.advance(0.1)
    port.wake()
    assert recv_all(client, 576) == bytes(576)
    client.close()


def test_a_commanded_device_reads_and_answers():
    """The emulator interface's other half: receive() gets what the driver wrote at
    the simulator's next step, send() answers on the same line (a stand-in servo
    controller that acknowledges each command)."""
    from sim.devices.clocks import StepClock
    from sim.devices.config import WireConfig
    from sim.devices.device import Devices
    from sim.devices.emulator import DeviceContext, Emulator, NoOptions

    class Servo(Emulator):
        sensor, protocol = "actuators", "stand-in"

        def __init__(self, ctx):
            super().__init__(ctx)
            self.commands = []

        def receive(self, data, t):
            for line in data.split(b"\n")[:-1]:
                self.commands.append((t, line))
                self.send(b"ACK " + line + b"\n", t)

    devices = Devices([], StepClock())
    servo = Servo(DeviceContext("AUV1", "actuators", 1, NoOptions()))
    device = devices.add(servo, WireConfig(protocol="stand-in", tcp="127.0.0.1:0", baud=9600))
    try:
        client = socket.create_connection(device.port.transport.address)
        wait_until(lambda: device.port.transport.connects == 1, what="the driver connected")
        client.sendall(b"RUDDER 0.1\n")
        wait_until(lambda: device.port.received == 11, what="the command read")
        devices.step(1.0)  # handed to the emulator at the step; its answer queued at t = 1.0
        devices.step(1.0078)  # 15 bytes at 9600 baud: 7 complete by 1.0078 s ...
        assert device.port.sent == 7  # ... and written by the step itself, not later by the writer
        devices.step(1.1)
        assert device.port.sent == 15
        assert servo.commands == [(1.0, b"RUDDER 0.1")]
        assert recv_all(client, 15) == b"ACK RUDDER 0.1\n"
        assert device.records[0].t_start == 1.0
        client.close()
    finally:
        devices.close()
