"""No module opens a file except through the input and output layers (issue 37, point 7).

Every module of generator/, runtime_py/ and studies/ is read as a syntax tree and every call
that opens, reads or writes a file by name (the list: tests/layers/file_access.py) must be in
ALLOWED, each entry justified: the layers themselves, swarmvm's own package files, and the
scratch files swarmvm makes for a child process in a folder only it uses. Any other read goes
through ``swarmvm.boundary.errors.open_input`` / ``read_input`` (the runtime: its mirror
``swarmvm_format.read_file``), any other write through ``swarmvm.boundary.output.write_outputs``
(the runtime: ``swarmvm_format.write_file``). Files drawn in memory (``io.BytesIO``) are
not accesses. The synthetic modules below show the walk finds each kind of access."""

from pathlib import Path

import pytest

from layers.file_access import accesses, tree_accesses

ROOT = Path(__file__).resolve().parents[2]
FOLDERS = ("generator", "runtime_py", "studies")

# (module, function): the calls it may make, and why it need not go through a layer.
ALLOWED: dict[tuple[str, str], tuple[set[str], str]] = {
    # The layers themselves: the one place each direction opens files.
    ("generator/boundary/errors.py", "open_input"): (
        {"os.open", "os.fdopen"}, "the input layer: opens without waiting, regular files only, bounded"),
    ("generator/boundary/output.py", "FileOps.open"): (
        {"tempfile.mkstemp"}, "the output layer stages each file in a new temporary file beside its destination"),
    ("generator/boundary/output.py", "umask"): (
        {"open"}, "the output layer reads the process's umask from /proc/self/status (the kernel's, not input)"),
    ("generator/boundary/terminal.py", "stream_failed"): (
        {"os.open"}, "points a failed standard output at /dev/null so that exit's flush cannot fail again"),
    ("runtime_py/swarmvm_format.py", "read_file"): (
        {"os.open"}, "the Python runtime's input layer (a robot carries no compiler)"),
    ("runtime_py/swarmvm_format.py", "write_file"): (
        {"tempfile.mkstemp"}, "the Python runtime's writer: a temporary file beside the destination, renamed in"),
    # swarmvm's own package files (importlib.resources: possibly inside a wheel, not a path the
    # layer could open; trusted, docs/security.md).
    ("generator/compiler/render.py", "_template_source"): ({"resource.read_text"}, "a template of the package"),
    ("generator/inspector/page.py", "asset"): ({"TEMPLATES.joinpath('inspect', name).read_text"},
                                               "the inspector page's script and style, package files"),
    ("generator/targets/__init__.py", "generate"): ({"source.read_bytes"}, "a runtime file copied into a target"),
    ("generator/targets/capbot.py", "values"): ({"QEMU.joinpath('m4.flags').read_text"},
                                                "the bare-metal CapBot build's compiler flags, a package file"),
    ("generator/footprint/measure.py", "runtime_names"): ({"source.read_text"}, "the C runtime's own sources"),
    ("generator/footprint/measure.py", "source_sizes"): ({"(folder / n).read_bytes"}, "the runtimes' own sources"),
    ("generator/footprint/kilobot_board/__init__.py", "board_path"): (
        {"SOURCE.read_bytes", "copy.write_bytes"}, "the package's Kilobot board model, copied into swarmvm's cache"),
    # Scratch files in a temporary folder swarmvm made and alone uses, for a child process.
    ("generator/footprint/kilobot_board/__init__.py", "run"): (
        {"schedule.write_text", "(Path(work) / 'script').write_text", "(Path(work) / 'eeprom.in').write_bytes",
         "(Path(work) / 'eeprom.out').read_bytes"}, "simavr's inputs and outputs in the run's temporary folder"),
    ("generator/footprint/qemu_gdb.py", "QemuGdb.__init__"): (
        {"tempfile.TemporaryFile"}, "QEMU's output, in an unnamed temporary file only this process holds"),
    ("studies/energy_replenishment/trial.py", "run"): (
        {"config.write_text", "(Path(folder) / 'err.txt').read_text", "result.read_text", "log.read_text"},
        "ARGoS's experiment file, log and results in the trial's temporary folder"),
    # The energy study's plugin build cache (XDG cache): the package's sources copied, built and
    # logged in a folder swarmvm owns; nothing there is the user's input or output.
    ("studies/energy_replenishment/plugin.py", "_generate"): ({"shutil.copy"}, "the study's sources into the cache"),
    ("studies/energy_replenishment/plugin.py", "_key"): ({"path.read_bytes"}, "hashing the copied sources"),
    ("studies/energy_replenishment/plugin.py", "run_logged"): ({"open"}, "the cache's build log"),
    ("studies/energy_replenishment/plugin.py", "build"): (
        {"open", "log.write_text", "log.read_text"}, "the cache's lock file and build log"),
}


