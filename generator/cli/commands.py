"""The ``swarmvm`` command line (check, pack, gen, script, trace, footprint, synth, equiv,
export, inspect): a thin layer over :mod:`swarmvm.api`.

Bad input ends with one line ``swarmvm: error: FILE: KEY: WHERE: MESSAGE`` on stderr and
exit status 2, before anything is written."""

import functools
import os
import sys
from pathlib import Path
from typing import Any, Callable

import click

from .. import __version__, api
from ..boundary import terminal
from ..boundary.errors import verb_scope
from ..boundary.escape import markdown
from ..boundary.output import write_outputs
from ..boundary.termination import end_verbs_on_sigterm
from ..compiler.runtime_files import RUNTIME_CPP, python_app, python_vm
from ..footprint import budget as fp_budget
from ..footprint import measure as fp
from ..footprint import report as fp_report
from ..footprint.chart import svg_chart
from ..inspector.page import ROBOT_STEPS, window
from ..models.export import FORMATS
from ..compat.switch import VARIANTS as COMPAT_VARIANTS
from ..targets.kilobot import LIMITS as KILOBOT_LIMITS
from .options import SEED, FiniteFloat, OneLineErrors

vm = python_vm()


def reports_errors(command: Callable[..., Any]) -> Callable[..., Any]:
    """Turn InputError into the one-line message and exit status 2; what the verb reads, in
    all the API calls it makes, no output of it may replace (boundary.errors.verb_scope)."""
    @functools.wraps(command)
    def wrapper(*args: Any, **kwargs: Any) -> Any:
        try:
            with verb_scope():
                return command(*args, **kwargs)
        except api.InputError as exc:
            terminal.fail(exc)
    return wrapper


def _warn(warnings: Any) -> None:
    for warning in warnings:
        terminal.warn(warning)


def max_states_option(what: str) -> Callable[[Callable[..., Any]], Callable[..., Any]]:
    """``--max-states``, the state budget of the verbs whose work can grow exponentially
    (docs/limits.md); ``what`` says where the verb spends it."""
    return click.option("--max-states", default=api.DEFAULT_MAX_STATES, show_default=True, type=click.IntRange(1),
                        help="Product states (and %d transitions per state) %s may explore; past them it stops "
                             "with a one-line error." % (api.TRANSITIONS_PER_STATE, what))


@click.group(cls=OneLineErrors, context_settings={"help_option_names": ["-h", "--help"]})
@click.version_option(__version__, prog_name="swarmvm")
@click.pass_context
def main(ctx: click.Context) -> None:
    """Compile synthesised supervisors into table-driven VMs for swarm robots."""
    ctx.call_on_close(end_verbs_on_sigterm())


@main.command()
@click.argument("files", nargs=-1, required=True)
@click.option("--properties", is_flag=True,
              help="Check each set's design instead of printing the size table: deadlocks, lost control, "
                   "dead events, ignored inputs, confluence.")
@click.option("--all", "all_findings", is_flag=True,
              help="With --properties: list every finding (without it, the first 3 of each check).")
@click.option("-t", "--target", type=click.Choice(sorted(api.TARGETS)),
              help="Also apply this target's own rules, as gen would (nothing is written).")
@click.option("--name", help="With --target: the model name gen would be given (default: the file stem).")
@max_states_option("the design checks (--properties)")
@reports_errors
def check(files: tuple[str, ...], properties: bool, all_findings: bool, target: str | None, name: str | None,
          max_states: int) -> None:
    """Validate supervisors (.yaml, .c, .h, .xml, .xmd, .nza, .gen) or table images (.svm) and print their sizes.

    Counts are as read from each file, summed over its local supervisors; bytes is the file
    size. A .svm image is checked (magic, version, checksum) and its counts printed."""
    if all_findings and not properties:
        raise click.BadOptionUsage("--all", "only with --properties")
    if properties:
        for report in api.check_properties(files, max_states=max_states, all_findings=all_findings):
            terminal.lines(report)
        return
    rows, warnings = api.check(files, target=target, name=name)
    _warn(warnings)
    terminal.line("| file | events | supervisors | states | transitions | bytes |")
    terminal.line("|---|---|---|---|---|---|")
    for r in rows:
        terminal.line("| %s | %d | %d | %d | %d | %d |" % (markdown(r.file), r.events, r.supervisors, r.states,
                                                           r.transitions, r.bytes))


