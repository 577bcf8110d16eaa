"""Puts this checkout first on ``sys.path``: a benchmark run as ``python bench/NAME.py`` then measures this
checkout's rotorcosim, not an installed copy (Python puts the script's own folder, bench/, first, and the
checkout's root is not on the path). Imported by every benchmark before rotorcosim."""
import sys
from pathlib import Path

ROOT = str(Path(__file__).resolve().parents[1])
if sys.path[:1] != [ROOT]:
    sys.path.insert(0, ROOT)
