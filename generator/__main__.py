"""``python -m swarmvm``: the same command line as the ``swarmvm`` script."""

from .cli import main

main(prog_name="swarmvm")
