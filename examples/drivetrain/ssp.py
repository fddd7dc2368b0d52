"""The drivetrain as an SSP 1.0 system: `SystemStructure.ssd` (committed, written by
`write_ssd`), packed with the two FMUs into `drivetrain.ssp` by `package_ssp`, and run in
libcosim (libcosimpy) by `run_libcosim` and in fmpy's SSP master by `run_fmpy`.

    python examples/drivetrain/ssp.py            # rewrite SystemStructure.ssd
    python examples/drivetrain/ssp.py --run      # package target/drivetrain/drivetrain.ssp, run libcosim

Both masters' fixed-step algorithms are Jacobi schemes (every component steps on the others'
outputs of the last communication point): the bearings' outputs at t + h then belong to the
shaft displacement the shaft computed for the load at t, one step behind the Gauss-Seidel
loop of drivetrain.py.
"""

from __future__ import annotations

import subprocess
import sys
import zipfile
from pathlib import Path
from xml.sax.saxutils import quoteattr

import numpy as np

HERE = Path(__file__).resolve().parent
sys.path.insert(0, str(HERE))
import drivetrain as dt  # noqa: E402

SSD = HERE / "SystemStructure.ssd"
SHAFT_SOURCE = "resources/Shaft.fmu"
BEARING_SOURCE = "resources/TaperedRollerBearing.fmu"


def connections() -> list[tuple[str, str, str, str]]:
    """(start element, start connector, end element, end connector)."""
    out = []
    for name in dt.BEARINGS:
        for d in dt.DISPLACEMENT:
            out.append(("shaft", f"{name}.{d}", name, d))
        out.append(("shaft", "speed", name, "speed"))
        for r in dt.REACTION:
            out.append((name, f"reaction.{r}", "shaft", f"{name}.reaction.{r}"))
        for s in dt.STIFFNESS:
            out.append((name, s, "shaft", f"{name}.{s}"))
        for c in dt.CONE:
            out.append((name, c, "shaft", f"{name}.{c}"))
    return out


def parameters() -> dict[str, dict[str, float | int]]:
    """Start values per component (the bearings in displacement causality, preloaded)."""
    shaft = dict(dt.SHAFT_PARAMETERS)
    bearing = {"causality": 1, "fidelity": 0, "displacement.x": shaft["preload.displacement"] / 2, "speed": shaft["shaft.speed"]}
    return {"shaft": shaft, "bearingA": dict(bearing), "bearingB": dict(bearing)}


def ssd_text() -> str:
    conns = connections()
    params = parameters()
    lines = [
        '<?xml version="1.0" encoding="UTF-8"?>',
        '<ssd:SystemStructureDescription xmlns:ssc="http://ssp-standard.org/SSP1/SystemStructureCommon"'
        ' xmlns:ssd="http://ssp-standard.org/SSP1/SystemStructureDescription"'
        ' xmlns:ssv="http://ssp-standard.org/SSP1/SystemStructureParameterValues"'
        ' name="Drivetrain" version="1.0"'
        ' generationTool="examples/drivetrain/ssp.py">',
        "  <!-- A shaft on two tapered roller bearings in an O arrangement (examples/drivetrain/README.md).",
        "       Written by examples/drivetrain/ssp.py: edit that, not this. -->",
        '  <ssd:System name="Drivetrain">',
        "    <ssd:Elements>",
    ]
    for element, source in [("shaft", SHAFT_SOURCE), ("bearingA", BEARING_SOURCE), ("bearingB", BEARING_SOURCE)]:
        lines.append(f'      <ssd:Component name="{element}" type="application/x-fmu-sharedlibrary" source="{source}">')
        lines.append("        <ssd:Connectors>")
        seen = set()
        for a, ca, b, cb in conns:
            for el, conn, kind in [(a, ca, "output"), (b, cb, "input")]:
                if el == element and conn not in seen:
                    seen.add(conn)
                    lines.append(f'          <ssd:Connector name={quoteattr(conn)} kind="{kind}"><ssc:Real/></ssd:Connector>')
        lines.append("        </ssd:Connectors>")
        lines.append("        <ssd:ParameterBindings>")
        lines.append("          <ssd:ParameterBinding>")
        lines.append("            <ssd:ParameterValues>")
        lines.append(f'              <ssv:ParameterSet version="1.0" name="{element}">')
        lines.append("                <ssv:Parameters>")
        for name, value in params[element].items():
            tag = "Integer" if isinstance(value, int) else "Real"
            lines.append(f'                  <ssv:Parameter name={quoteattr(name)}><ssv:{tag} value="{value!r}"/></ssv:Parameter>')
        lines.append("                </ssv:Parameters>")
        lines.append("              </ssv:ParameterSet>")
        lines.append("            </ssd:ParameterValues>")
        lines.append("          </ssd:ParameterBinding>")
        lines.append("        </ssd:ParameterBindings>")
        lines.append("      </ssd:Component>")
    lines.append("    </ssd:Elements>")
    lines.append("    <ssd:Connections>")
    for a, ca, b, cb in conns:
        lines.append(f"      <ssd:Connection startElement={quoteattr(a)} startConnector={quoteattr(ca)} endElement={quoteattr(b)} endConnector={quoteattr(cb)}/>")
    lines.append("    </ssd:Connections>")
    lines.append("  </ssd:System>")
    lines.append('  <ssd:DefaultExperiment startTime="0" stopTime="1"/>')
    lines.append("</ssd:SystemStructureDescription>")
    return "\n".join(lines) + "\n"


def write_ssd(path: Path = SSD) -> Path:
    path.write_text(ssd_text())
    return path


