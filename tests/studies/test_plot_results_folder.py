"""`plot uav|energy RESULTS`: a folder without finished trials, or with the other study's, is one
line naming it and the sweep that writes such trials, exit status 2, nothing drawn. Before, an
empty folder drew nothing and exited 0 (uav) or ended in a KeyError traceback (energy), as did
the drone study's trials given to the energy plot."""

import shlex

import pytest
from click.testing import CliRunner

from swarmvm.cli.commands import main

QUICK_UAV = ["--rules", "least-confident", "--thresholds", "", "--taus", "20", "--runs", "1", "--no-progress",
             "--weeks", "1", "--week-s", "4000", "--drones", "3", "--accuracy-samples", "10"]


@pytest.mark.parametrize("study", ["uav", "energy"])
def test_a_folder_without_trials_is_one_line(study, tmp_path):
    results = tmp_path / "no trials; here"
    (results / "trials").mkdir(parents=True)
    result = CliRunner().invoke(main, ["plot", study, str(results), "-o", str(tmp_path / "img")])
    assert result.exit_code == 2 and result.output.count("\n") == 1, result.output
    assert result.output.endswith("%s: no finished trials in this folder (swarmvm sweep %s -o %s writes them)\n"
                                  % (results, study, shlex.quote(str(results))))
    assert not (tmp_path / "img").exists()


def test_the_other_studys_trials_are_one_line(tmp_path):
    results = tmp_path / "uav"
    assert CliRunner().invoke(main, ["sweep", "uav", "-o", str(results), *QUICK_UAV]).exit_code == 0
    result = CliRunner().invoke(main, ["plot", "energy", str(results), "-o", str(tmp_path / "img")])
    assert result.output == "swarmvm: error: energy: %s: these are not the trials of swarmvm sweep energy\n" % results
    assert result.exit_code == 2 and not (tmp_path / "img").exists()
