"""A QEMU system emulator driven through its GDB stub (the GDB remote serial protocol over a
Unix socket): start it halted, set breakpoints, run to them, read and write registers and
memory. Enough to watch one function's calls in an unchanged program (footprint.cycles_m4)
without a cross gdb, which is not installed beside arm-none-eabi-gcc everywhere.

Only the packets QEMU's stub answers for a Cortex-M are used: ``Z0``/``z0`` (breakpoints),
``c`` (continue), ``s`` (one instruction), ``p``/``P`` (one register, once the target
description has been read), ``m``/``M`` (memory), ``k`` (kill). Acks are on
(the protocol's default): each packet is acknowledged with ``+`` and the stub's ``+`` is read
and dropped."""

import socket
import subprocess
import tempfile
import time
from pathlib import Path

CONNECT_SECONDS = 10.0
REPLY_SECONDS = 60.0                     # a run to the next breakpoint, on a busy machine


class QemuGdbError(Exception):
    """The emulator did not start, closed the connection, or answered an error."""


class QemuGdb:
    """One QEMU run under the stub; use as a context manager (the emulator is ended on exit).
    ``stop()`` returns the stop reply of the run: ``T05...`` at a breakpoint, ``W..`` when the
    program exited (its status in hex)."""

    def __init__(self, command: list[str]):
        self._folder = tempfile.TemporaryDirectory(prefix="swarmvm-qemu-")
        path = str(Path(self._folder.name) / "gdb")
        self._output = tempfile.TemporaryFile("w+")
        self.process = subprocess.Popen([*command, "-S", "-chardev", "socket,id=gdb,path=%s,server=on,wait=off" % path,
                                         "-gdb", "chardev:gdb"], stdin=subprocess.DEVNULL, stdout=self._output,
                                        stderr=self._output)
        self.socket = socket.socket(socket.AF_UNIX, socket.SOCK_STREAM)
        deadline = time.monotonic() + CONNECT_SECONDS
        while True:
            try:
                self.socket.connect(path)
                break
            except OSError:
                if self.process.poll() is not None or time.monotonic() > deadline:
                    raise QemuGdbError("QEMU did not start its GDB stub: %s" % self.output().strip())
                time.sleep(0.05)
        self.socket.settimeout(REPLY_SECONDS)
        self._pending = b""
        # QEMU's stub answers ``p``/``P`` only to a client that has read the target description.
        self.request("qXfer:features:read:target.xml:0,ffb")

    def __enter__(self) -> "QemuGdb":
        return self

    def __exit__(self, *exc_info: object) -> None:
        self.close()

    def output(self) -> str:
        """What QEMU printed (the program's semihosting output included) so far."""
        self._output.flush()
        self._output.seek(0)
        return self._output.read()

    def close(self) -> None:
        self.socket.close()
        if self.process.poll() is None:
            self.process.kill()
        self.process.wait()
        self._output.close()
        self._folder.cleanup()

    def _send(self, packet: str) -> None:
        body = packet.encode()
        try:
            self.socket.sendall(b"$%s#%02x" % (body, sum(body) % 256))
        except OSError:
            raise QemuGdbError("QEMU closed its GDB stub: %s" % self.output().strip())

    def _receive(self) -> str:
        """The next packet's body (its ``+`` ack sent); acks and notifications before it dropped."""
        while True:
            start = self._pending.find(b"$")
            end = self._pending.find(b"#", start + 1) if start >= 0 else -1
            if start >= 0 and end >= 0 and len(self._pending) >= end + 3:
                body, self._pending = self._pending[start + 1:end], self._pending[end + 3:]
                try:
                    self.socket.sendall(b"+")
                except OSError:
                    # After its exit report (W, X) QEMU may be gone before the ack arrives.
                    if not body.startswith((b"W", b"X")):
                        raise QemuGdbError("QEMU closed its GDB stub: %s" % self.output().strip())
                return body.decode()
            try:
                data = self.socket.recv(4096)
            except socket.timeout:
                raise QemuGdbError("no answer from QEMU's GDB stub in %.0f s" % REPLY_SECONDS)
            if not data:
                raise QemuGdbError("QEMU closed its GDB stub: %s" % self.output().strip())
            self._pending += data

    def request(self, packet: str) -> str:
        self._send(packet)
        reply = self._receive()
        if reply.startswith("E") and len(reply) == 3:
            raise QemuGdbError("QEMU's GDB stub refused %r (%s)" % (packet[:20], reply))
        return reply

    def breakpoint(self, address: int, on: bool = True) -> None:
        self.request("%s0,%x,2" % ("Z" if on else "z", address))

    def run(self) -> str:
        """Continue to the next stop; its reply (``T05`` at a breakpoint, ``W`` + status at exit)."""
        return self.request("c")

    def register(self, number: int) -> int:
        return int.from_bytes(bytes.fromhex(self.request("p%x" % number)), "little")

    def set_register(self, number: int, value: int) -> None:
        self.request("P%x=%s" % (number, value.to_bytes(4, "little").hex()))

    def read_word(self, address: int) -> int:
        return int.from_bytes(bytes.fromhex(self.request("m%x,4" % address)), "little")

    def write_word(self, address: int, value: int) -> None:
        self.request("M%x,4:%s" % (address, value.to_bytes(4, "little").hex()))
