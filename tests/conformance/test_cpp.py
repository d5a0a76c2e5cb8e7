"""C++ VM conformance: every run of every batch prints the Python reference trace byte for byte.

One harness (runtime_cpp/conformance_harness.cpp) is compiled per compiler, with every corpus
image compiled in; each batch is then run twice, with the image compiled in and with the same
image loaded from a .svm file at run time (docs/conformance.md, points 2 and 3)."""

import subprocess

import pytest

from conformance.cases import batches, reference
from conformance.cpp_harness import FLAGS, c_array, runs_text
from swarmvm.compiler.runtime_files import RUNTIME_CPP, python_vm

COMPILERS = ("g++", "clang++")
BATCHES = batches()


@pytest.fixture(scope="module")
def workdir(tmp_path_factory):
    """Images, RUNS files and the images.inc compiled into the harness, one per batch."""
    root = tmp_path_factory.mktemp("cpp_conformance")
    inc = []
    for k, batch in enumerate(BATCHES):
        (root / ("%d.svm" % k)).write_bytes(batch.image)
        (root / ("%d.runs" % k)).write_text(runs_text(batch))
        inc.append(c_array("kImage%d" % k, batch.image))
    inc.append("const unsigned char* const kImages[] = {%s};\n" % ", ".join("kImage%d" % k for k in range(len(BATCHES))))
    inc.append("const std::size_t kImageSizes[] = {%s};\n" % ", ".join("sizeof kImage%d" % k for k in range(len(BATCHES))))
    (root / "images.inc").write_text("".join(inc))
    return root


@pytest.fixture(scope="module", params=COMPILERS)
def harness(request, workdir):
    exe = workdir / ("harness_" + request.param.replace("+", "p"))
    subprocess.run([request.param] + FLAGS + ["-I", str(RUNTIME_CPP), "-I", str(workdir),
                    "-DSWARMVM_IMAGES=\"images.inc\"", "-o", str(exe),
                    str(RUNTIME_CPP / "conformance_harness.cpp")], check=True)
    return exe


def expected(batch):
    return "".join("\n".join(reference(batch, run)) + "\nend\n" for run in batch.runs)


@pytest.mark.parametrize("mode", ["--compiled", "--image"])
def test_every_run_matches_reference(harness, workdir, mode):
    for k, batch in enumerate(BATCHES):
        source = str(k) if mode == "--compiled" else str(workdir / ("%d.svm" % k))
        out = subprocess.run([str(harness), mode, source, str(workdir / ("%d.runs" % k))],
                             capture_output=True, text=True, check=True).stdout
        want = expected(batch)
        if out != want:
            got_runs, want_runs = out.split("end\n"), want.split("end\n")
            for run, got, ref in zip(batch.runs, got_runs, want_runs):
                assert got == ref, "%s %s: first differing run %s" % (batch.name, mode, run)
            assert out == want, batch.name


def test_corpus_exercises_every_option():
    """The batches cover weighted images and both input and control modes (guards the suite itself)."""
    assert len(BATCHES) >= 8
    assert sum(len(b.runs) for b in BATCHES) >= 8 * 72
    assert any(b.image[5] & 2 for b in BATCHES), "no probabilistic image in the corpus"


def test_refused_image_reports_the_defect(harness, workdir):
    """A corrupted image is refused with a clear message, not run."""
    bad = bytearray(BATCHES[0].image)
    bad[20] ^= 0xFF
    path = workdir / "bad.svm"
    path.write_bytes(bytes(bad))
    result = subprocess.run([str(harness), "--image", str(path), str(workdir / "0.runs")],
                            capture_output=True, text=True)
    assert result.returncode == 1
    assert "checksum mismatch" in result.stderr


def python_compat_lines(yaml_path, steps):
    """What runtime_cpp/compat_check.cpp prints per step, from the Python runtime's SCT."""
    sct = python_vm().SCT(str(yaml_path), exact=False)     # the C++ SCT has the canonical step only
    called, step = [], [0]
    for name, index in sct.EV.items():
        if sct.ev_controllable[index]:
            sct.add_callback(index, lambda data, name=name: data.append(name), None, called)
        else:
            sct.add_callback(index, None, lambda _data, name=name: (step[0] * 7 + len(name)) % 3 == 0, None)
    lines = []
    for step[0] in range(1, steps + 1):
        del called[:]
        sct.run_step()
        lines.append("%d %s %s %d" % (step[0], ",".join(called) or "-", ",".join(str(s) for s in sct.sup_current_state),
                                      sct.vm.violations))
    return lines


@pytest.fixture(scope="module", params=COMPILERS)
def compat_check(request, workdir):
    exe = workdir / ("compat_check_" + request.param.replace("+", "p"))
    subprocess.run([request.param] + FLAGS + ["-I", str(RUNTIME_CPP), "-o", str(exe),
                    str(RUNTIME_CPP / "compat_check.cpp")], check=True)
    return exe


@pytest.mark.parametrize("supervisor", ["energy_worker", "network_worker", "hitl_leader"])
def test_compat_api_matches_python_sct(tmp_path, compat_check, supervisor):
    """SCT(path.yaml) loads the .svm beside it; published-style registration (member functions,
    NULL halves) drives the same run as the Python SCT; unknown names, corrupted images and
    image swaps behave as specified."""
    corpus = [b for b in BATCHES if b.name == supervisor][0]
    (tmp_path / "supervisor.svm").write_bytes(corpus.image)
    out = subprocess.run([str(compat_check), str(tmp_path / "supervisor.yaml"), "30"], capture_output=True, text=True)
    assert out.returncode == 0, out.stdout + out.stderr
    lines = out.stdout.splitlines()
    assert lines[:30] == python_compat_lines(tmp_path / "supervisor.yaml", 30)
    assert any(line.split()[1] != "-" for line in lines[:30]), "no action ever ran"
    if supervisor == "network_worker":
        assert int(lines[29].split()[3]) > 0, "the run should exercise violations"
    assert lines[30:] == ["ok unknown event refused with its name", "ok learned policy refused",
                          "ok corrupted image refused, previous logic kept",
                          "ok swapped image restarts from the initial states",
                          "ok callbacks rebound by name after the swap: the run repeats",
                          "ok member callbacks and the violation hook on the core VM"]
