"""The model tests' fixture: small automata written as libFAUDES .gen files."""

import pytest

from models.model_cases import gen_text


@pytest.fixture
def write_gen(tmp_path):
    """write_gen(name, transitions, controllable=(), ...) -> path of a new .gen file."""
    def write(name, transitions, controllable=(), **options):
        path = tmp_path / (name + ".gen")
        path.write_text(gen_text(transitions, controllable, **options))
        return path
    return write