def test_every_file_access_goes_through_a_layer_or_is_allowed_with_a_reason():
    found = tree_accesses(ROOT, FOLDERS)
    outside = ["%s:%d: %s() in %s" % (a.module, a.line, a.call, a.function) for a in found
               if a.call not in ALLOWED.get((a.module, a.function), (set(), ""))[0]]
    assert not outside, "files opened outside the input and output layers:\n" + "\n".join(outside)


def test_every_allowed_entry_is_still_used():
    """A stale entry would let a later access through unseen."""
    used = {(a.module, a.function, a.call) for a in tree_accesses(ROOT, FOLDERS)}
    stale = [(module, function, call) for (module, function), (calls, _) in ALLOWED.items() for call in calls
             if (module, function, call) not in used]
    assert not stale


SYNTHETIC = '''
import io, json, shutil, tomllib
from pathlib import Path

def reads(path):
    with open(path) as handle:
        return handle.read()

def reads_path(path):
    return Path(path).read_text()

def writes(path, text):
    Path(path).write_bytes(text)

def opens_path(path):
    with Path(path).open("rb") as handle:
        return handle.read()

def loads(path):
    with Path(path).open("rb") as handle:
        return tomllib.load(handle), json.load(handle)

def plots(figure, path):
    figure.savefig(path)

def copies(a, b):
    shutil.copyfile(a, b)

def table(frame, path):
    frame.to_parquet(path)

def in_memory(figure, frame):
    png = io.BytesIO()
    figure.savefig(png)
    text = frame.to_csv()
    return png.getvalue(), text, frame.to_parquet(io.BytesIO())
'''


def test_the_walk_finds_each_kind_of_access_in_a_synthetic_module():
    found = {(a.function, a.call) for a in accesses(SYNTHETIC, "synthetic.py")}
    assert found == {("reads", "open"), ("reads_path", "Path(path).read_text"), ("writes", "Path(path).write_bytes"),
                     ("opens_path", "Path(path).open"), ("loads", "Path(path).open"), ("loads", "tomllib.load"),
                     ("loads", "json.load"), ("plots", "figure.savefig"), ("copies", "shutil.copyfile"),
                     ("table", "frame.to_parquet")}


@pytest.mark.parametrize("line", ["open('x')", "Path('x').write_text('y')", "figure.savefig('x.png')",
                                  "shutil.copy('a', 'b')", "os.open('x', 0)", "json.dump({}, open('x', 'w'))"])
def test_one_unlisted_access_fails_the_check(line):
    """One access planted in a module of the tree, outside the allowed list, is reported."""
    planted = "def planted(figure):\n    %s\n" % line
    found = [a for a in accesses(planted, "generator/planted.py")
             if a.call not in ALLOWED.get((a.module, a.function), (set(), ""))[0]]
    assert found and found[0].module == "generator/planted.py"


# The C++ runtime's headers: a file is opened only by swarmvm::read_regular_file. A line that
# opens one elsewhere is listed here with why; LEFT holds what is not yet through the layer.
CPP_OPENING = ("std::ifstream", "std::ofstream", "std::fstream", "fopen(", "::open(")
CPP_ALLOWED = {
    ("swarmvm_image.hpp", "const int fd = ::open(path.c_str(), O_RDONLY | O_NONBLOCK | O_CLOEXEC);"):
        "read_regular_file itself",
    ("swarmvm_image.hpp", "std::ifstream in(path, std::ios::binary);"):
        "read_regular_file's bounded read where POSIX is missing (no FIFOs or devices by path there)",
}
CPP_LEFT: dict[tuple[str, str], str] = {}


def test_the_cpp_runtime_opens_files_only_through_its_layer():
    found = set()
    for header in sorted((ROOT / "runtime_cpp").glob("*.h*")):
        for line in header.read_text(encoding="utf-8").splitlines():
            code = line.split("//")[0].strip()
            if any(opening in code for opening in CPP_OPENING):
                found.add((header.name, code))
    assert found - set(CPP_ALLOWED) - set(CPP_LEFT) == set()
    assert set(CPP_ALLOWED) <= found
