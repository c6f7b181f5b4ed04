"""``python -m stiffid``: the ``stiffid`` command (see ``stiffid._cli``)."""

from ._cli import main

main()
