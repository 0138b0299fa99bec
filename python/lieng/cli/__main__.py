"""``python -m lieng.cli``: the same as the ``lieng`` command."""

import sys

from lieng.cli.parser import main

sys.exit(main())
