"""Switch a published OpenSwarm ARGoS project from its published VM to swarmvm's ``sct.h``
(``swarmvm compat-switch``, docs/compat.md): the build files and includes edited as they are.

The published projects build their VM into a ``utility`` library (``src/utility/sct.h``,
``sct.cpp``, linked with yaml-cpp, beside their own ``pid``, ``robot_message``, ... sources),
and their controllers include ``<utility/sct.h>``. A patch written for one layout fails on the
next, so the switch is made by reading each file for what it must change:

- ``src/utility/CMakeLists.txt``: in ``add_library(utility ...)``, ``sct.cpp`` goes and
  ``sct.h`` becomes swarmvm's header-only drop-in (``${SWARMVM_RUNTIME_DIR}/sct.h``); the other
  sources stay, and so does ``yaml-cpp`` in its ``target_link_libraries`` when another of them
  includes a yaml-cpp header;
- ``src/CMakeLists.txt``: before its first ``add_subdirectory``, the lines that ask the
  ``swarmvm`` program for its CMake folder (``swarmvm cmake-dir``: no ``python3`` involved),
  include ``swarmvm_argos.cmake``, put the drop-in on the include path, define the mhsc variant
  where the project uses it, and pack the project's supervisors into the images beside them;
- every C++ file under ``src/`` outside ``utility/``: ``#include <utility/sct.h>`` (or
  ``"utility/sct.h"``) becomes ``#include <sct.h>``.

Which published variant a project uses is read from its published ``sct.h`` (``add_callback``
taking ``std::string event`` or ``unsigned char event``), else from its controllers' calls. A
file already switched is left as it is, so a second run changes nothing. The published
``sct.h`` and ``sct.cpp`` themselves stay where they are, no longer built."""

import os
import re
from dataclasses import dataclass
from pathlib import Path

from ..boundary.errors import InputError, read_input
from ..boundary.escape import cmake_string
from ..boundary.output import write_outputs
from ..compiler.pipeline import load

VARIANTS = ("default", "mhsc")
TOP = Path("src") / "CMakeLists.txt"
UTILITY = Path("src") / "utility" / "CMakeLists.txt"
DROP_IN = "${SWARMVM_RUNTIME_DIR}/sct.h"
MHSC_DEFINE = "SWARMVM_SCT_VARIANT_MHSC"
# What CMake says when neither PATH nor -DSWARMVM_EXECUTABLE gives a swarmvm (docs/compat.md shows it).
NOT_FOUND = ("swarmvm not found (SWARMVM_EXECUTABLE=${SWARMVM_EXECUTABLE}): install it (pip install swarmvm), "
             "or pass -DSWARMVM_EXECUTABLE=<path of the swarmvm program>")
CXX_SUFFIXES = (".h", ".hh", ".hpp", ".hxx", ".c", ".cc", ".cpp", ".cxx")

_UTILITY_LIBRARY = re.compile(r"add_library\s*\(\s*utility\b([^)]*)\)", re.I)
_UTILITY_LINKS = re.compile(r"target_link_libraries\s*\(\s*utility\b([^)]*)\)", re.I)
_FIRST_SUBDIRECTORY = re.compile(r"^(?:[ \t]*#[^\n]*\n)*[ \t]*add_subdirectory\s*\(", re.I | re.M)
_PUBLISHED_INCLUDE = re.compile(r'#([ \t]*)include[ \t]*[<"](?:\.\./)*utility/sct\.h[>"]')
_YAML_CPP_INCLUDE = re.compile(r'#[ \t]*include[ \t]*[<"]yaml-cpp/')


@dataclass(frozen=True)
class Switch:
    """What ``compat-switch`` did to a project: the files it wrote (none: it was switched
    already), the variant it switched to (None when ``src/CMakeLists.txt`` was switched
    already), and the supervisors the build now packs."""
    written: list[str]
    variant: str | None
    supervisors: list[str]


def _text(path: Path) -> str:
    """The text of a file the switch may edit in place, bytes that are not UTF-8 kept as they
    are (written back unchanged); read as a file to be replaced, not as an input to keep."""
    return read_input(str(path), edit=True).decode("utf-8", "surrogateescape")


def _bytes(text: str) -> bytes:
    return text.encode("utf-8", "surrogateescape")


