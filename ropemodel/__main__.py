"""``python -m ropemodel`` runs the command line."""

from ropemodel.cli import run_console

run_console()