@main.command()
@click.argument("inputs", nargs=-1, required=True)
@click.option("-o", "--output", required=True, help="The .svm file to write.")
@click.option("--no-names", is_flag=True, help="Leave event names out (callbacks then bind by index).")
@reports_errors
def pack(inputs: tuple[str, ...], output: str, no_names: bool) -> None:
    """Write the portable table image of a supervisor: the .svm file every runtime loads."""
    compiled = api.write_image(inputs, output, names=not no_names)
    _warn(compiled.model.warnings)
    terminal.line("%s: %d bytes" % (output, len(compiled.packed_image)))     # what write_image wrote


@main.command()
@click.argument("inputs", nargs=-1, required=True)
@click.option("-t", "--target", type=click.Choice(sorted(api.TARGETS)), required=True,
              help="The robot or language to generate for.")
@click.option("-o", "--output", "outdir", required=True, help="Directory to write into.")
@click.option("--name", help="Model name for generated files (default: the input's file stem; for a "
                             "supervisor.yaml, its folder's name).")
@click.option("--learned-check", "learned", multiple=True, metavar="YES/NO",
              help="Decide the uncontrollable pair YES/NO (e.g. capableTask/notCapableTask) with an "
                   "online classifier on features the application supplies. Repeatable.")
@click.option("--sct-header", metavar="NAME.h",
              help="C targets: also write NAME.h, the header a published program on Nadzoru's C API includes "
                   "(e.g. sct_work_and_charge.h): EV_x, NUM_EVENTS, NUM_SUPERVISORS, the SCT_* prototypes.")
@reports_errors
def gen(inputs: tuple[str, ...], target: str, outdir: str, name: str | None, learned: tuple[str, ...],
        sct_header: str | None) -> None:
    """Generate a target's VM sources: table image, tables, glue and a controller skeleton.

    INPUTS is a supervisor.yaml (Nadzoru 2), Nadzoru's C tables (.c, .h) or a table image
    (.svm), or one or more automata that make one set of local supervisors, one each:
    Nadzoru 2 XML (.xml), IDES (.xmd), Nadzoru (.nza) or libFAUDES (.gen). Generated files are
    rewritten on every run; a controller skeleton that already exists is never overwritten,
    and when its callbacks no longer match the model a warning names them and a fresh
    skeleton is written beside it as <file>.new."""
    result = api.generate_target(inputs, target, outdir, name=name, learned=learned, sct_header=sct_header)
    if name is None and result.compiled.stem != Path(inputs[0]).stem:
        terminal.note("named the model %s after the folder of %s (give --name to choose another)"
                      % (result.compiled.name, inputs[0]))
    _warn(result.compiled.model.warnings)
    _warn(d.message() for d in result.drifts)
    for path in result.written:
        terminal.line(path)


@main.command()
@click.argument("inputs", nargs=-1, required=True)
@click.option("--steps", default=100, show_default=True, type=click.IntRange(1, 10 ** 7),
              help="Steps (lines) in the script.")
@click.option("--seed", default=1, show_default=True, type=SEED,
              help="Seed of the script's random draws: the same seed, the same script.")
@click.option("--density", default=0.25, show_default=True, type=FiniteFloat(0, 1),
              help="Chance that an uncontrollable event occurs in a step.")
@reports_errors
def script(inputs: tuple[str, ...], steps: int, seed: int, density: float) -> None:
    """Print a reproducible random event script for a supervisor."""
    for line in api.script_lines(inputs, steps, seed, density):
        terminal.line(line)


@main.command()
@click.argument("inputs", nargs=-1, required=True)
@click.option("--script", "script_path", required=True, type=click.Path(allow_dash=True),
              help="Event script: a line per step naming the uncontrollable events that occur (- for none), "
                   "as swarmvm script writes it; - reads it from standard input.")
@click.option("--seed", default=1, show_default=True, type=SEED,
              help="Seed of the VM's generator, which chooses among enabled controllable events.")
@click.option("--inputs", "input_mode", type=click.Choice(vm.INPUT_MODES), default="level", show_default=True,
              help="An uncontrollable event occurs in every step its check is true (level), or only in the "
                   "step it becomes true (edge).")
@click.option("--control", type=click.Choice(vm.CONTROL_MODES), default="after-inputs", show_default=True,
              help="A controllable event is chosen in every step, after its inputs (after-inputs), or only in a "
                   "step where no uncontrollable event occurred (if-quiet).")
