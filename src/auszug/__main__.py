"""``python -m auszug``: the same as the ``auszug`` console script."""

import sys

from auszug.cli import main

sys.exit(main())
