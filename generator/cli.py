"""The ``swarmvm`` command line: check, pack, gen, script, trace, footprint.

Bad input ends with one line ``swarmvm: error: FILE: KEY: WHERE: MESSAGE`` on stderr and
exit status 2, before anything is written."""

import functools
import os
import sys

import click

from . import __version__
from .errors import InputError
from .pipeline import compile_inputs, compile_spec, load
from .runtime import python_vm
from .script import format_script, parse_script, random_script
from .targets import TARGETS, generate
from .render import write_outputs
from .studies import cli as studies_cli

vm = python_vm()


def reports_errors(command):
    """Turn InputError into the one-line message and exit status 2."""
    @functools.wraps(command)
    def wrapper(*args, **kwargs):
        try:
            return command(*args, **kwargs)
        except InputError as exc:
            click.echo("swarmvm: error: %s" % exc, err=True)
            sys.exit(2)
    return wrapper


def _warn(compiled):
    for warning in compiled.model.warnings:
        click.echo("swarmvm: warning: %s" % warning, err=True)


def _load_image(path):
    try:
        return vm.Image.load(path)
    except vm.ImageError as exc:
        raise InputError(path, "image", str(exc))
    except OSError as exc:
        raise InputError(path, "", "cannot read file (%s)" % exc.strerror)


@click.group(context_settings={"help_option_names": ["-h", "--help"]})
@click.version_option(__version__, prog_name="swarmvm")
def main():
    """Compile synthesised supervisors into table-driven VMs for swarm robots."""


@main.command()
@click.argument("files", nargs=-1, required=True)
@reports_errors
def check(files):
    """Validate supervisors (.yaml, .xml) or table images (.svm) and print their sizes.

    Counts are as read from each file, summed over its local supervisors; bytes is the file
    size. A .svm image is checked (magic, version, checksum) and its counts printed."""
    rows = []
    for path in files:
        if path.endswith(".svm"):
            image = _load_image(path)
            counts = (image.num_events, image.num_supervisors, len(image.state_defined), len(image.targets))
            rows.append((os.path.basename(path),) + counts + (len(image.raw),))
            continue
        spec = load([path])
        _warn(compile_spec(spec, [path]))
        rows.append((os.path.basename(path),) + spec.counts() + (spec.size_bytes,))
    click.echo("| file | events | supervisors | states | transitions | bytes |")
    click.echo("|---|---|---|---|---|---|")
    for row in rows:
        click.echo("| %s | %d | %d | %d | %d | %d |" % row)


@main.command()
@click.argument("inputs", nargs=-1, required=True)
@click.option("-o", "--output", required=True, help="The .svm file to write.")
@click.option("--no-names", is_flag=True, help="Leave event names out (callbacks then bind by index).")
@reports_errors
def pack(inputs, output, no_names):
    """Write the portable table image of a supervisor (docs/image-format.md)."""
    compiled = compile_inputs(inputs, names=not no_names)
    _warn(compiled)
    directory, name = os.path.split(os.path.abspath(output))
    write_outputs(directory, {name: (compiled.image, False)})
    click.echo("%s: %d bytes" % (output, len(compiled.image)))


@main.command()
@click.argument("inputs", nargs=-1, required=True)
@click.option("-t", "--target", type=click.Choice(sorted(TARGETS)), required=True)
@click.option("-o", "--output", "outdir", required=True, help="Directory to write into.")
@click.option("--name", help="Model name for generated files (default: the input's file stem).")
@click.option("--learned-check", "learned", multiple=True, metavar="YES/NO",
              help="Decide the uncontrollable pair YES/NO (e.g. capableTask/notCapableTask) with an "
                   "online classifier on features the application supplies (docs/learning.md). Repeatable.")
@reports_errors
def gen(inputs, target, outdir, name, learned):
    """Generate a target's VM sources: table image, tables, glue and a controller skeleton.

    Several Nadzoru 2 XML automata make one set of local supervisors. A controller skeleton
    that already exists is never overwritten."""
    compiled = compile_inputs(inputs, name=name)
    _warn(compiled)
    pairs = _learned_pairs(inputs[0], compiled.model, target, learned)
    for path in write_outputs(outdir, generate(compiled, target, learned_checks=pairs)):
        click.echo(path)


def _learned_pairs(source, model, target, specs):
    """``--learned-check YES/NO`` values as [{yes, no}] of bare event names, validated: two
    distinct uncontrollable events of the model, each in one pair only."""
    if specs and not TARGETS[target].learned_templates:
        raise InputError(source, "--learned-check", "target %s does not generate learned checks" % target)
    pairs, used = [], set()
    for spec in specs:
        names = [n[3:] if n.startswith("EV_") else n for n in spec.split("/")]
        if len(names) != 2 or names[0] == names[1]:
            raise InputError(source, "--learned-check", "%r is not YES/NO (two different event names)" % spec)
        for bare in names:
            if bare not in model.events:
                raise InputError(source, "--learned-check", "no event named %r" % bare)
            if model.controllable[model.events.index(bare)]:
                raise InputError(source, "--learned-check", "%s is controllable: only checks can be learned" % bare)
            if bare in used:
                raise InputError(source, "--learned-check", "%s is in two learned checks" % bare)
            used.add(bare)
        pairs.append(dict(yes=names[0], no=names[1]))
    return pairs


