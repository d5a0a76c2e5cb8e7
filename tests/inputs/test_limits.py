"""The limits of docs/limits.md that no other test covers: one more than each is one line and
exit status 2, nothing written; at the limit it works."""

from click.testing import CliRunner

from checkout import EXAMPLE
from swarmvm.cli import main


def supervisors(count):
    """A set of ``count`` one-state supervisors over one controllable event."""
    return ("num_events: 1\nnum_supervisors: %d\nevents: [ EV_go ]\nev_controllable: [ 1 ]\nev_shared: [ 0 ]\n"
            "sup_events: [ %s ]\nsup_init_state: [ %s ]\nsup_current_state: [ %s ]\nsup_data_pos: [ %s ]\n"
            "sup_data: [ %s ]\n" % (count, ",".join(["[ 1 ]"] * count), ",".join(["0"] * count),
                                    ",".join(["0"] * count), ",".join(str(4 * s) for s in range(count)),
                                    ",".join(["1,EV_go,0,0"] * count)))


def chain(states):
    """A libFAUDES .gen automaton: one event moving round a ring of ``states`` states."""
    names = "\n".join("s%d" % i for i in range(states))
    moves = "\n".join("s%d a s%d" % (i, (i + 1) % states) for i in range(states))
    return ('<Generator>\n"ring"\n<Alphabet>\na\n</Alphabet>\n<States>\n%s\n</States>\n<TransRel>\n%s\n</TransRel>\n'
            "<InitStates>\ns0\n</InitStates>\n<MarkedStates>\ns0\n</MarkedStates>\n</Generator>\n" % (names, moves))


def check(path):
    result = CliRunner().invoke(main, ["check", str(path)])
    return result.exit_code, result.output


def test_255_supervisors_load_and_256_do_not(tmp_path):
    (tmp_path / "many.yaml").write_text(supervisors(255))
    assert check(tmp_path / "many.yaml")[0] == 0
    (tmp_path / "too_many.yaml").write_text(supervisors(256))
    status, output = check(tmp_path / "too_many.yaml")
    assert status == 2 and output == "swarmvm: error: %s: num_supervisors: value 256 out of range (must be in 1..255)\n" % (
        tmp_path / "too_many.yaml")


def test_an_image_over_65535_bytes_is_refused(tmp_path):
    (tmp_path / "ring.gen").write_text(chain(20000))
    status, output = check(tmp_path / "ring.gen")
    assert status == 2 and output.count("\n") == 1
    assert "table image would be 100029 bytes, over the format's limit of 65535" in output


def test_script_steps_over_ten_million_are_refused():
    result = CliRunner().invoke(main, ["script", str(EXAMPLE), "--steps", "10000001"])
    assert result.exit_code == 2 and "10000001 is not in the range 1<=x<=10000000" in result.output
