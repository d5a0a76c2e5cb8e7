"""Every Python writer escapes (issue 37, point 3), as every template does
(tests/boundary/test_template_filters.py).

The check (tests/boundary/python_writers.py, whose docstring defines a write, a writer function
and an escaped value) reads every module of generator/ and studies/ as a syntax tree, finds the
functions whose text reaches the output layer (``write_outputs``), and fails on a value
interpolated into that text through no function of swarmvm.boundary.escape. KNOWN_SAFE lists the
values it cannot see to be safe, each with the reason it holds no user text, or the place
downstream that escapes it; a synthetic module shows the check finds an unescaped write (the
issue's own example: a file name written raw into a ``.gen`` comment)."""

from pathlib import Path

from boundary.python_writers import check_source, load_tree, unescaped, writer_functions

ROOT = Path(__file__).resolve().parents[2]
FOLDERS = ("generator", "studies")

_MESSAGE = "message text (a budget's or a baseline's key, a figure): printed through swarmvm.boundary.terminal, " \
           "and in the report's Markdown and JUnit through report.py's markdown() / html()"
_MODEL_NAME = "a model name: validated as an identifier by the naming rule before any file is named " \
              "(swarmvm.compiler.naming), and a file name, not file content"
_PACKAGE = "the package's own constant (its version, a column's label, a CSS class of the chart's fixed set)"
_NUMBERS = "numbers the checker cannot see as numbers (state indices, digests' hex)"
_BY_CALLER = "escaped as a whole by its caller: %s"
_LATER = "a line of the list %s, escaped as a whole where it is written (markdown(line))"
# (module, function, value as written): why it holds no user text, or where it is escaped.
KNOWN_SAFE: dict[tuple[str, str, str], str] = {
    ("generator/compat/switch.py", "_drop_token", "word"): "a token of the project's own build file, put back as read",
    ("generator/compat/switch.py", "_replace_token", "re.escape(token)"): "a regular expression, not output text",
    ("generator/footprint/budget.py", "_bounds", "column"): _MESSAGE,
    ("generator/footprint/budget.py", "_bounds", "key"): _MESSAGE,
    ("generator/footprint/budget.py", "_limit_checks", "robot.robot"): _MESSAGE,
    ("generator/footprint/budget.py", "checks", "column"): _MESSAGE,
    ("generator/footprint/budget.py", "checks", "unit"): _MESSAGE,
    ("generator/footprint/budget.py", "parse_budgets", "prefix[:depth + 1]"): _MESSAGE,
    ("generator/footprint/budget.py", "parse_budgets", "prefix + (target,)"): _MESSAGE,
    ("generator/footprint/budget.py", "parse_budgets", "key"): _MESSAGE,
    ("generator/footprint/budget.py", "parse_budgets", "supervisor"): _MESSAGE,
    ("generator/footprint/chart.py", "_row", "COLUMN[column].label"): _PACKAGE,
    ("generator/footprint/chart.py", "_row", "kind"): _PACKAGE + ": 'budget' or 'limit' (budget._bounds's keys)",
    ("generator/footprint/chart.py", "svg_chart", "COLUMN[column].label"): _PACKAGE,
    ("generator/footprint/chart.py", "svg_chart", "part"): _PACKAGE + ": PARTS",
    ("generator/footprint/cycles.py", "script_masks", "names[e]"): "event names: validated identifiers (the image's)",
    ("generator/footprint/cycles.py", "script_masks", "script"): _MESSAGE + " (the sidecar an error names)",
    ("generator/footprint/delta.py", "_change", "(after.script_sha256 or '')[:12]"): _NUMBERS,
    ("generator/footprint/delta.py", "_change", "before.script_sha256[:12]"): _NUMBERS,
    ("generator/footprint/delta.py", "_image_row", "key"): _MESSAGE,
    ("generator/footprint/delta.py", "growth", "c.column"): _MESSAGE,
    ("generator/footprint/delta.py", "growth", "c.text()"): _MESSAGE,
    ("generator/footprint/delta.py", "growth", "(c.transition() for c in judged)"): _MESSAGE,
    ("generator/footprint/delta.py", "growth", "removed[delta.row.target]"): _MESSAGE,
    ("generator/footprint/stack.py", "measure_stack", "Path(elf).name"): _MESSAGE,
    ("generator/footprint/stack.py", "measure_stack", "architecture(target).objdump"): _MESSAGE,
    ("generator/footprint/stack.py", "measure_stack", "exc.stderr.strip().splitlines()[-1:]"): _MESSAGE,
    ("generator/footprint/stack.py", "su_files", "elf.name"): "a glob pattern, not output text",
    ("generator/inspector/page.py", "_drawings", "title"): "passed to supervisor_dot, which writes it with dot_string",
    ("generator/models/export.py", "_flat", "(str(v) for v in values)"): "integers (flags, indices, states)",
    ("generator/models/export.py", "export_files", "name"): _MODEL_NAME,
    ("generator/models/export.py", "gen_files", "name"): _MODEL_NAME,
    ("generator/models/pictures.py", "_graph", "lines"): "the lines the function built, each through dot_string",
    ("generator/models/pictures.py", "picture_files", "name"): _MODEL_NAME,
    ("generator/footprint/report.py", "_budget_change", "column"): _PACKAGE + ": a budget column's key (COLUMNS)",
    ("generator/footprint/report.py", "_budget_change", "unit"): _PACKAGE + ": a column's unit",
    ("generator/footprint/report.py", "_cells", "change.text()"): _NUMBERS + ": a change's figures, delta and per cent",
    ("generator/footprint/report.py", "_checks_section", "unit"): _PACKAGE + ": a column's unit",
    ("generator/footprint/report.py", "_checks_section", "check.status"): _PACKAGE + ": 'passed', 'failed' or 'skipped'",
    ("generator/footprint/report.py", "_rows_section", "d.old_name.partition('/')[2]"): _BY_CALLER % "a name cell, through markdown() in _table",
    ("generator/footprint/report.py", "_table", "(c.label for c in columns)"): _PACKAGE,
    ("generator/footprint/report.py", "_table", "[markdown(n) for n in names] + figures"): "the names through markdown(); the figure cells are _cells' numbers",
    ("generator/footprint/report.py", "markdown_report", "r.robot"): _PACKAGE + ": a robot's name in its target record",
    ("generator/footprint/report.py", "markdown_report", "d.row.name"): _LATER % "changed",
    ("generator/footprint/report.py", "markdown_report", "c.message"): _LATER % "skipped",
    ("generator/footprint/report.py", "markdown_report", "c.row.name"): _LATER % "skipped",
    ("generator/footprint/report.py", "markdown_report", "key"): _LATER % "unknown",
    ("generator/footprint/report.py", "markdown_report", "row.name"): _LATER % "unknown",
    ("generator/footprint/report.py", "markdown_report", "why"): _LATER % "unknown",
    ("generator/footprint/report.py", "markdown_report", "name"): _PACKAGE + ": a runtime file's name (source_sizes, SEED_KPI_SOURCE)",
    ("generator/models/pictures.py", "product_dot", "map(str, v)"): _NUMBERS,
    ("generator/targets/__init__.py", "copy_banner", "__version__"): _PACKAGE,
    ("generator/targets/__init__.py", "generate", "name"): _MODEL_NAME,
    # The footprint's Markdown report: parts escaped by the function that places them.
    ("generator/footprint/delta.py", "_total", "COLUMN[column].label"): _PACKAGE,
    ("generator/footprint/delta.py", "_total", "Change(column, sum((c.old or 0 for c in both)), "
                                               "sum((c.new or 0 for c in both))).text()"): _NUMBERS,
    ("generator/footprint/delta.py", "summary", "baseline.file"): _BY_CALLER % "markdown(summary(...)), report._rows_section",
    ("generator/footprint/delta.py", "summary", "s"): "a status of the fixed set (STATUS_ORDER)",
    ("studies/energy_replenishment/trial.py", "vm_trace_files", "kinds[robot.rstrip('0123456789')]"):
        "a supervisor name of the study's own (experiment.robot_kinds)",
    ("studies/energy_replenishment/trial.py", "vm_trace_files", "robot"):
        "an ARGoS robot id of the study's own experiment file (w0, c3), a file name",
    ("studies/energy_replenishment/trial.py", "vm_trace_files", "rest"):
        "a VM trace line as the runtime prints it: data swarmvm inspect parses, a format without escapes",
    ("studies/energy_replenishment/trial.py", "vm_trace_files", "rows"): "the trace lines above",
}


