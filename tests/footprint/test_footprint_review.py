"""The report a reviewer needs (issue 36, point 3; docs/footprint.md, "Reading the report",
"Symbols", "JSON"): every row's figures before and after, change and per cent, budget and limit
with their margins, share of the robot's capacity ("capacity unknown" where the target's record
gives none); the JSON records each image's ELF and digest, commit, toolchain and section and
symbol sizes; ``--symbols N`` lists the N largest section and symbol changes, and fails closed,
in one line, when the baseline cannot give them. Before, a row showed only "after (+delta, +%)",
budget and margin only on failure, no capacity, no commit or toolchain, and there was no
--symbols (usage error)."""

import hashlib
import json
import re
import shutil
import subprocess

import pytest

from footprint_images import BALLAST_FLASH, BALLAST_RAM, elf, swarmvm_footprint
from swarmvm.footprint import measure as footprint
from swarmvm.footprint.symbols import commit_of, read_sections, toolchain_of

BUDGET = "[kilobot]\nflash = 13000\nram = 300\n"


@pytest.fixture(scope="module")
def baseline(build, tmp_path_factory):
    """The JSON report of the two energy_worker images as built: the main branch's."""
    path = tmp_path_factory.mktemp("review") / "main.json"
    result = swarmvm_footprint(elf(build, "kilobot", "energy_worker"), elf(build, "capbot", "energy_worker"),
                               "--json", path)
    assert result.returncode == 0, result.stderr
    return path


@pytest.fixture(scope="module")
def compared(build, larger, baseline):
    """The larger Kilobot image and the same CapBot one against it, with budgets, --symbols 4
    and the JSON: (Markdown, JSON)."""
    folder = baseline.parent
    (folder / "budget.toml").write_text(BUDGET)
    result = swarmvm_footprint(larger, elf(build, "capbot", "energy_worker"), "--baseline", baseline, "--budget",
                               folder / "budget.toml", "--symbols", "4", "--json", folder / "now.json")
    assert result.returncode == 0, result.stderr
    return result.stdout, json.loads((folder / "now.json").read_text())


def figures(markdown, row):
    """{figure: [cells]} of ``row``'s table under "Every figure"."""
    block = re.search(r"<summary>%s[^<]*</summary>\n\n(.*?)\n\n</details>" % re.escape(row), markdown, re.S).group(1)
    found = {}
    for line in block.splitlines()[2:]:
        cells = [c.strip() for c in line.strip("|").split("|")]
        found[cells[0]] = cells[1:]
    return found


def test_a_changed_row_shows_before_after_budget_limit_margins_and_capacity(build, larger, compared):
    markdown, _ = compared
    before, after = footprint.measure(elf(build, "kilobot", "energy_worker")), footprint.measure(larger)
    assert "<details open><summary>kilobot/energy_worker: changed</summary>" in markdown
    rows = figures(markdown, "kilobot/energy_worker")
    grown = after.flash.total - before.flash.total
    assert rows["flash (B)"] == [
        str(before.flash.total), str(after.flash.total), "+%d" % grown, "+%.2f %%" % (100 * grown / before.flash.total),
        "13000", "%+d (%.1f %%)" % (13000 - after.flash.total, 100 * (13000 - after.flash.total) / 13000),
        "28672", "%+d (%.1f %%)" % (28672 - after.flash.total, 100 * (28672 - after.flash.total) / 28672),
        "%.1f %% → %.1f %%" % (100 * before.flash.total / 28672, 100 * after.flash.total / 28672)]
    ram = rows["ram (B)"]
    assert ram[:3] == [str(before.ram.total), str(after.ram.total), "+%d" % BALLAST_RAM]
    assert ram[4:8] == ["300", "%+d (%.1f %%)" % (300 - after.ram.total, 100 * (300 - after.ram.total) / 300),
                        "1024", "%+d (%.1f %%)" % (1024 - after.ram.total, 100 * (1024 - after.ram.total) / 1024)]
    assert ram[8].endswith("→ %.1f %%" % (100 * after.ram.total / 2048))           # of the 2,048 B of SRAM
    assert rows["flash_core (B)"][2:6] == ["+0", "+0.00 %", "none", "—"]          # unchanged, no budget: shown
    assert rows["vm (B)"][-1] == "capacity unknown"                                # flash and RAM: a share of neither


