"""``python3 -m freeplay run|suite …``: ``freeplay run|suite`` with every option, and Python policies
(``--set robot.policy=python:MODULE:CLASS``, MODULE found on PYTHONPATH)."""

import sys

from . import _freeplay

USAGE = """usage: python3 -m freeplay run SCENARIO [options]
       python3 -m freeplay suite SUITE [options]
The options are those of `freeplay run|suite` (python3 -m freeplay run --help); robot.policy may name a Python
policy, python:MODULE:CLASS (docs/python.md)."""


def main(argv=None):
    """Runs the command line ``argv`` (default: sys.argv[1:]); returns the exit status."""
    argv = list(sys.argv[1:] if argv is None else argv)
    if not argv or argv[0] in ("-h", "--help"):
        print(USAGE)
        return 0 if argv else 2
    if argv[0] not in ("run", "suite", "--version"):
        print(f"python3 -m freeplay: unknown command '{argv[0]}' (allowed: run, suite)\n{USAGE}", file=sys.stderr)
        return 2
    sys.stdout.flush()
    return _freeplay._cli_main(["python3 -m freeplay"] + argv)


if __name__ == "__main__":
    sys.exit(main())