def _newline(text: str) -> str:
    return "\r\n" if "\r\n" in text else "\n"


def _drop_token(arguments: str, token: str) -> str:
    """``arguments`` of a CMake command without the argument ``token``: its whole line when it
    is alone on one, else the token and the blank before it."""
    word = re.escape(token)
    alone = re.compile(r"^[ \t]*%s[ \t]*\r?\n" % word, re.M)
    if alone.search(arguments):
        return alone.sub("", arguments, count=1)
    return re.sub(r"[ \t\r\n]*(?<![^\s(])%s(?![^\s)])" % word, "", arguments, count=1)


def _replace_token(arguments: str, token: str, replacement: str) -> str:
    return re.sub(r"(?<![^\s(])%s(?![^\s)])" % re.escape(token), lambda _: replacement, arguments, count=1)


def _tokens(arguments: str) -> list[str]:
    return arguments.split()


def _not_a_project(project: Path, found: str) -> InputError:
    return InputError(str(project), "", "not an OpenSwarm ARGoS project: looked for %s and %s with an "
                      "add_library(utility ...) listing the published VM's sct.cpp; %s" % (TOP, UTILITY, found))


def _switched_utility(project: Path) -> str | None:
    """The new text of ``src/utility/CMakeLists.txt``, or None when it is switched already."""
    text = _text(project / UTILITY)
    library = _UTILITY_LIBRARY.search(text)
    if library is None:
        raise _not_a_project(project, "%s has no add_library(utility ...)" % UTILITY)
    sources = _tokens(library.group(1))
    if "sct.cpp" not in sources:
        if DROP_IN in sources:
            return None
        raise _not_a_project(project, "its utility library does not list sct.cpp")
    others = [s for s in sources if s not in ("sct.h", "sct.cpp", "SHARED", "STATIC", "MODULE")]
    if not any(s.endswith((".c", ".cc", ".cpp", ".cxx")) for s in others):
        raise InputError(str(project / UTILITY), "add_library(utility)", "the published VM is its only source: "
                         "swarmvm's sct.h is header-only, so remove the library and its uses by hand")
    arguments = _drop_token(library.group(1), "sct.cpp")
    arguments = _replace_token(arguments, "sct.h", DROP_IN) if "sct.h" in sources else arguments
    text = text[:library.start(1)] + arguments + text[library.end(1):]
    links = _UTILITY_LINKS.search(text)
    needs_yaml = any(_YAML_CPP_INCLUDE.search(_text(path)) for path in
                     (project / UTILITY.parent / s for s in others) if path.is_file())
    if links is not None and "yaml-cpp" in _tokens(links.group(1)) and not needs_yaml:
        text = text[:links.start(1)] + _drop_token(links.group(1), "yaml-cpp") + text[links.end(1):]
    return text


def _variant(project: Path, sources: list[Path]) -> str:
    """The published variant the project uses: from its published sct.h, else its controllers."""
    published = project / UTILITY.parent / "sct.h"
    if published.is_file():
        header = _text(published)
        if re.search(r"add_callback\s*\([^)]*unsigned\s+char\s+event", header):
            return "mhsc"
        if re.search(r"add_callback\s*\([^)]*std::string\s+event", header):
            return "default"
    calls = "".join(_text(path) for path in sources)
    if re.search(r"add_callback\s*\(\s*this\s*,\s*[\w>.-]*events\s*\[", calls):
        return "mhsc"
    if re.search(r"add_callback\s*\(\s*this\s*,\s*std::string\s*\(", calls):
        return "default"
    raise InputError(str(project), "--variant", "cannot tell which published sct.h the project uses (neither "
                     "src/utility/sct.h nor a controller's add_callback call says): pass --variant default or "
                     "--variant mhsc")


def _supervisors(project: Path) -> list[Path]:
    """The supervisor files (``*.yaml`` that swarmvm reads as one) in the project, outside
    hidden folders and CMake build folders."""
    found = []
    for folder, subfolders, files in os.walk(project):
        subfolders[:] = sorted(d for d in subfolders if not d.startswith(".")
                               and not (Path(folder) / d / "CMakeCache.txt").exists())
        for name in sorted(files):
            if name.endswith(".yaml"):
                try:
                    load([str(Path(folder) / name)])
                except InputError:
                    continue
                found.append(Path(folder) / name)
    return found


