"""``python -m dhfield.cli``."""
import sys

from . import main

sys.exit(main())
