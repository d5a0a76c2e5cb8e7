"""The learned policy kept in a store (runtime_c/swarmvm_learn_store.c), on a host: the save
cadence (one save each KEEPER_EVERY credited rewards while the preferences move, none while
nothing is learned), a restart loads exactly what was saved last, and with both slots damaged
the initial parameters stay. The forager of examples/learning, the chosen event `far` rewarded."""

import re
from pathlib import Path

import learnbuild
from swarmvm.compiler.pipeline import compile_inputs

FORAGER = learnbuild.ROOT / "examples" / "learning" / "supervisor.yaml"
EVERY = 50


def test_the_keeper_saves_on_its_cadence_and_restores_the_last_save(tmp_path):
    compiled = compile_inputs([str(FORAGER)])
    good = list(compiled.model.events).index("far")
    image = compiled.image
    Path(tmp_path / "keeper_data.h").write_text(
        "static const uint8_t keeper_image[%d] = {%s};\n#define KEEPER_GOOD %du\n#define KEEPER_EVERY %du\n"
        % (len(image), ", ".join(map(str, image)), good, EVERY))
    exe = learnbuild.build_host(tmp_path / "keeper_probe",
                                [learnbuild.RUNTIME_C / n for n in ("swarmvm.c", "swarmvm_learn.c", "swarmvm_store.c",
                                                                     "swarmvm_learn_store.c")]
                                + [learnbuild.PROBES / "keeper_probe.c"], includes=(tmp_path,))
    text = learnbuild.run_host(exe)
    assert "begin 0\n" in text
    saves = [int(u) for u in re.findall(r"save (\d+)", text)]
    assert len(saves) >= 5 and saves == [EVERY * (k + 1) for k in range(len(saves))]
    assert "quiet 0\n" in text
    assert "restart 1 1\n" in text
    assert "damaged 0 1\n" in text