def _snippet(variant: str, supervisors: list[str], newline: str) -> str:
    """The lines ``src/CMakeLists.txt`` gets: swarmvm found through its program, never python3."""
    lines = [
        "# swarmvm's sct.h instead of the published VM (swarmvm compat-switch): the swarmvm program",
        "# says where its CMake folder is; -DSWARMVM_EXECUTABLE=<path> when it is not on PATH",
        'find_program(SWARMVM_EXECUTABLE swarmvm DOC "The swarmvm program (swarmvm cmake-dir, swarmvm_pack)")',
        'execute_process(COMMAND "${SWARMVM_EXECUTABLE}" cmake-dir OUTPUT_VARIABLE SWARMVM_CMAKE_DIR',
        "                OUTPUT_STRIP_TRAILING_WHITESPACE ERROR_QUIET)",
        'if(NOT EXISTS "${SWARMVM_CMAKE_DIR}/swarmvm_argos.cmake")',
        '  message(FATAL_ERROR "%s")' % NOT_FOUND,
        "endif()",
        'include("${SWARMVM_CMAKE_DIR}/swarmvm_argos.cmake")',
        'include_directories("${SWARMVM_RUNTIME_DIR}")',
    ]
    if variant == "mhsc":
        lines.append("add_compile_definitions(%s)" % MHSC_DEFINE)
    if supervisors:
        lines.append("swarmvm_pack(supervisors %s)" % " ".join(cmake_string(s) for s in supervisors))
    return newline.join(lines) + newline + newline


def _switched_top(project: Path, variant: str | None, sources: list[Path]) -> tuple[str | None, str | None, list[str]]:
    """(new text of src/CMakeLists.txt or None when switched already, the variant, the
    supervisors packed, relative to src/)."""
    text = _text(project / TOP)
    if "swarmvm_argos.cmake" in text:
        return None, None, []
    first = _FIRST_SUBDIRECTORY.search(text)
    if first is None:
        raise _not_a_project(project, "%s has no add_subdirectory(...)" % TOP)
    variant = variant or _variant(project, sources)
    supervisors = [Path(os.path.relpath(p, project / "src")).as_posix() for p in _supervisors(project)]
    snippet = _snippet(variant, supervisors, _newline(text))
    return text[:first.start()] + snippet + text[first.start():], variant, supervisors


def _cxx_files(project: Path) -> list[Path]:
    """The C++ files under src/, outside utility/ (the published VM's folder), hidden folders
    and CMake build folders."""
    found = []
    for folder, subfolders, files in os.walk(project / "src"):
        subfolders[:] = sorted(d for d in subfolders if not d.startswith(".")
                               and not (Path(folder) / d / "CMakeCache.txt").exists()
                               and Path(folder) / d != project / UTILITY.parent)
        found += [Path(folder) / name for name in sorted(files) if name.endswith(CXX_SUFFIXES)]
    return found


def switch_project(project: Path, variant: str | None = None) -> Switch:
    """Switch the OpenSwarm ARGoS project in ``project`` (the folder holding ``src/``) to
    swarmvm's sct.h, writing every changed file or none (this module's docstring); ``variant``
    (one of VARIANTS) overrides the one read from the project. InputError, before anything is
    written, when the folder is not such a project."""
    if not (project / TOP).is_file() or not (project / UTILITY).is_file():
        missing = TOP if not (project / TOP).is_file() else UTILITY
        raise _not_a_project(project, "%s is missing" % missing)
    files: dict[str, tuple[bytes, bool]] = {}
    utility = _switched_utility(project)
    if utility is not None:
        files[UTILITY.as_posix()] = (_bytes(utility), False)
    sources = _cxx_files(project)
    top, chosen, supervisors = _switched_top(project, variant, sources)
    if top is not None:
        files[TOP.as_posix()] = (_bytes(top), False)
    for path in sources:
        text = _text(path)
        if _PUBLISHED_INCLUDE.search(text):
            text = _PUBLISHED_INCLUDE.sub(lambda m: "#%sinclude <sct.h>" % m.group(1), text)
            files[path.relative_to(project).as_posix()] = (_bytes(text), False)
    written = write_outputs(project, files, option="PROJECT_DIR") if files else []
    return Switch(written, chosen, supervisors)
