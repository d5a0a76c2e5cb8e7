"""The simavr Kilobot board, by the name the tests, the swap demo and ``make kilobot-board`` use
(``import board`` from firmware/kilobot/). Its code and C source are the package's,
``swarmvm.footprint.kilobot_board`` (generator/footprint/kilobot_board/), so that an installed swarmvm has them for
``swarmvm footprint --cycles``; this module only points there.

    python3 firmware/kilobot/board.py      prints the board program's path (building it if need be)
"""

import sys

from swarmvm.footprint.kilobot_board import Run, board_path, run

__all__ = ["Run", "board_path", "run"]

if __name__ == "__main__":
    from kilolib_build import print_path       # beside this file: the script's folder is on sys.path
    sys.exit(print_path(board_path))
