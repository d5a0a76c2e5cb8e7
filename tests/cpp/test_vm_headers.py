"""The C++ runtime's headers: the VM stands without the compatibility layer, every old include
keeps working, and the VM is under the seed's 100 kB by the seed's measure (source bytes).

swarmvm.hpp is the umbrella of swarmvm_format.hpp (generated), swarmvm_image.hpp, swarmvm_vm.hpp
and swarmvm_compat.hpp (the published SCT's API). The footprint report's source table counts the
VM's files in one row and the compatibility layer in another (docs/footprint.md)."""

import subprocess

import pytest

from swarmvm.compiler.runtime_files import CPP_COMPAT_HEADERS, CPP_RUNTIME_HEADERS, CPP_VM_HEADERS, RUNTIME_CPP
from swarmvm.footprint.measure import source_sizes

SEED_KPI = 100_000
FLAGS = ["-std=c++17", "-Wall", "-Wextra", "-Werror", "-pedantic", "-fsyntax-only"]


def syntax_check(tmp_path, source):
    program = tmp_path / "use.cpp"
    program.write_text(source)
    return subprocess.run(["g++", *FLAGS, "-I", str(RUNTIME_CPP), str(program)], capture_output=True, text=True)


@pytest.mark.parametrize("header", CPP_RUNTIME_HEADERS)
def test_each_header_compiles_on_its_own(tmp_path, header):
    run = syntax_check(tmp_path, '#include "%s"\nint main() { return 0; }\n' % header)
    assert run.returncode == 0, run.stderr


def test_the_vm_header_runs_a_vm_without_the_compatibility_layer(tmp_path):
    use_vm = '#include "swarmvm_vm.hpp"\nint main() { swarmvm::XorShift32 rng(1); return rng.next() == 270369u ? 0 : 1; }\n'
    assert syntax_check(tmp_path, use_vm).returncode == 0
    use_sct = '#include "swarmvm_vm.hpp"\nint main() { swarmvm::SCT* sct = nullptr; return sct == nullptr ? 0 : 1; }\n'
    run = syntax_check(tmp_path, use_sct)
    assert run.returncode != 0 and "SCT" in run.stderr
    run = syntax_check(tmp_path, use_sct.replace("swarmvm_vm.hpp", "swarmvm.hpp"))
    assert run.returncode == 0, run.stderr


def test_the_vm_row_is_under_the_seed_kpi_and_the_compatibility_layer_has_its_own():
    sizes = source_sizes()
    vm = [size for name, size in sizes.items() if name.startswith("C++ VM (")]
    compat = [size for name, size in sizes.items() if name.startswith("C++ compatibility layer (")]
    assert vm == [sum(len((RUNTIME_CPP / n).read_bytes()) for n in CPP_VM_HEADERS)]
    assert compat == [sum(len((RUNTIME_CPP / n).read_bytes()) for n in CPP_COMPAT_HEADERS)]
    assert vm[0] < SEED_KPI
    # the umbrella only includes: every byte of the runtime is in one of the two rows
    assert set(CPP_RUNTIME_HEADERS) - set(CPP_VM_HEADERS) - set(CPP_COMPAT_HEADERS) == {"swarmvm.hpp"}
    assert "#include" in (RUNTIME_CPP / "swarmvm.hpp").read_text() and len((RUNTIME_CPP / "swarmvm.hpp").read_bytes()) < 1000
