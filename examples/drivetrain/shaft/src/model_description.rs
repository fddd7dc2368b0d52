//! modelDescription.xml of the shaft FMU, written from the variable table.

use crate::fmi::GUID;
use crate::variables::{variables, Causality};
use std::fmt::Write;

fn escape(s: &str) -> String {
    s.replace('&', "&amp;")
        .replace('<', "&lt;")
        .replace('>', "&gt;")
        .replace('"', "&quot;")
}

/// The model description (FMI 2.0, Co-Simulation, model identifier `Shaft`).
pub fn model_description() -> String {
    let vars = variables();
    let mut units: Vec<&str> = vars.iter().map(|v| v.unit).filter(|u| *u != "1").collect();
    units.sort();
    units.dedup();
    let mut x = String::new();
    x.push_str("<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n");
    let _ = writeln!(
        x,
        "<fmiModelDescription fmiVersion=\"2.0\" modelName=\"Shaft\" guid=\"{GUID}\" description=\"Quasi-static rigid 5-DOF shaft on two TRBs (O arrangement) with a gear mesh force: one Newton step per communication step\" generationTool=\"drivetrain-shaft (tapered-roller-bearing examples/drivetrain)\" variableNamingConvention=\"structured\" numberOfEventIndicators=\"0\">"
    );
    x.push_str("  <CoSimulation modelIdentifier=\"Shaft\" canHandleVariableCommunicationStepSize=\"true\" canNotUseMemoryManagementFunctions=\"true\" canBeInstantiatedOnlyOncePerProcess=\"false\"/>\n");
    x.push_str("  <UnitDefinitions>\n");
    for u in &units {
        let _ = writeln!(x, "    <Unit name=\"{}\"/>", escape(u));
    }
    x.push_str("  </UnitDefinitions>\n  <DefaultExperiment startTime=\"0\" stopTime=\"2\" stepSize=\"0.01\"/>\n  <ModelVariables>\n");
    let mut outputs = Vec::new();
    for (k, v) in vars.iter().enumerate() {
        let (causality, variability, initial, start) = match v.causality {
            Causality::Parameter => ("parameter", "fixed", " initial=\"exact\"", Some(v.start)),
            Causality::Input => ("input", "continuous", "", Some(v.start)),
            Causality::Output => {
                outputs.push(k + 1);
                ("output", "continuous", " initial=\"calculated\"", None)
            }
        };
        let _ = writeln!(
            x,
            "    <!-- {} --><ScalarVariable name=\"{}\" valueReference=\"{}\" causality=\"{causality}\" variability=\"{variability}\"{initial} description=\"{}\">",
            k + 1,
            escape(&v.name),
            v.vr,
            escape(&v.description)
        );
        let unit = if v.unit == "1" {
            String::new()
        } else {
            format!(" unit=\"{}\"", escape(v.unit))
        };
        match start {
            Some(s) => {
                let _ = writeln!(x, "      <Real{unit} start=\"{s:?}\"/>");
            }
            None => {
                let _ = writeln!(x, "      <Real{unit}/>");
            }
        }
        x.push_str("    </ScalarVariable>\n");
    }
    x.push_str("  </ModelVariables>\n  <ModelStructure>\n    <Outputs>\n");
    for k in &outputs {
        let _ = writeln!(x, "      <Unknown index=\"{k}\"/>");
    }
    x.push_str("    </Outputs>\n    <InitialUnknowns>\n");
    for k in &outputs {
        let _ = writeln!(x, "      <Unknown index=\"{k}\"/>");
    }
    x.push_str("    </InitialUnknowns>\n  </ModelStructure>\n</fmiModelDescription>\n");
    x
}