def build_integer_bearing_fmu(out: Path = dt.REPO / "target" / "fmu" / f"{dt.BEARING_PRESET}-integers.fmu") -> Path:
    """The bearing FMU with its Enumeration parameters declared as Integers (`trb fmu
    --enumerations-as-integers`: same value references, start values and ranges, the same
    binary). libcosim (libcosimpy 0.0.6) ignores Enumeration variables, so an SSP parameter
    set could not reach `causality` otherwise."""
    subprocess.run(
        ["cargo", "run", "--release", "--quiet", "--", "fmu", "--bearing", dt.BEARING_PRESET, "--enumerations-as-integers", "--out", str(out)],
        check=True,
        cwd=dt.REPO,
    )
    return out


def package_ssp(out: Path, bearing_fmu: Path | None = None, shaft_fmu: Path = dt.SHAFT_FMU) -> Path:
    """drivetrain.ssp: the committed SystemStructure.ssd, the shaft FMU and the bearing FMU,
    packaged with its Enumeration parameters declared as Integers (`build_integer_bearing_fmu`
    when not given)."""
    if bearing_fmu is None:
        bearing_fmu = build_integer_bearing_fmu()
    with zipfile.ZipFile(bearing_fmu) as z:
        if b"<Enumeration" in z.read("modelDescription.xml"):
            raise ValueError(f"{bearing_fmu} declares Enumerations, which libcosim ignores: package it with `trb fmu --enumerations-as-integers`")
    out.parent.mkdir(parents=True, exist_ok=True)
    with zipfile.ZipFile(out, "w", zipfile.ZIP_DEFLATED) as z:
        z.write(SSD, "SystemStructure.ssd")
        z.write(shaft_fmu, SHAFT_SOURCE)
        z.write(bearing_fmu, BEARING_SOURCE)
    return out


def run_libcosim(ssp: Path, stop: float = 1.0, step: float = 0.002) -> dict:
    """Run the SSP in libcosim's fixed-step (Jacobi) algorithm; the bearings' reactions and
    the mesh force after every step."""
    from libcosimpy.CosimExecution import CosimExecution
    from libcosimpy.CosimObserver import CosimObserver

    step_ns = int(round(step * 1e9))
    execution = CosimExecution.from_ssp_file(str(ssp), step_size=step_ns)
    observer = CosimObserver.create_last_value()
    assert execution.add_observer(observer=observer)
    index = {name: execution.slave_index_from_instance_name(name) for name in ["shaft", *dt.BEARINGS]}
    refs = {}
    for name, i in index.items():
        refs[name] = {v.name.decode(): v.reference for v in execution.slave_variables(i)}
    reaction_names = [f"reaction.{r}" for r in dt.REACTION]
    extra = ["frictionTorque", "life.L10", "life.L10r"]
    out = {"time": [], "reactions": [], "force": [], "extra": []}
    n = int(round(stop / step))
    for k in range(n):
        assert execution.step(step_count=1), f"libcosim step failed: {execution.status()}"
        out["time"].append((k + 1) * step)
        out["reactions"].append(
            [observer.last_real_values(slave_index=index[b], variable_references=[refs[b][v] for v in reaction_names]) for b in dt.BEARINGS]
        )
        out["extra"].append([observer.last_real_values(slave_index=index[b], variable_references=[refs[b][v] for v in extra]) for b in dt.BEARINGS])
        out["force"].append(observer.last_real_values(slave_index=index["shaft"], variable_references=[refs["shaft"][f"mesh.F{c}"] for c in "xyz"]))
    status = execution.status()
    assert status.current_time == n * step_ns, status
    del execution, observer
    return {k: np.array(v) for k, v in out.items()}


def run_fmpy(ssp: Path, stop: float = 1.0, step: float = 0.002) -> dict:
    """Run the SSP in fmpy's own SSP master (fmpy.ssp.simulation.simulate_ssp, a fixed-step
    Jacobi loop like libcosim's). It applies only the parameter set it is given, so the
    SSD's parameter bindings are collected into one; it starts every connection at 0 (the
    bearings see zero displacement and the shaft zero stiffness in the first step: the
    shaft holds, then its trust region keeps the first steps in range), so its first
    steps are a start-up transient. Rows at the end of each step, as run_libcosim's."""
    from fmpy.ssp.simulation import simulate_ssp
    from fmpy.ssp.ssd import Parameter, ParameterSet, find_components, read_ssd

    ssd = read_ssd(str(ssp))
    bindings = ParameterSet(name="bindings")
    for component in find_components(ssd.system):
        for binding in component.parameterBindings:
            for values in binding.parameterValues:
                for par in values.parameters:
                    q = Parameter(name=f"{component.name}.{par.name}")
                    q.type, q.value = par.type, par.value
                    bindings.parameters.append(q)
    rows = simulate_ssp(str(ssp), stop_time=stop, step_size=step, parameter_set=bindings)
    reactions = np.stack([np.stack([rows[f"{b}.reaction.{r}"] for r in dt.REACTION], axis=1) for b in dt.BEARINGS], axis=1)
    return {"time": rows["time"] + step, "reactions": reactions}


def main():
    write_ssd()
    print(f"wrote {SSD}")
    if "--run" in sys.argv:
        dt.build_shaft_fmu()
        ssp = package_ssp(dt.REPO / "target" / "drivetrain" / "drivetrain.ssp")
        res = run_libcosim(ssp)
        a, b = res["reactions"][-1]
        print(f"libcosim: {len(res['time'])} steps; at the end A {a}, B {b}")


if __name__ == "__main__":
    main()
