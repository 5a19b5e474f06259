"""`python3 -m rtcsim ARGS...` is `simulate ARGS...` (same options and exit codes)."""
import sys

from . import simulate

if __name__ == "__main__":
    sys.exit(simulate(sys.argv[1:]))
