import sys

from rotorcosim.master.cli.program import main

sys.exit(main())