@click.option("--policy", type=click.Choice(python_app().OPTION_POLICIES), default="uniform", show_default=True,
              help="How the VM chooses among enabled controllable events.")
@reports_errors
def trace(inputs: tuple[str, ...], script_path: str, seed: int, input_mode: str, control: str, policy: str) -> None:
    """Run the reference (Python) VM on an event script and print the canonical trace.

    INPUTS is a supervisor (.yaml, .xml...) or a table image (.svm)."""
    for line in api.trace(inputs, script_path, seed=seed, input_mode=input_mode, control=control, policy=policy):
        terminal.line(line)


@main.command()
@click.argument("elfs", nargs=-1, required=True, type=click.Path())
@click.option("--json", "json_path", type=click.Path(), help="Also write the report as JSON (a later run's --baseline).")
@click.option("--budget", "budget_path", type=click.Path(),
              help="TOML file of budgets per target and row (default: [tool.swarmvm.footprint] of ./pyproject.toml).")
@click.option("--baseline", "baseline_path", type=click.Path(),
              help="An earlier --json report: show each row's change in bytes and per cent.")
@click.option("--format", "report_format", type=click.Choice(["markdown", "junit"]), default="markdown",
              show_default=True, help="markdown: the table (changes first against a baseline); junit: JUnit XML.")
@click.option("--fail-on-growth", type=FiniteFloat(min=0), metavar="PCT",
              help="Exit with status 1 when a column of a row grew by more than PCT per cent on the baseline.")
@click.option("--chart", "chart_path", type=click.Path(), help="Also draw flash and RAM per row as an SVG file.")
@click.option("--runtime-sizes", is_flag=True, help="Also list the runtimes' source sizes (the project's own figures).")
@click.option("--kilobot-flash", default=KILOBOT_LIMITS.flash, show_default=True, type=click.IntRange(0),
              help="Flash a Kilobot image may use (bytes below the bootloader).")
@click.option("--kilobot-stack", default=KILOBOT_LIMITS.min_stack, show_default=True, type=click.IntRange(0),
              help="SRAM a Kilobot image must leave for the stack (of {:,} bytes).".format(KILOBOT_LIMITS.sram))
@click.option("--vm-limit", default=fp.VM_KPI, show_default=True, type=click.IntRange(0),
              help="Bytes the VM (core + tables, flash + RAM) may take: the seed's KPI.")
@click.option("--indirect", multiple=True, metavar="CALLER=TARGET,...",
              help="What an indirect call in CALLER may reach, for the worst-case stack (repeatable), added to "
                   "what the image's target declares (a generated Kilobot project needs none); an undeclared one "
                   "makes the bound unknown, which fails the checks of the stack.")
@click.option("--frame", "frames", multiple=True, metavar="FUNCTION=BYTES",
              help="The stack frame of a function without a -fstack-usage entry whose code does not make it "
                   "certain (a library built without the flag), return address included (repeatable).")
@click.option("--cycles", "cycles_path", type=click.Path(), metavar="SCRIPT",
              help="Run each image with this event script (Kilobot: simavr, CPU cycles; CapBot: QEMU, "
                   "instructions): mean and worst per step (checks answered through the dispatch declared "
                   "with --indirect svm_step=...).")
@click.option("--symbols", "symbols", type=click.IntRange(1), metavar="N",
              help="With --baseline: also list each row's N largest section changes and N largest symbol "
                   "changes, read from the ELF (as Bloaty's -d sections,symbols).")
