"""The first `sim energy` builds the study's ARGoS plugin (about 10 s): the wait says what it is,
names the log that keeps the build's output, and reports make's per cent (issue 27, point 1)."""

import sys

import pytest

from swarmvm.studies.energy_replenishment import plugin

# A stand-in for a slow make: its progress lines, a compiler line between each, a pause in each.
SLOW_MAKE = """import sys, time
for p in (3, 9, 14, 30, 31, 52, 77, 80, 100):
    print("[%3d%%] Building CXX object part%d.o" % (p, p)); print("g++ -c part%d.cpp" % p)
    sys.stdout.flush(); time.sleep(0.05)
sys.exit(int(sys.argv[1]))
"""


@pytest.mark.parametrize("status", [0, 1])
def test_run_logged_reports_every_25_points_and_keeps_the_output(tmp_path, capsys, status):
    log = tmp_path / "build.log"
    assert plugin.run_logged([sys.executable, "-c", SLOW_MAKE, str(status)], log, "compiling") is (status == 0)
    assert capsys.readouterr().err.splitlines() == [
        "swarmvm: note: compiling: %d%%" % p for p in (3, 30, 77, 100)]
    assert log.read_text().count("g++ -c part") == 9


@pytest.mark.slow
@pytest.mark.emulator
def test_the_first_build_says_so_and_the_second_is_silent(tmp_path, capsys):
    try:
        plugin.find_argos()
    except plugin.BuildError as exc:
        pytest.skip(str(exc))
    plugin.build(cache=tmp_path)
    said = capsys.readouterr().err.splitlines()
    assert said[0] == ("swarmvm: note: building the energy study's ARGoS plugin, once for these sources "
                       "(about 10 s); full output: %s" % (tmp_path / "build.log"))
    assert said[-1] == "swarmvm: note: compiling the plugin: 100%"
    assert "Linking CXX shared" in (tmp_path / "build.log").read_text()
    plugin.build(cache=tmp_path)
    assert capsys.readouterr().err == ""
