"""``python -m pywarp`` is the ``pywarp`` command."""
import sys

from .cli import main

sys.exit(main())
