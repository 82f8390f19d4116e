"""Run the command line with `python -m scriptc`."""

from __future__ import annotations

from scriptc.cli import main

main()
