"""The one error a user sees for a bad sweep: it names the offending field.

`trb-sweep` prints `trb-sweep: error: field `grid.Fy`: ...` (or `option `--workers`: ...`) and
exits with code 2 (as `trb simulate` does for a bad scenario), never with a traceback.
"""

from __future__ import annotations


class SweepError(Exception):
    """A sweep file, option or program that cannot be used; `field` names where."""

    def __init__(self, field: str, message: str):
        kind = "option" if field.startswith("--") else "field"
        super().__init__(f"{kind} `{field}`: {message}" if field else message)
        self.field = field
        self.message = message
