"""The targets ``swarmvm gen --target`` knows: which templates render to which files.

A target differs from another only in its templates and the runtime files it ships; the
tables and image are the same for all. A file entry is (template, output name, keep): output
names may use ``{name}``; ``keep`` marks user-edited files that are never overwritten."""

from dataclasses import dataclass, field

from .render import context, render
from .runtime import RUNTIME_PY


@dataclass(frozen=True)
class Target:
    description: str
    templates: tuple                     # (template, output name, keep)
    copies: tuple = field(default=())    # (source path, output name)


TARGETS = {
    "python": Target(
        "Python VM: table module, controller skeleton, the runtime (stdlib only)",
        templates=(("python/tables.py.j2", "{name}_tables.py", False),
                   ("python/controller.py.j2", "{name}_controller.py", True)),
        copies=((RUNTIME_PY, "swarmvm_vm.py"),)),
}


def generate(compiled, target, **options):
    """{output name: (bytes, keep)} for one target: rendered templates, runtime copies, image."""
    spec = TARGETS[target]
    values = context(compiled, target=target, **options)
    files = {"%s.svm" % compiled.name: (compiled.image, False)}
    for template, output, keep in spec.templates:
        files[output.format(name=compiled.name)] = (render(template, values), keep)
    for source, output in spec.copies:
        files[output.format(name=compiled.name)] = (source.read_bytes(), False)
    return files
