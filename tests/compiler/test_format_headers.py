"""The C and C++ copies of the image format's numbers are generated, and committed as written.

runtime_c/swarmvm_format.h and runtime_cpp/swarmvm_format.hpp are scripts/format_headers.py's
output from runtime_py/swarmvm_format.py. Like the golden copies, they are written again here in
memory and compared byte for byte with the committed files: a change of the format without
``make format-headers`` fails, naming the command. test_format_constants.py then checks what the
compilers make of them."""

import sys

from checkout import ROOT
from swarmvm.compiler.runtime_files import RUNTIME_C, RUNTIME_CPP, image_format

sys.path.insert(0, str(ROOT / "scripts"))
import format_headers  # noqa: E402

F = image_format()


def test_the_committed_headers_are_what_the_script_writes():
    for path, write in format_headers.HEADERS:
        assert path.read_text() == write(F), "%s is stale: run %s" % (path.relative_to(ROOT), format_headers.REGENERATE)


def test_the_check_names_a_stale_header_and_how_to_regenerate_it(tmp_path, monkeypatch, capsys):
    stale = tmp_path / "swarmvm_format.h"
    stale.write_text(format_headers.c_header(F).replace("#define SVM_Q15_ONE 32768u", "#define SVM_Q15_ONE 32767u"))
    monkeypatch.setattr(format_headers, "ROOT", tmp_path)
    monkeypatch.setattr(format_headers, "HEADERS", ((stale, format_headers.c_header),))
    assert format_headers.main(["--check"]) == 1
    assert capsys.readouterr().err == "swarmvm_format.h differs from swarmvm_format.py: run %s\n" % format_headers.REGENERATE
    assert format_headers.main([]) == 0 and format_headers.main(["--check"]) == 0
    assert "#define SVM_Q15_ONE 32768u" in stale.read_text()


def test_the_headers_follow_a_change_of_the_format(monkeypatch):
    """What the headers say comes from the module, not from the script: another limit or code
    changes them."""
    monkeypatch.setattr(F, "Q15_ONE", 1 << 14)
    assert "#define SVM_Q15_ONE 16384u" in format_headers.c_header(F)
    assert "constexpr std::uint32_t kQ15One = 16384;" in format_headers.cpp_header(F)


def test_the_shipped_runtimes_are_the_checkout_s():
    """The headers the package ships (swarmvm.runtime_c, swarmvm.runtime_cpp) are the files compared."""
    assert (RUNTIME_C / "swarmvm_format.h").read_text() == format_headers.C_HEADER.read_text()
    assert (RUNTIME_CPP / "swarmvm_format.hpp").read_text() == format_headers.CPP_HEADER.read_text()
