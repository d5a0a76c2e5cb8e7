"""`swarmvm gen --target argos`: the generated e-puck controller carries the same image as the
.svm, has one stub per event, is generated deterministically, and a user-edited controller is
never overwritten. Building and running it in real ARGoS: the other tests in tests/argos/."""

import re

import pytest
from argos_project import CORPUS, generate

from swarmvm.naming import message_code, message_name
from swarmvm.pipeline import compile_inputs

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


def test_one_stub_per_event_and_messages_by_name(generated):
    name, out = generated
    source = (out / (name + "_controller.cpp")).read_text()
    model = compile_inputs([str(CORPUS / (name + ".yaml"))]).model
    for index, event in enumerate(model.events):
        const = "EV_" + event
        kind = "set_action" if model.controllable[index] else "set_check"
        assert '%s("%s"' % (kind, const) in source, const
        if model.public[index]:
            message = message_name(event, model.controllable[index])
            assert '%du /* "%s" */' % (message_code(message), message) in source, const
    assert "SetLinearVelocity" in source
    assert 'GetNode(t_node, "SCT"), "path"' in source
    assert 'REGISTER_CONTROLLER(C%sController, "%s_controller")' % (
        "".join(p.capitalize() for p in name.split("_")), name) in source
    argos = (out / (name + ".argos")).read_text()
    assert "<%s_controller " % name in argos and '<SCT path="%s.svm" />' % name in argos
    assert "find_package(ARGoS REQUIRED CONFIG" in (out / "CMakeLists.txt").read_text()


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
