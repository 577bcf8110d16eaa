"""``python -m rotorcosim ...``: the same command line as ``rotorcosim ...`` (master/cli)."""
from rotorcosim.master.cli import main

raise SystemExit(main())
