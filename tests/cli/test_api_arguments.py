"""Every public function of swarmvm.api refuses wrong arguments with its documented exception
(docs/api.md, "Errors"): TypeError for a wrong type, InputError (one line, naming the parameter
or the file) for a value it cannot use. Before, ``compile_model([])`` raised IndexError and
``compile_model("x.yaml")`` read the files "x", ".", "y"..., nan passed as a density."""

import inspect
import math
from pathlib import Path

import pytest

from swarmvm import api
from swarmvm.footprint.measure import FootprintError

ROOT = Path(__file__).parents[2]
EXAMPLE = str(ROOT / "examples" / "energy_worker" / "supervisor.yaml")
MISSING = "/nonexistent/swarmvm/missing.yaml"
COMPILED = api.compile_model([EXAMPLE])


def file_list(param, missing=api.InputError):
    """The wrong arguments of a parameter that takes a list of file names."""
    return [(param, [], api.InputError, param), (param, EXAMPLE, TypeError, param),
            (param, (Path(EXAMPLE),), TypeError, param + "[0]"), (param, [EXAMPLE, 3], TypeError, param + "[1]"),
            (param, [MISSING], missing, MISSING), (param, ["in\0put.yaml"], api.InputError, param + "[0]")]


def one_file(param):
    """The wrong arguments of a parameter that takes one file name."""
    return [(param, Path(EXAMPLE), TypeError, param), (param, None, TypeError, param),
            (param, "", api.InputError, param), (param, "out\0put", api.InputError, param)]


def script_options():
    return [("steps", 0, api.InputError, "steps"), ("steps", -1, api.InputError, "steps"),
            ("steps", 2.5, TypeError, "steps"), ("steps", True, TypeError, "steps"),
            ("seed", -1, api.InputError, "seed"), ("seed", 2 ** 32, api.InputError, "seed"),
            ("density", math.nan, api.InputError, "density"), ("density", math.inf, api.InputError, "density"),
            ("density", 1.5, api.InputError, "density"), ("density", "0.5", TypeError, "density")]


MAX_STATES = [("max_states", 0, api.InputError, "max_states"), ("max_states", "many", TypeError, "max_states")]
SCRIPT = dict(inputs=[EXAMPLE], steps=5, seed=1, density=0.25)