def test_every_value_a_python_writer_writes_is_escaped():
    modules = load_tree(ROOT, FOLDERS)
    found = unescaped(modules)
    raw = ["%s:%d: %s writes %s unescaped" % (u.module, u.line, u.function, u.value) for u in found
           if (u.module, u.function, u.value) not in KNOWN_SAFE]
    assert not raw, "values written through no escaping function:\n" + "\n".join(raw)


def test_every_known_safe_entry_is_still_needed():
    """An entry no writer needs any more would let a later raw write through unseen."""
    found = {(u.module, u.function, u.value) for u in unescaped(load_tree(ROOT, FOLDERS))}
    assert not set(KNOWN_SAFE) - found


def test_the_writers_found_include_every_kind_of_output():
    """The search reaches the writers of every verb and study that writes text: export's formats,
    the pictures, the inspector's page, the footprint's JSON, chart, Markdown and JUnit (printed),
    the studies' tables."""
    writers = writer_functions(load_tree(ROOT, FOLDERS))
    for wanted in [("generator/models/export.py", "to_gen"), ("generator/models/export.py", "to_yaml"),
                   ("generator/models/pictures.py", "supervisor_dot"), ("generator/footprint/chart.py", "svg_chart"),
                   ("studies/drone_delivery/plots.py", "summary_markdown"), ("generator/inspector/page.py", "page_html"),
                   ("generator/footprint/report.py", "markdown_report"), ("generator/footprint/report.py", "junit_report"),
                   ("generator/footprint/report.py", "json_report")]:
        assert wanted in writers, wanted