def test_the_capbot_capacity_is_its_records_never_invented(build, compared):
    """The CapBot target's record gives the nRF52840's flash below the logic page and its RAM: the
    shares are of those, the VM figure's capacity unknown, and the note says which is which."""
    markdown, _ = compared
    rows = figures(markdown, "capbot/energy_worker")
    image = footprint.measure(elf(build, "capbot", "energy_worker"))
    assert rows["flash (B)"][-1] == "%.1f %%" % (100 * image.flash.total / 0xF3000)
    assert rows["ram (B)"][-1] == "%.1f %%" % (100 * image.ram.total / (256 * 1024))
    assert rows["vm (B)"][-1] == "capacity unknown"
    assert "- capbot: capacity: CapBot SRAM 262144 B, CapBot flash 995328 B; capacity unknown: VM is flash and RAM " \
           "together, a share of neither" in markdown


def test_symbols_lists_the_largest_section_and_symbol_changes(compared):
    markdown, _ = compared
    block = markdown[markdown.index("## The 4 largest section and symbol changes"):]
    assert "- capbot/energy_worker: no section or symbol changed" in block
    sections = re.findall(r"^\| (\.\w+) \| (\d+) \| (\d+) \| ([+-]\d+) \|", block, re.M)
    assert [s[0] for s in sections] == [".text", ".bss"] and int(sections[1][3]) == BALLAST_RAM
    symbols = re.findall(r"^\| ([^|]+?) \| (\.\w+) \| ([^|]+) \| ([^|]+) \| ([+-]\d+) \| ([^|]+) \|", block, re.M)
    assert symbols[:2] == [("ballast_flash (energy_worker_controller.c)", ".text", "—", str(BALLAST_FLASH),
                            "+%d" % BALLAST_FLASH, "new"),
                           ("ballast_ram", ".bss", "—", str(BALLAST_RAM), "+%d" % BALLAST_RAM, "new")]
    assert len(symbols) == 4


def test_the_json_records_the_elf_its_digest_commit_toolchain_and_sizes(larger, compared):
    _, data = compared
    image = next(i for i in data["images"] if i["target"] == "kilobot")
    assert image["elf"] == str(larger) and image["elf_sha256"] == hashlib.sha256(larger.read_bytes()).hexdigest()
    assert image["commit"] == {"sha": None, "why": "%s is not in a git work tree" % larger.parent}
    assert image["toolchain"] == {"versions": image["compiler"], "from": ".comment"} and image["compiler"]
    assert image["tables_sha256"] == hashlib.sha256(footprint.table_image(larger)).hexdigest()
    for each in data["images"]:                          # AVR and ARM (Thumb functions: bit 0 of their address)
        sections = each["sections"]
        assert sum(s["size"] for s in sections.values() if s["kind"] in ("flash", "both")) == each["flash"]["total"]
        assert sum(s["size"] for s in sections.values() if s["kind"] in ("ram", "both")) == each["ram"]["total"]
        for section in sections.values():                # the symbols and the bytes none covers make up each
            assert sum(section["symbols"].values()) == section["size"]
        assert sections[".text"]["symbols"]["svm_step"] > 0


def test_the_commit_is_the_work_trees_head_and_says_when_files_differ(build, tmp_path):
    """An ELF in a git work tree records its HEAD; a tracked file changed since is said; a tree
    without a commit and a folder in none record null with why, never a guess."""
    repo = tmp_path / "robot"
    repo.mkdir()
    assert commit_of(str(repo / "robot.elf")).why == "%s is not in a git work tree" % repo

    def git(*words):
        return subprocess.run(["git", "-C", str(repo), "-c", "user.name=t", "-c", "user.email=t@t", *words],
                              check=True, capture_output=True, text=True).stdout.strip()
    git("init", "-q")
    assert commit_of(str(repo / "robot.elf")).why == "the git work tree of %s has no commit yet" % repo
    source = elf(build, "kilobot", "energy_worker")
    for built in source.parent.iterdir():                # the ELF and the .su files its stack needs
        if built.suffix in (".elf", ".su"):
            shutil.copy(built, repo / built.name)
    (repo / "controller.c").write_text("int x;\n")
    git("add", "controller.c")
    git("commit", "-q", "-m", "one")
    result = swarmvm_footprint(repo / source.name, "--json", tmp_path / "r.json", cwd=tmp_path)
    assert result.returncode == 0, result.stderr
    recorded = json.loads((tmp_path / "r.json").read_text())["images"][0]["commit"]
    assert recorded == {"sha": git("rev-parse", "HEAD"), "modified": False}
    assert "| %s (modified)" % recorded["sha"][:12] not in result.stdout and recorded["sha"][:12] in result.stdout
    (repo / "controller.c").write_text("int x, y;\n")
    assert commit_of(str(repo / source.name)).modified


