"""scriptc: compile a robot screenplay into one deterministic timeline and perform it in sync."""

from __future__ import annotations

__version__ = "0.1.0"