@reports_errors
def footprint(elfs: tuple[str, ...], json_path: str | None, budget_path: str | None, baseline_path: str | None,
              report_format: str, fail_on_growth: float | None, chart_path: str | None, runtime_sizes: bool,
              kilobot_flash: int, kilobot_stack: int, vm_limit: int, indirect: tuple[str, ...],
              frames: tuple[str, ...], cycles_path: str | None, symbols: int | None) -> None:
    """Report flash, static RAM and worst-case stack of linked VM images, split into VM core,
    tables and application.

    ELFS are linked images named <supervisor>.elf; the target comes from the machine (AVR:
    kilobot, ARM: capbot); the stack from the -fstack-usage files beside them. Prints Markdown or
    JUnit XML; exits with status 1 and one line per row over a limit or
    budget or whose figure for one is unknown, or grown past --fail-on-growth or changed in a way
    it cannot judge."""
    if fail_on_growth is not None and baseline_path is None:
        raise click.BadOptionUsage("--fail-on-growth", "growth is measured against a --baseline: give one")
    if symbols is not None and baseline_path is None:
        raise click.BadOptionUsage("--symbols", "the section and symbol changes are against a --baseline: give one")
    if budget_path is None and Path(fp_budget.PYPROJECT).is_file():
        budget_path = fp_budget.PYPROJECT
    limits = fp.Limits(vm=vm_limit).replaced("kilobot", flash=kilobot_flash, min_stack=kilobot_stack)
    try:
        report = api.footprint_report(list(elfs), budget=budget_path, baseline=baseline_path,
                                      fail_on_growth=fail_on_growth, limits=limits, indirect=indirect,
                                      cycles=cycles_path, frames=frames, symbols=symbols)
    except fp.FootprintError as exc:
        terminal.fail(exc)
    # first, as one transaction: a file that cannot be written ends the command before any output
    # and leaves the other unwritten
    outputs: tuple[tuple[str, str | None, Callable[[], str]], ...] = (
        ("--json", json_path, lambda: fp_report.json_report(report, runtime_sizes)),
        ("--chart", chart_path, lambda: svg_chart(report)))
    files = {option: (Path(path).absolute(), text) for option, path, text in outputs if path}
    if files:
        folder = Path(os.path.commonpath([target.parent for target, _ in files.values()]))
        write_outputs(folder, {str(target.relative_to(folder)): (text().encode(), False)
                               for target, text in files.values()}, option=", ".join(files))
    if report_format == "junit":
        terminal.lines(fp_report.junit_report(report).removesuffix("\n"))
    else:
        terminal.lines(fp_report.markdown_report(report, runtime_sizes).removesuffix("\n"))
    failures = report.failures()
    for failure in failures:
        terminal.message("footprint", failure)
    if failures:
        sys.exit(1)


@main.command()
@click.argument("models", nargs=-1, required=True)
@click.option("--script", "script_path", type=click.Path(),
              help="Synthesis script, one statement a line, e.g. Nadzoru 2's script.txt or Nadzoru's script.lua.")
@click.option("-e", "--statement", "statements", multiple=True, metavar="STATEMENT",
              help="A script statement, e.g. 'S = SupC(G, K)' (repeatable; instead of --script).")
@click.option("--export", "exports", multiple=True, metavar="NAME",
              help="A result that joins the output set, in order (repeatable; default: the script's export, "
                   "else every SupC result).")
@click.option("--minimise", is_flag=True, help="Minimise each output supervisor (libFAUDES StateMin).")
@click.option("-f", "--format", "fmt", type=click.Choice(["yaml", "gen"]), default="yaml", show_default=True,
              help="Write the supervisors as one Nadzoru 2 supervisor.yaml, or as libFAUDES .gen files.")
@click.option("-o", "--output", required=True,
              help="yaml: the supervisor.yaml to write; gen: a directory for one .gen per supervisor.")
@max_states_option("each Sync or SupC step, checked before libFAUDES runs it,")
@reports_errors
def synth(models: tuple[str, ...], script_path: str | None, statements: tuple[str, ...], exports: tuple[str, ...],
          minimise: bool, fmt: str, output: str, max_states: int) -> None:
    """Synthesise local modular supervisors from plants and specifications (libFAUDES).

    MODELS are automata (.xml, .xmd, .nza, .gen); the script names each by its file stem."""
    for path in api.synthesise_models(models, script_path, statements, exports, minimise, fmt, output,
                                      max_states=max_states):
        terminal.line(path)


@main.command()
@click.argument("a")
@click.argument("b")
@max_states_option("the comparison")
@reports_errors
def equiv(a: str, b: str, max_states: int) -> None:
    """Do supervisor sets A and B have the same events and the same conjunction language?

    A and B are supervisor files, automata, or directories of automata. Exit status 0 when
    equivalent; 1 with a shortest distinguishing event sequence when not."""
    same, report = api.equivalent(a, b, max_states=max_states)
    terminal.lines(report)
    if not same:
        sys.exit(1)


@main.command()
@click.argument("inputs", nargs=-1, required=True)
@click.option("-f", "--format", "fmt", type=click.Choice(FORMATS), required=True,
              help="yaml: Nadzoru 2 YAML; gen: libFAUDES; dot, svg: Graphviz pictures.")
@click.option("-o", "--output", required=True, help="yaml: the file to write; gen, dot, svg: a directory.")
@click.option("--name", help="Stem of the files written (default: the input's file stem).")
@click.option("--product-limit", default=200, show_default=True, type=click.IntRange(0),
              help="Draw the product of the supervisors only up to this many states.")