# function name -> (arguments it accepts, [(parameter, wrong value, exception, text its message holds)])
TABLE = {
    "load": (dict(paths=[EXAMPLE]), file_list("paths")),
    "compile_model": (dict(inputs=[EXAMPLE]), file_list("inputs") + [
        ("name", 3, TypeError, "name"), ("names", "yes", TypeError, "names")]),
    "check": (dict(paths=[EXAMPLE]), file_list("paths") + [
        ("target", "z80", api.InputError, "target"), ("name", b"x", TypeError, "name")]),
    "read_image": (dict(path=EXAMPLE), one_file("path") + [("path", MISSING, api.InputError, MISSING)]),
    "parse_image": (dict(data=b""), [
        ("data", "text", TypeError, "data"), ("data", b"junk", api.InputError, "image"),
        ("source", 1, TypeError, "source")]),
    "write_image": (dict(inputs=[EXAMPLE], output="out.svm"), file_list("inputs") + one_file("output") + [
        ("names", 1, TypeError, "names")]),
    "learned_pairs": (dict(compiled=COMPILED, target="python", specs=[]), [
        ("compiled", EXAMPLE, TypeError, "compiled"), ("target", "z80", api.InputError, "target"),
        ("specs", "atWork/notAtWork", TypeError, "specs"), ("specs", ["nope/none"], api.InputError, "nope")]),
    "generate_target": (dict(inputs=[EXAMPLE], target="python", outdir="out"), file_list("inputs") + one_file("outdir") + [
        ("target", "z80", api.InputError, "target"), ("target", None, TypeError, "target"),
        ("name", 1, TypeError, "name"), ("learned", "a/b", TypeError, "learned")]),
    "script_lines": (SCRIPT, file_list("inputs") + script_options()),
    "make_script": (SCRIPT, file_list("inputs") + script_options()),
    "trace": (dict(inputs=[EXAMPLE], script_path="s.txt"), file_list("inputs") + one_file("script_path") + [
        ("script_path", MISSING, api.InputError, MISSING), ("seed", -1, api.InputError, "seed"),
        ("input_mode", "both", api.InputError, "input_mode"), ("control", "never", api.InputError, "control"),
        ("policy", "best", api.InputError, "policy"), ("policy", "learned", api.InputError, "policy"),
        ("policy", 0, TypeError, "policy")]),
    "measure_footprint": (dict(elfs=["x.elf"]), file_list("elfs", missing=FootprintError) + [
        ("indirect", "svm_step=f", TypeError, "indirect"), ("indirect", ["svm_step"], api.InputError, "indirect[0]")]),
    "footprint_report": (dict(elfs=["x.elf"]), file_list("elfs", missing=FootprintError) + [
        ("budget", "", api.InputError, "budget"), ("budget", Path("b.toml"), TypeError, "budget"),
        ("budget", MISSING, api.InputError, MISSING), ("baseline", "in\0put.json", api.InputError, "baseline"),
        ("baseline", MISSING, api.InputError, MISSING), ("fail_on_growth", -1, api.InputError, "fail_on_growth"),
        ("fail_on_growth", math.nan, api.InputError, "fail_on_growth"), ("fail_on_growth", "5", TypeError, "fail_on_growth"),
        ("fail_on_growth", 5.0, api.InputError, "fail_on_growth: growth is measured against a baseline"),
        ("limits", {"vm": 1}, TypeError, "limits"), ("indirect", [3], TypeError, "indirect[0]"),
        ("indirect", ["=f"], api.InputError, "indirect[0]")]),
    "check_properties": (dict(paths=[EXAMPLE]), file_list("paths") + MAX_STATES + [
        ("all_findings", "yes", TypeError, "all_findings")]),
    "equivalent": (dict(a=EXAMPLE, b=EXAMPLE), one_file("a") + one_file("b") + MAX_STATES + [
        ("b", MISSING, api.InputError, MISSING)]),
    "write_export": (dict(model=COMPILED.model, name="m", fmt="yaml", output="out.yaml"), one_file("output") + MAX_STATES + [
        ("model", COMPILED, TypeError, "model"), ("name", None, TypeError, "name"),
        ("fmt", "pdf", api.InputError, "fmt"), ("product_limit", -1, api.InputError, "product_limit")]),
    "export": (dict(inputs=[EXAMPLE], fmt="yaml", output="out.yaml"), file_list("inputs") + one_file("output") + [
        ("fmt", "pdf", api.InputError, "fmt"), ("fmt", None, TypeError, "fmt"),
        ("product_limit", math.nan, TypeError, "product_limit"), ("product_limit", -1, api.InputError, "product_limit")]),
    "synthesise_models": (dict(models=[EXAMPLE], script_path=None, statements=["S = SupC(G, K)"], exports=[],
                               minimise=False, fmt="yaml", output="out.yaml"),
                          file_list("models") + one_file("output") + MAX_STATES + [
        ("script_path", MISSING, api.InputError, MISSING), ("script_path", "", api.InputError, "script_path"),
        ("statements", "S = SupC(G, K)", TypeError, "statements"), ("exports", [1], TypeError, "exports[0]"),
        ("minimise", "no", TypeError, "minimise"), ("fmt", "dot", api.InputError, "fmt")]),
    "inspect": (dict(supervisor=EXAMPLE, traces=[], output="out.html"), one_file("supervisor") + one_file("output") + [
        ("supervisor", MISSING, api.InputError, MISSING), ("traces", "r.trace", TypeError, "traces"),
        ("traces", [MISSING], api.InputError, MISSING), ("traces", ["r\0.trace"], api.InputError, "traces[0]"),
        ("traces", [Path("r.trace")], TypeError, "traces[0]"), ("name", 1, TypeError, "name"),
        ("compare", "yes", TypeError, "compare"), ("compare", True, api.InputError, "compare"),
        ("first_step", 0, api.InputError, "first_step"), ("first_step", 1.5, TypeError, "first_step")]),
    "compat_switch": (dict(project=str(ROOT / "examples")), one_file("project") + [
        ("variant", "energy", api.InputError, "variant"), ("variant", 1, TypeError, "variant")]),
}

CASES = [(name, param, value, error, text) for name, (_good, bad) in TABLE.items() for param, value, error, text in bad]


def test_every_public_function_has_a_row():
    """A function added to the API without its row here fails this test."""
    public = {name for name in api.__all__ if inspect.isfunction(getattr(api, name))}
    assert public == set(TABLE)


@pytest.mark.parametrize("name,param,value,error,text", CASES,
                         ids=["%s-%s-%r" % (c[0], c[1], c[2])[:70] for c in CASES])
def test_a_wrong_argument_raises_the_documented_exception(name, param, value, error, text, tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)                       # nothing may be written, but never into the tree
    good, _bad = TABLE[name]
    with pytest.raises(error) as raised:
        getattr(api, name)(**{**good, param: value})     # the checks run at the call, iterators' included
    message = str(raised.value)
    assert text in message and "\n" not in message
    assert list(tmp_path.iterdir()) == []
