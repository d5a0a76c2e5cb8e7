"""Learning tests import the runtime modules (runtime_py/) the way a robot does: by file name."""

import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]
sys.path.insert(0, str(ROOT / "runtime_py"))