# The example: the input's file name written raw into a .gen comment, where a newline in
# it starts a libFAUDES directive.
UNESCAPED_WRITER = '''
from swarmvm.boundary.output import write_outputs
from swarmvm.boundary.escape import gen_string, comment

def to_gen(model, name):
    header = "%% written by swarmvm from %s" % model.source
    return "\\n".join(['<Generator name=%s>' % gen_string(name), header, "% public: " + " ".join(model.events)])

def escaped_gen(model, name):
    return "%% written by swarmvm from %s, %d states\\n" % (comment(model.source), len(model.states))

def export(model, out):
    write_outputs(out, {"x.gen": (to_gen(model, "x").encode(), False), "y.gen": (escaped_gen(model, "y").encode(), False)})
'''


def test_the_check_finds_an_unescaped_write_in_a_synthetic_module():
    found = {(u.function, u.value) for u in check_source(UNESCAPED_WRITER)}
    assert found == {("to_gen", "model.source"), ("to_gen", "model.events")}


def test_a_message_is_not_a_write():
    """An exception's text is escaped where it is printed (swarmvm.boundary.terminal)."""
    source = UNESCAPED_WRITER.replace('    header = "%% written by swarmvm from %s" % model.source\n',
                                      '    header = ""\n    raise ValueError("%s: bad" % model.source)\n')
    assert {(u.function, u.value) for u in check_source(source)} == {("to_gen", "model.events")}
