"""``python -m swarmvm``: the same command line as the ``swarmvm`` script."""

from .cli.commands import main

main(prog_name="swarmvm")