@main.command()
@click.argument("inputs", nargs=-1, required=True)
@click.option("--steps", default=100, show_default=True, type=click.IntRange(1, 10 ** 7))
@click.option("--seed", default=1, show_default=True, type=int)
@click.option("--density", default=0.25, show_default=True, type=click.FloatRange(0, 1),
              help="Chance that an uncontrollable event occurs in a step.")
@reports_errors
def script(inputs, steps, seed, density):
    """Print a reproducible random event script for a supervisor."""
    compiled = compile_inputs(inputs)
    rows = random_script(compiled.tables, steps, seed, density)
    click.echo(format_script(rows, compiled.model.events), nl=False)


@main.command()
@click.argument("inputs", nargs=-1, required=True)
@click.option("--script", "script_path", required=True, type=click.Path(dir_okay=False),
              help="Event script (docs/conformance.md).")
@click.option("--seed", default=1, show_default=True, type=click.IntRange(0, 0xFFFFFFFF))
@click.option("--inputs", "input_mode", type=click.Choice(vm.INPUT_MODES), default="level", show_default=True)
@click.option("--control", type=click.Choice(vm.CONTROL_MODES), default="after-inputs", show_default=True)
@click.option("--policy", type=click.Choice(["uniform", "first", "weighted"]), default="uniform", show_default=True)
@reports_errors
def trace(inputs, script_path, seed, input_mode, control, policy):
    """Run the reference (Python) VM on an event script and print the canonical trace.

    INPUTS is a supervisor (.yaml, .xml...) or a table image (.svm)."""
    if len(inputs) == 1 and inputs[0].endswith(".svm"):
        image = _load_image(inputs[0])
    else:
        compiled = compile_inputs(inputs)
        _warn(compiled)
        image = vm.Image.parse(compiled.image)
    if image.names is None:
        raise InputError(inputs[0], "image", "carries no event names; scripts name events")
    try:
        with open(script_path) as handle:
            text = handle.read()
    except OSError as exc:
        raise InputError(script_path, "", "cannot read file (%s)" % exc.strerror)
    rows = parse_script(script_path, text, image.names, image.controllable)
    machine = vm.VM(image, inputs=input_mode, control=control, policy=policy, seed=seed)
    for line in vm.replay(machine, rows):
        click.echo(line)


@main.command()
@click.argument("elfs", nargs=-1, required=True, type=click.Path(exists=True, dir_okay=False))
@click.option("--json", "json_path", type=click.Path(dir_okay=False), help="Also write the report as JSON.")
@click.option("--kilobot-flash", default=28672, show_default=True, type=click.IntRange(0),
              help="Flash a Kilobot image may use (bytes below the bootloader).")
@click.option("--kilobot-stack", default=1024, show_default=True, type=click.IntRange(0),
              help="SRAM a Kilobot image must leave for the stack (of 2,048 bytes).")
@click.option("--vm-limit", default=100000, show_default=True, type=click.IntRange(0),
              help="Bytes the VM (core + tables, flash + RAM) may take: the seed's KPI.")
def footprint(elfs, json_path, kilobot_flash, kilobot_stack, vm_limit):
    """Report flash and static RAM of linked VM images, split into VM core, tables and application.

    ELFS are linked images named <supervisor>.elf; the target comes from the machine (AVR:
    kilobot, ARM: capbot). Prints Markdown (docs/footprint.md); exits with status 1 and a
    one-line reason when an image exceeds a limit."""
    from elftools.common.exceptions import ELFError

    from . import footprint as fp
    try:
        rows = [fp.measure(path) for path in elfs]
    except (fp.FootprintError, ELFError) as exc:
        click.echo("swarmvm: error: %s" % exc, err=True)
        sys.exit(2)
    limits = fp.Limits(kilobot_flash=kilobot_flash, kilobot_min_stack=kilobot_stack, vm=vm_limit)
    click.echo(fp.report_markdown(rows, limits), nl=False)
    if json_path:
        directory, name = os.path.split(os.path.abspath(json_path))
        write_outputs(directory, {name: (fp.report_json(rows, limits).encode(), False)})
    problems = fp.violations(rows, limits)
    if problems:
        more = " (and %d more)" % (len(problems) - 1) if len(problems) > 1 else ""
        click.echo("swarmvm: footprint: %s%s" % (problems[0], more), err=True)
        sys.exit(1)


main.add_command(studies_cli.sim)
main.add_command(studies_cli.sweep)
main.add_command(studies_cli.plot)