@max_states_option("finding the product to draw (when --product-limit is over it)")
@reports_errors
def export(inputs: tuple[str, ...], fmt: str, output: str, name: str | None, product_limit: int,
           max_states: int) -> None:
    """Write a supervisor set as Nadzoru 2 YAML (canonical), libFAUDES .gen, or Graphviz pictures."""
    compiled, written = api.export(inputs, fmt, output, name=name, product_limit=product_limit,
                                   max_states=max_states)
    _warn(compiled.model.warnings)
    for path in written:
        terminal.line(path)



@main.command()
@click.argument("supervisor")
@click.argument("traces", nargs=-1)
@click.option("-o", "--output", required=True, help="The HTML file to write.")
@click.option("--name", help="The page's title (default: the supervisor's file stem).")
@click.option("--compare", is_flag=True, help="Two traces of the same supervisors: find and show the first step "
                                              "where they differ, side by side.")
@click.option("--first-step", default=1, show_default=True, type=click.IntRange(1),
              help="The first step the page keeps in full (a page keeps %d robot-steps)."
                   % ROBOT_STEPS)
@reports_errors
def inspect(supervisor: str, traces: tuple[str, ...], output: str, name: str | None, compare: bool,
            first_step: int) -> None:
    """Write one offline HTML page replaying traces against the supervisors drawn.

    SUPERVISOR is a supervisor (.yaml, .xml...); each TRACE is a canonical trace of one robot
    (as swarmvm trace, the C host program, simavr or ARGoS print it)."""
    page = api.inspect(supervisor, traces, output, name=name, compare=compare, first_step=first_step)
    terminal.line(page.path)
    if page.kept < page.total:
        terminal.note("%d of %d robot-steps kept in full (the rest summarised): --first-step %d writes the next page"
                      % (page.kept, page.total, first_step + window(len(traces))))

@main.command("compat-switch")
@click.argument("project_dir")
@click.option("--variant", type=click.Choice(COMPAT_VARIANTS), help="The published sct.h the project "
              "uses (default: read from its src/utility/sct.h, else from its controllers' add_callback calls).")
@reports_errors
def compat_switch(project_dir: str, variant: str | None) -> None:
    """Switch an OpenSwarm ARGoS project from the published VM to swarmvm's sct.h.

    PROJECT_DIR holds src/: its CMakeLists.txt, utility/CMakeLists.txt and the controllers'
    includes of <utility/sct.h> are edited as they are. Prints the files changed; run again,
    it changes nothing and says so."""
    switch = api.compat_switch(project_dir, variant)
    for path in switch.written:
        terminal.line(path)
    if not switch.written:
        terminal.note("%s is switched already: nothing changed" % project_dir)
    elif switch.variant is not None:
        terminal.note("switched to swarmvm's sct.h (%s variant); packed at build time: %s; src/utility/sct.h "
                      "and sct.cpp are no longer built" % (switch.variant, ", ".join(switch.supervisors) or "none"))


@main.command("cmake-dir")
def cmake_dir() -> None:
    """Print the folder of swarmvm_argos.cmake and sct.h (what a CMake project includes)."""
    terminal.line(RUNTIME_CPP)


class StudyVerb(click.Group):
    """A verb of the studies (sim, sweep, plot, bounds), whose subcommands (one per study) live in
    swarmvm.studies and are imported only when the verb runs or lists them: the compiler's
    verbs, and ``swarmvm --help``, neither need the studies nor pay for importing them."""

    def _studies(self) -> dict[str, click.Command]:
        from ..studies.cli import SUBCOMMANDS
        return {command.name: command for command in SUBCOMMANDS[self.name] if command.name}

    def list_commands(self, ctx: click.Context) -> list[str]:
        return sorted(self._studies())

    def get_command(self, ctx: click.Context, cmd_name: str) -> click.Command | None:
        return self._studies().get(cmd_name)


@main.group(cls=StudyVerb)
def sim() -> None:
    """Run one trial of a study."""


@main.group(cls=StudyVerb)
def sweep() -> None:
    """Run a study's grid of trials (resumable; local processes or a Dask cluster)."""


@main.group(cls=StudyVerb)
def plot() -> None:
    """Draw a study's figures from sweep results."""


@main.group(cls=StudyVerb)
def bounds() -> None:
    """Print a study's theoretical bounds."""
