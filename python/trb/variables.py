"""The FMU's variables as the `trb` program packages them for one bearing.

A sweep names FMU inputs, parameters and outputs. Which names exist (the per-roller ones
depend on the bearing's roller count), their causality, type, unit and range are read from
the modelDescription.xml of the FMU that the same `trb` program packages for the sweep's
bearing (`trb fmu --bearing B --out TMP.fmu`, about half a second), so the names checked are
the names of the model that runs the cases.
"""

from __future__ import annotations

import subprocess
import tempfile
from dataclasses import dataclass
from pathlib import Path

from .errors import SweepError


@dataclass(frozen=True)
class Variable:
    name: str
    causality: str  # "parameter", "input", "output", ...
    type: str  # "Real", "Integer", "Enumeration", "Boolean"
    unit: str | None
    min: float | None
    max: float | None
    start: object


@dataclass(frozen=True)
class VariableTable:
    bearing: str
    variables: dict[str, Variable]

    def names(self, causality: str) -> list[str]:
        return [v.name for v in self.variables.values() if v.causality == causality]

    def get(self, name: str) -> Variable | None:
        return self.variables.get(name)


def _number(text):
    return None if text is None else float(text)


def read_fmu(path: Path, bearing: str) -> VariableTable:
    """The variable table of an FMU file (its modelDescription.xml, read by fmpy)."""
    from fmpy import read_model_description

    md = read_model_description(str(path))
    table = {}
    for v in md.modelVariables:
        table[v.name] = Variable(
            name=v.name,
            causality=v.causality,
            type=v.type,
            unit=getattr(v, "unit", None) or None,
            min=_number(getattr(v, "min", None)),
            max=_number(getattr(v, "max", None)),
            start=v.start,
        )
    return VariableTable(bearing=bearing, variables=table)


def package_table(trb: Path, bearing: str, field: str = "bearing") -> VariableTable:
    """Package the FMU of `bearing` (a preset name or an absolute bearing file path) with the
    program `trb` into a temporary directory and read its variables. A bearing the program
    refuses is a SweepError naming `field`."""
    with tempfile.TemporaryDirectory(prefix="trb-sweep-fmu-") as tmp:
        out = Path(tmp) / "TaperedRollerBearing.fmu"
        try:
            proc = subprocess.run(
                [str(trb), "fmu", "--bearing", bearing, "--out", str(out)],
                capture_output=True,
                text=True,
                timeout=300,
            )
        except OSError as e:
            raise SweepError("--trb", f"cannot run the trb program {trb}: {e}") from None
        if proc.returncode != 0:
            msg = (proc.stderr.strip() or proc.stdout.strip()).splitlines()
            raise SweepError(field, f"`trb fmu --bearing {bearing}` refused it: {' '.join(msg)}")
        return read_fmu(out, bearing)
