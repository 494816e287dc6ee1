"""``python -m model``: the command line (see ``model.cli``)."""
from .cli import main

raise SystemExit(main())