def test_without_a_comment_section_the_toolchain_is_the_installed_compilers_said_so(build, tmp_path):
    stripped = tmp_path / "energy_worker.elf"
    subprocess.run(["avr-objcopy", "--remove-section", ".comment", str(elf(build, "kilobot", "energy_worker")),
                    str(stripped)], check=True)
    measured = footprint.measure(stripped)
    assert measured.compiler == ()
    toolchain = toolchain_of(measured)
    version = subprocess.run(["avr-gcc", "--version"], capture_output=True, text=True).stdout.splitlines()[0]
    assert toolchain.versions == (version,) and toolchain.source.startswith("avr-gcc --version (installed")


def test_symbols_without_a_baseline_is_one_line():
    result = swarmvm_footprint("missing.elf", "--symbols", "5")
    assert result.returncode == 2 and result.stderr == (
        "swarmvm: error: --symbols: the section and symbol changes are against a --baseline: give one\n")


def test_a_baseline_without_sizes_reads_its_elf_or_fails_closed_in_one_line(build, baseline, tmp_path):
    """An older baseline holds no sizes: --symbols reads them from the ELF it names while that is
    the file it measured (same digest); once it is gone, one line naming the key, status 2."""
    data = json.loads(baseline.read_text())
    for image in data["images"]:
        del image["sections"]
    old = tmp_path / "old.json"
    old.write_text(json.dumps(data))
    image = elf(build, "kilobot", "energy_worker")
    same = swarmvm_footprint(image, "--baseline", old, "--symbols", "2")
    assert same.returncode == 0 and "- kilobot/energy_worker: no section or symbol changed" in same.stdout, same.stderr
    data["images"][1]["elf"] = str(tmp_path / "gone.elf")
    old.write_text(json.dumps(data))
    gone = swarmvm_footprint(image, "--baseline", old, "--symbols", "2")
    assert gone.returncode == 2 and gone.stdout == "" and gone.stderr == (
        "swarmvm: error: %s: images[1].sections: --symbols cannot compare kilobot/energy_worker: it records no section "
        "or symbol sizes, and its ELF %s is gone (write the baseline again with this swarmvm)\n" % (old, tmp_path / "gone.elf"))


def test_read_sections_refuses_a_file_that_is_not_the_one_measured(build):
    with pytest.raises(footprint.FootprintError, match="changed while it was read"):
        read_sections(str(elf(build, "kilobot", "energy_worker")), "0" * 64)


def test_every_sized_symbol_binutils_lists_is_read_at_odd_addresses_too(build):
    """Every address of a sized function or object that avr-readelf lists in an AVR image has a
    symbol in read_sections (of aliases, several names at one address of one section, one). The
    reader once cleared bit 0 of every address, right only for an ARM function's Thumb bit: on AVR
    it took an object at an odd address for an alias of the one before it and dropped it
    (ballast_ram, rx_msg, kilo_irlow); the VM-core figure reads the same walk."""
    path = elf(build, "kilobot", "energy_worker")
    sections = read_sections(str(path))
    listed = {name.split(" (")[0] for section in sections.values() for name in section.symbols}
    out = subprocess.run(["avr-readelf", "-sW", str(path)], capture_output=True, text=True, check=True)
    by_address: dict[tuple[str, int], set[str]] = {}
    for fields in (line.split() for line in out.stdout.splitlines()):
        if len(fields) == 8 and fields[3] in ("FUNC", "OBJECT") and fields[6].isdigit() and int(fields[2]) > 0:
            by_address.setdefault((fields[6], int(fields[1], 16)), set()).add(fields[7])
    assert any(address % 2 for _, address in by_address), "no odd address in the image: the case is not tested"
    assert [names for names in by_address.values() if not names & listed] == []
