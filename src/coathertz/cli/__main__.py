import sys

from coathertz.cli import main

sys.exit(main())
