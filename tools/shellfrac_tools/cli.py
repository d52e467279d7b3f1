"""How a command-line script stops on a problem it cannot go on from."""
import os
import sys


def program():
    """The running script's file name (e.g. fracture_summary.py)."""
    return os.path.basename(sys.argv[0]) if sys.argv and sys.argv[0] else "shellfrac tool"


def fail(message):
    """Prints `<script>: <message>` on stderr and exits with 1."""
    sys.stderr.write("%s: %s\n" % (program(), message))
    sys.exit(1)


def note(message):
    """Prints `<script>: note: <message>` on stderr (something the user should know; the script goes on)."""
    sys.stderr.write("%s: note: %s\n" % (program(), message))
