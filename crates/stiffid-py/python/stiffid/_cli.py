"""The ``stiffid`` command installed with the Python package (the wheel's console script).

It runs the same command-line program as the Rust ``stiffid`` binary, compiled into the package's
native module: same options, same outputs, same exit codes (0 success, 1 a gate the result failed, 2 bad
input). ``python -m stiffid`` runs it too.
"""

import signal
import sys


def main() -> None:
    """Run ``stiffid`` with this process's arguments; never returns (exits with its code)."""
    # Ctrl-C ends the command at once, as it ends the binary: Python's own handler would only
    # raise KeyboardInterrupt after the command returns.
    signal.signal(signal.SIGINT, signal.SIG_DFL)
    from ._stiffid import _cli

    _cli(sys.argv)


if __name__ == "__main__":
    main()
