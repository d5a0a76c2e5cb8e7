"""`swarmvm gen --target argos`: the generated e-puck controller carries the same image as the
.svm, its generated base class binds every event by name and sends the public ones' messages,
the user's subclass holds one stub per private event and nothing generated, generation is
deterministic, and a user-edited controller is never overwritten but is checked for drift. Building and running it in real ARGoS: the other tests in tests/targets/argos/."""

import re
import subprocess

import pytest
from targets.argos.argos_project import CORPUS, generate

from swarmvm.compiler.naming import callback_stem, message_code, message_name
from swarmvm.compiler.pipeline import compile_inputs

SUPERVISORS = ("energy_worker", "network_worker")


def gen(supervisor, outdir):
    return generate(CORPUS / (supervisor + ".yaml"), outdir).folder


@pytest.fixture(scope="module", params=SUPERVISORS)
def generated(request, tmp_path_factory):
    return request.param, gen(request.param, tmp_path_factory.mktemp("argos_" + request.param))


def test_compiled_in_image_is_the_svm(generated):
    name, out = generated
    text = (out / (name + "_image.hpp")).read_text()
    body = text[text.index("kImage["):]
    data = bytes(int(h, 16) for h in re.findall(r"0x([0-9a-f]{2})", body[:body.index("};")]))
    assert data == (out / (name + ".svm")).read_bytes()


def test_base_binds_every_event_and_the_user_file_holds_the_private_ones(generated):
    name, out = generated
    base = (out / (name + "_base.h")).read_text()
    user = (out / (name + "_controller.h")).read_text() + (out / (name + "_controller.cpp")).read_text()
    assert base.splitlines()[0].endswith("do not edit.")
    model = compile_inputs([str(CORPUS / (name + ".yaml"))]).model
    for index, event in enumerate(model.events):
        const = "EV_" + event
        controllable = model.controllable[index]
        assert '%s("%s"' % ("set_action" if controllable else "set_check", const) in base, const
        method = ("On_" if controllable else "Check_") + callback_stem(event)
        if model.public[index]:
            message = message_name(event, controllable)
            assert '%du /* "%s" */' % (message_code(message), message) in base, const
            assert method + "(" not in user, const       # a generated default, overridable
        else:
            assert "virtual %s %s() = 0;" % ("void" if controllable else "bool", method) in base, const
            assert user.count(method + "(") == 2, const   # declared and defined
    for glue in ("set_check", "set_action", "Send(", "Heard(", "Init(", "ControlStep("):
        assert glue not in user, glue
    camel = "".join(p.capitalize() for p in name.split("_"))
    assert 'REGISTER_CONTROLLER(C%sController, "%s_controller")' % (camel, name) in user
    assert "class C%sController : public C%sBase" % (camel, camel) in user
    argos = (out / (name + ".argos")).read_text()
    assert "<%s_controller " % name in argos and '<SCT path="%s.svm" />' % name in argos
    assert 'include("${CMAKE_CURRENT_SOURCE_DIR}/swarmvm_argos.cmake")' in (out / "CMakeLists.txt").read_text()
    assert "find_package(ARGoS REQUIRED CONFIG" in (out / "swarmvm_argos.cmake").read_text()


def test_generation_is_deterministic(tmp_path):
    first, second = gen("network_worker", tmp_path / "a"), gen("network_worker", tmp_path / "b")
    names = sorted(p.name for p in first.iterdir())
    assert names == sorted(p.name for p in second.iterdir())
    for file_name in names:
        assert (first / file_name).read_bytes() == (second / file_name).read_bytes(), file_name
        assert str(tmp_path) not in (first / file_name).read_bytes().decode("latin-1"), file_name


def test_user_edited_controller_is_kept(tmp_path):
    out = gen("energy_worker", tmp_path)
    controller = out / "energy_worker_controller.cpp"
    edited = controller.read_text().replace("return false;", "return true;  // user code", 1)
    controller.write_text(edited)
    (out / "energy_worker_image.hpp").unlink()
    gen("energy_worker", tmp_path)
    assert controller.read_text() == edited
    assert (out / "energy_worker_image.hpp").exists()


def test_drifted_controller_is_named_and_a_public_override_is_not_stale(tmp_path):
    out = gen("network_worker", tmp_path)
    header = out / "network_worker_controller.h"
    model = compile_inputs([str(CORPUS / "network_worker.yaml")]).model
    public = next(e for i, e in enumerate(model.events) if model.public[i] and model.controllable[i])
    private = re.search(r"bool (Check_\w+)\(\) override;", header.read_text()).group(1)
    # The user overrides a public event's message default and deletes one private check.
    header.write_text(header.read_text().replace("protected:\n", "protected:\n    void On_%s() override;\n" % public, 1)
                      .replace("    bool %s() override;\n" % private, ""))
    result = subprocess.run(["swarmvm", "gen", str(CORPUS / "network_worker.yaml"), "--target", "argos", "-o", str(out)],
                            capture_output=True, text=True)
    assert result.returncode == 0, result.stderr
    warning = [line for line in result.stderr.splitlines() if "network_worker_controller.h" in line]
    assert len(warning) == 1 and "missing" in warning[0] and private in warning[0], result.stderr
    assert "stale" not in warning[0] and (out / "network_worker_controller.h.new").is_file()
