"""The targets ``swarmvm gen --target`` knows, and what renders them: one registry of records.

Every module of this package that exports ``TARGET`` (a swarmvm.targets.record.Target) is a
target, and so is every such module in the folders of the environment variable
``SWARMVM_TARGET_PATH`` (separated as PATH is): a target is its module, its template folder and
its docs page (docs/extending.md), registered here by :func:`register` and named nowhere else.
A target differs from another only in its record: the tables and image are the same for all."""

import dataclasses
import fnmatch
import os
import pkgutil
import sys
from collections.abc import Iterator
from importlib import import_module, util
from pathlib import Path
from types import ModuleType

from .. import __version__
from ..boundary.errors import InputError
from ..boundary.escape import UnsafeText
from ..compiler.pipeline import Compiled
from ..compiler.render import FOLDERS, context, render
from ..footprint.sidecar import SUFFIX, sidecar_text
from .record import Readme, Target

TARGET_PATH = "SWARMVM_TARGET_PATH"

TARGETS: dict[str, Target] = {}


def register(target: Target) -> None:
    """Make ``target`` one of TARGETS, its template folder the one its ``<name>/`` templates
    are read from; ValueError when another target has its name."""
    if target.name in TARGETS:
        raise ValueError("two targets named %r" % target.name)
    TARGETS[target.name] = target
    FOLDERS[target.name] = target.template_folder


def module_from_file(path: Path) -> ModuleType:
    """A target module outside the package, imported by its path (not registered: the registry
    registers the TARGET of each module it finds)."""
    spec = util.spec_from_file_location("swarmvm_target_" + path.stem, path)
    if spec is None or spec.loader is None:
        raise ImportError("cannot import the target module %s" % path)
    module = util.module_from_spec(spec)
    sys.modules[spec.name] = module
    spec.loader.exec_module(module)
    return module


def target_modules() -> Iterator[ModuleType]:
    """This package's modules, then those of the SWARMVM_TARGET_PATH folders, each in name order."""
    for info in sorted(pkgutil.iter_modules(__path__), key=lambda i: i.name):
        yield import_module("%s.%s" % (__name__, info.name))
    for folder in filter(None, os.environ.get(TARGET_PATH, "").split(os.pathsep)):
        for path in sorted(Path(folder).glob("*.py")):
            yield module_from_file(path)


for _module in target_modules():
    if isinstance(getattr(_module, "TARGET", None), Target):
        register(_module.TARGET)


def generate(compiled: Compiled, target: str, **options: object) -> dict[str, tuple[bytes, bool]]:
    """{output name: (bytes, keep)} for one target: rendered templates, runtime copies, image."""
    spec = TARGETS[target]
    name = compiled.name        # refused (InputError) for every target alike, before any target's own checks
    if spec.keeps_order:
        compiled = dataclasses.replace(compiled, image=compiled.ordered_image)
    try:
        extra = spec.rules(compiled) if spec.rules else {}
    except InputError as error:         # refused for this target only: say which
        raise InputError(error.file, error.key, "target %s: %s" % (target, error.message), error.where)
    if spec.values:
        extra = dict(extra, **spec.values(compiled))
    values = context(compiled, target=target, **dict(options, **extra))
    templates, copies = spec.templates, spec.copies
    if options.get("learned_checks"):
        templates, copies = templates + spec.learned_templates, copies + spec.learned_copies
    files = {"%s.svm" % name: (compiled.image, False)}
    for template, output, keep in templates:
        rel = output.format(name=name)
        try:
            files[rel] = (render(template, values), keep)
        except UnsafeText as error:     # text that file's language cannot hold (swarmvm.boundary.escape)
            raise InputError(compiled.model.source, "--target", "target %s: %s: %s" % (target, rel, error))
    for source, output in copies:
        files[output.format(name=name)] = (copy_banner(output) + source.read_bytes(), False)
    if spec.elf is not None:        # what `swarmvm footprint` needs beside the ELF the folder's build links
        text = sidecar_text(target, compiled.image, compiled.tables, compiled.model.events,
                            spec.elf.indirect + spec.elf.generated_indirect, spec.elf.script_steps)
        files[name + SUFFIX] = (text.encode("utf-8"), False)
    if spec.readme is not None:
        files[README] = (readme(spec, spec.readme, values, files), False)
    _refuse_case_twins(compiled, target, files)
    return files


README = "README.md"
README_TEMPLATE = "common/README.md.j2"


def readme(spec: Target, about: Readme, values: dict[str, object], files: dict[str, tuple[bytes, bool]]) -> bytes:
    """The folder's README.md (README_TEMPLATE, one for every target, with the part ``about`` names):
    what each of ``files`` and the README itself is, one row per pattern of ``about`` in its order
    (a file under the first that matches it; one named by none last, undescribed) and owner, and
    how to build, run and measure the folder."""
    name = str(values["name"])
    patterns = [(pattern.format(name=name), what.format(name=name)) for pattern, what in about.files]
    rows: dict[tuple[int, bool], list[str]] = {}
    for rel in sorted({*files, README}):
        index = next((i for i, (pattern, _) in enumerate(patterns) if fnmatch.fnmatchcase(rel, pattern)), len(patterns))
        rows.setdefault((index, files.get(rel, (b"", False))[1]), []).append(rel)
    listed = [dict(names=names, keep=keep, what=patterns[index][1] if index < len(patterns) else "")
              for (index, keep), names in sorted(rows.items())]
    return render(README_TEMPLATE, dict(values, readme_files=listed, readme_part=about.part, measured=spec.elf is not None,
                                        description=spec.description,
                                        script_steps=spec.elf.script_steps if spec.elf else 0))


def _refuse_case_twins(compiled: Compiled, target: str, files: dict[str, tuple[bytes, bool]]) -> None:
    """InputError when two output names differ only by case: one file on the case-insensitive
    file systems of Windows and macOS, so a checkout or a build there would lose one."""
    seen: dict[str, str] = {}
    for rel in sorted(files):
        other = seen.setdefault(rel.lower(), rel)
        if other != rel:
            raise InputError(compiled.source, "--name", "target %s: the files %s and %s differ only by case, one file "
                             "on Windows and macOS: give another name with --name" % (target, other, rel))


def copy_banner(output: str) -> bytes:
    """The first line of a runtime file copied into a target: where it comes from, and that
    ``swarmvm gen`` owns it (rewrites it on every run)."""
    text = "Copied from the swarmvm %s runtime by swarmvm gen, which rewrites it: do not edit." % __version__
    return ("# %s\n" % text if output.endswith((".py", ".cmake")) else "/* %s */\n" % text).encode("ascii")
