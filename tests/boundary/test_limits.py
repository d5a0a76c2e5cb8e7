"""The limits of docs/limits.md that no other test covers: one more than each is one line and
exit status 2, nothing written; at the limit it works."""

from click.testing import CliRunner

from checkout import EXAMPLE
from swarmvm.cli.commands import main


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


def consecutive(first, last):
    """A .gen automaton whose states are one <Consecutive> range, one self-loop on the first."""
    return ('<Generator>\n"range"\n<Alphabet>\na\n</Alphabet>\n<States>\n<Consecutive> %d %d </Consecutive>\n'
            "</States>\n<TransRel>\n%d a %d\n</TransRel>\n<InitStates>\n%d\n</InitStates>\n<MarkedStates>\n%d\n"
            "</MarkedStates>\n</Generator>\n" % (first, last, first, first, first, first))


def test_a_consecutive_range_over_65536_states_is_refused_at_once(tmp_path):
    """A range of 65,536 states is read (the one reachable state is kept; the warning names the
    first 20 dropped); one more is refused for the range, as is a range of a billion states,
    before anything is expanded."""
    (tmp_path / "at.gen").write_text(consecutive(1, 65536))
    status, output = check(tmp_path / "at.gen")
    assert status == 0 and "| %s | 1 | 1 | 65536 | 1 |" % (tmp_path / "at.gen") in output
    warning = output.splitlines()[0]
    assert warning.endswith("65535 unreachable state(s) dropped (states %s, ...)" % ", ".join(map(str, range(1, 21))))
    for last in (65537, 999999999):
        (tmp_path / "over.gen").write_text(consecutive(1, last))
        status, output = check(tmp_path / "over.gen")
        assert status == 2 and output == "swarmvm: error: %s: States: line 7: <Consecutive> 1 %d: over 65536 states\n" % (
            tmp_path / "over.gen", last)


def xml_with_events(count):
    """An IDES-style .xml automaton with ``count`` self-loop events on its one state."""
    events = "".join('<event id="%d" name="e%d" controllable="False" observable="True"/>\n' % (i, i)
                     for i in range(count))
    loops = "".join('<transition source="0" target="0" event="%d"/>\n' % i for i in range(count))
    return ('<?xml version="1.0" encoding="UTF-8"?>\n<model version="0.0" type="FSA" id="many">\n<data>\n'
            '<state id="0" name="1" initial="True" marked="True"/>\n%s%s</data>\n</model>\n' % (events, loops))


def test_255_events_load_and_256_do_not_in_every_format(tmp_path):
    from boundary.test_hostile_inputs import gen_with_events
    for suffix, write in ((".gen", gen_with_events), (".xml", xml_with_events)):
        (tmp_path / ("at" + suffix)).write_text(write(255))
        status, output = check(tmp_path / ("at" + suffix))
        assert status == 0 and "| %s | 255 | 1 |" % (tmp_path / ("at" + suffix)) in output, output
        (tmp_path / ("over" + suffix)).write_text(write(256))
        status, output = check(tmp_path / ("over" + suffix))
        assert status == 2 and output.count("\n") == 1 and "256 events, over the image format's limit of 255" in output


def test_a_file_of_exactly_the_size_limit_is_read(tmp_path):
    from swarmvm.boundary.errors import MAX_BYTES
    text = EXAMPLE.read_text()
    padded = tmp_path / "padded.yaml"
    padded.write_text(text + "#" * (MAX_BYTES - len(text.encode()) - 1) + "\n")
    assert padded.stat().st_size == MAX_BYTES and check(padded)[0] == 0


def test_a_name_of_255_characters_loads_and_256_does_not(tmp_path):
    text = EXAMPLE.read_text()
    for length, status in ((255, 0), (256, 2)):
        path = tmp_path / ("name_%d.yaml" % length)
        path.write_text(text.replace("EV_moveToCharge", "EV_" + "n" * length))
        result, output = check(path)
        assert result == status and output.count("swarmvm: error") == (status == 2), output
        assert status == 0 or "is not an event name (at most 255" in output
