"""QEMU's GDB stub closes its end when the program exits, sometimes before the client's ack of
the exit report reaches it: that is the end of a run, not a failure to read the ELF (it was
reported as `cannot read file (Broken pipe)` under load). Any other packet whose ack fails is a
stub that went away, said as such."""

import socket

import pytest

from swarmvm.footprint.qemu_gdb import QemuGdb, QemuGdbError


class _Output:
    def flush(self):
        pass

    def seek(self, _):
        pass

    def read(self):
        return "qemu said goodbye"


def stub_gone_after(packet: bytes) -> QemuGdb:
    """A client holding ``packet`` unread, whose peer has closed its end."""
    ours, theirs = socket.socketpair()
    theirs.close()
    client = object.__new__(QemuGdb)
    client.socket, client._pending, client._output = ours, packet, _Output()
    return client


@pytest.mark.parametrize("report", [b"W00", b"W2a", b"X0b"])
def test_an_exit_report_is_read_though_its_ack_cannot_be_sent(report):
    body = report + b"#%02x" % (sum(report) % 256)
    assert stub_gone_after(b"$" + body)._receive() == report.decode()


def test_another_packet_whose_ack_fails_says_the_stub_closed():
    with pytest.raises(QemuGdbError, match="QEMU closed its GDB stub: qemu said goodbye"):
        stub_gone_after(b"$T05#b9")._receive()


def test_a_request_to_a_closed_stub_says_so():
    with pytest.raises(QemuGdbError, match="QEMU closed its GDB stub"):
        stub_gone_after(b"").request("c")
