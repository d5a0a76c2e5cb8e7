"""Every C header of runtime_c/ can be included from C++ (issue 28, point 5): a C++ translation
unit that includes them calls the runtime by its C names, so it links against the runtime
compiled as C. Without ``extern "C"`` the C++ unit would ask for mangled names
(``_Z8svm_initP8svm_vm_t``) that no C object defines."""

import subprocess

import pytest

from targets.kilobot.needs import kilolib_or_skip
from swarmvm.compiler.runtime_files import RUNTIME_C

from imports import ROOT

# Headers the host compiles, each with one of its functions (called by the C++ unit) and the C
# source defining it; header-only ones (macros, static inline functions) with none.
HOST = {
    "swarmvm.h": ("svm_init", "swarmvm.c"),
    "swarmvm_sct.h": ("SCT_vm", "swarmvm_sct.c"),
    "swarmvm_store.h": ("svm_store_save", "swarmvm_store.c"),
    "swarmvm_learn.h": ("svl_classifier_init", "swarmvm_learn.c"),
    "swarmvm_learn_store.h": ("svl_keeper_start", "swarmvm_learn_store.c"),
    "swarmvm_stream.h": ("svm_stream_init", "swarmvm_stream.c"),
    "swarmvm_trace.h": None,
    "swarmvm_format.h": None,
    "swarmvm_crc_tables.h": None,
    "swarmvm_kilobot_eeprom.h": None,
}
# What the unit defines for the runtime: the generated tables' loader of the compatibility layer
# (swarmvm_sct.h), which swarmvm_sct.c calls by its C name.
DEFINED = "int svm_sct_load(svm_vm_t *vm)\n{\n    return vm == nullptr;\n}\n"
# Headers of one platform or linker script, compiled by a C++ compiler but not linked here: the
# runtime functions the unit refers to must be undefined under their C names.
PLATFORM = {"swarmvm_kilobot.h": "svm_kilobot_after_step", "swarmvm_store_zephyr.h": "svm_store_zephyr_flash",
            "swarmvm_logic_page.h": "svm_logic_page_size"}


def _unit(headers, functions, defined="") -> str:
    """A C++ translation unit including ``headers``, defining ``defined`` and taking the address
    of each of ``functions`` (a reference the linker resolves, no argument made up)."""
    includes = "".join('#include "%s"\n' % header for header in headers)
    calls = "".join("    used[%d] = reinterpret_cast<void (*)()>(&%s);\n" % (i, name) for i, name in enumerate(functions))
    return includes + "\n" + defined + "\nvoid (*volatile used[%d])();\n\nint main()\n{\n%s    return 0;\n}\n" % (
        max(len(functions), 1), calls)


def _run(command) -> None:
    proc = subprocess.run([str(part) for part in command], capture_output=True, text=True)
    assert proc.returncode == 0, proc.stderr[-3000:]


def test_every_runtime_header_is_covered():
    assert sorted([*HOST, *PLATFORM]) == sorted(path.name for path in RUNTIME_C.glob("*.h"))


def test_the_host_headers_link_from_cpp_against_the_c_runtime(tmp_path):
    objects = []
    for _function, source in filter(None, HOST.values()):
        objects.append(tmp_path / (source + ".o"))
        _run(["gcc", "-std=c99", "-O1", "-I", RUNTIME_C, "-c", RUNTIME_C / source, "-o", objects[-1]])
    unit = tmp_path / "unit.cpp"
    unit.write_text(_unit(sorted(HOST), [function for function, _source in filter(None, HOST.values())], DEFINED))
    _run(["g++", "-std=c++17", "-Wall", "-Werror", "-I", RUNTIME_C, "-c", unit, "-o", tmp_path / "unit.o"])
    _run(["g++", tmp_path / "unit.o", *objects, "-o", tmp_path / "unit"])
    _run([tmp_path / "unit"])


@pytest.mark.parametrize("header", sorted(PLATFORM))
def test_the_platform_headers_call_c_names_from_cpp(header, tmp_path):
    """Compiled by the platform's C++ compiler (avr-g++ with kilolib; g++ with the Zephyr
    stand-ins of firmware/capbot/zephyr, or for the logic page, whose bounds come from the
    CapBot linker script): the runtime function the unit refers to is undefined under its C
    name, the name the C object defines."""
    if header == "swarmvm_kilobot.h":
        command = ["avr-g++", "-mmcu=atmega328p", "-I", kilolib_or_skip()]
        nm = "avr-nm"
    else:
        command = ["g++", "-I", ROOT / "firmware" / "capbot"]      # <zephyr/...>: the stand-ins
        nm = "nm"
    unit = tmp_path / "unit.cpp"
    unit.write_text(_unit([header], [PLATFORM[header]]))
    _run([*command, "-std=c++17", "-I", RUNTIME_C, "-c", unit, "-o", tmp_path / "unit.o"])
    undefined = subprocess.run([nm, "-u", tmp_path / "unit.o"], capture_output=True, text=True, check=True).stdout
    assert PLATFORM[header] in undefined.split(), undefined
