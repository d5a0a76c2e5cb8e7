"""swarmvm on the Pi-puck: robot adapters (the real robot and a simulation) and the
fixed-rate control loop. Copied as it is into every generated Pi-puck target.

The controller talks to the robot only through a few methods, so it runs unchanged on the
Pi-puck and on a laptop (``--sim``): ``begin_step``, ``event_occurred``, ``received``,
``set_motors``, ``set_leds``, ``broadcast``, ``stop``.
"""

import json
import socket
from typing import TYPE_CHECKING, Callable, Iterable, Optional, Protocol, Set

if TYPE_CHECKING:   # mypy reads the runtime as the package's modules; a robot imports the copies beside this one
    from runtime_py import swarmvm_app
    from runtime_py.swarmvm_format import MAX_NAME_LENGTH
    from runtime_py.swarmvm_vm import VM
else:
    import swarmvm_app
    from swarmvm_format import MAX_NAME_LENGTH

# Public events travel as UDP broadcasts of the message name on the robots' Wi-Fi network.
MESSAGE_PORT = 47474
# The longest broadcast: a name of MAX_NAME_LENGTH characters (letters, digits and '_': nothing
# for JSON to escape). A longer datagram is not a robot's; read to this length, it fails to parse.
MAX_DATAGRAM = len(json.dumps({"message": "x" * MAX_NAME_LENGTH}).encode("utf-8"))


class Robot(Protocol):
    """The few methods a controller talks to the robot through: :class:`PiPuckRobot` and
    :class:`SimRobot` both have them."""

    def begin_step(self, number: int) -> None: ...
    def event_occurred(self, event: str) -> bool: ...
    def received(self, message: str) -> bool: ...
    def set_motors(self, left: float, right: float) -> None: ...
    def set_leds(self, colour: str) -> None: ...
    def broadcast(self, message: str) -> None: ...
    def stop(self) -> None: ...


def message_in(datagram: bytes) -> Optional[str]:
    """The message name a datagram carries, or None for one that is not a robot's broadcast
    (another program on the port, a damaged or cut datagram): what the network brings must not
    stop the control loop."""
    try:
        message = json.loads(datagram.decode("utf-8")).get("message")
    except (UnicodeDecodeError, ValueError, AttributeError):     # JSONDecodeError is a ValueError
        return None
    return message if isinstance(message, str) else None


class PiPuckRobot:
    """The Pi-puck through the ``pipuck`` library (PyPI), imported on first use.

    The library opens I2C and GPIO (``smbus``, ``RPi.GPIO``) when it is imported, which fails
    anywhere but on the robot: importing it here, not at module level, keeps the controller
    importable (and testable) on any machine."""

    def __init__(self, epuck_version: int = 2) -> None:
        try:
            from pipuck.pipuck import PiPuck
        except ImportError as exc:
            raise SystemExit("the pipuck library is not available (%s): run on the Pi-puck, "
                             "or use --sim on other machines" % exc)
        self._pipuck = PiPuck(epuck_version=epuck_version)
        self._socket = socket.socket(socket.AF_INET, socket.SOCK_DGRAM)
        self._socket.setsockopt(socket.SOL_SOCKET, socket.SO_BROADCAST, 1)
        self._socket.setsockopt(socket.SOL_SOCKET, socket.SO_REUSEADDR, 1)
        self._socket.bind(("", MESSAGE_PORT))
        self._socket.setblocking(False)
        self._heard: Set[str] = set()

    def begin_step(self, number: int) -> None:
        """Collect the messages that arrived since the previous step (message_in)."""
        self._heard = set()
        while True:
            try:
                data, _sender = self._socket.recvfrom(MAX_DATAGRAM)
            except BlockingIOError:
                return
            message = message_in(data)
            if message is not None:
                self._heard.add(message)

    def event_occurred(self, event: str) -> bool:
        """Placeholder for a sensor reading: the controller's checks replace it."""
        return False

    def received(self, message: str) -> bool:
        return message in self._heard

    def set_motors(self, left: float, right: float) -> None:
        """Wheel speeds in e-puck steps/s (-1000..1000)."""
        self._pipuck.epuck.set_motor_speeds(int(left), int(right))

    def set_leds(self, colour: str) -> None:
        """All three Pi-puck RGB LEDs: off, red, green, yellow, blue, magenta, cyan or white."""
        self._pipuck.set_leds_colour(colour)

    def broadcast(self, message: str) -> None:
        payload = json.dumps({"message": message}).encode("utf-8")
        self._socket.sendto(payload, ("<broadcast>", MESSAGE_PORT))

    def stop(self) -> None:
        self.set_motors(0, 0)
        self.set_leds("off")


class SimRobot:
    """A simulated Pi-puck for tests and laptops.

    Motor, LED and message commands are printed as ``sim ...`` lines. Uncontrollable events
    (and received messages, ``EV__x``) come from an event script (docs/conformance.md): row
    ``n`` lists the events whose checks return true at step ``n``; without a script they never
    occur."""

    def __init__(self, rows: Iterable[swarmvm_app.Row] = (), log: Callable[[str], None] = print) -> None:
        self._script = swarmvm_app.ScriptedEvents(rows)
        self._log = log

    def begin_step(self, number: int) -> None:
        self._script.begin_step(number)

    def event_occurred(self, event: str) -> bool:
        return self._script.occurred(event)

    def received(self, message: str) -> bool:
        return self._script.occurred("EV__" + message)

    def set_motors(self, left: float, right: float) -> None:
        self._log("sim motors %d %d" % (left, right))

    def set_leds(self, colour: str) -> None:
        self._log("sim leds %s" % colour)

    def broadcast(self, message: str) -> None:
        self._log("sim broadcast %s" % message)

    def stop(self) -> None:
        self.set_motors(0, 0)
        self.set_leds("off")


def run(vm: "VM", robot: Robot, period: float = 0.1, steps: Optional[int] = None, trace: bool = False) -> None:
    """Step the VM at a fixed rate (swarmvm_app.run), the robot's ``begin_step`` before each
    step; the robot is stopped when the loop ends, however it ends."""
    try:
        swarmvm_app.run(vm, period=period, steps=steps, trace=trace, begin_step=robot.begin_step)
    finally:
        robot.stop()
