//! `docs/variables.md`: every variable of the FMU as a reader looks it up, generated from the
//! variable table (`modelDescription/variables.json` via [`crate::variables::TABLE`]), the
//! same table that makes `modelDescription.xml` and the FMU's `documentation/index.html`.
//! `tests/variables_doc.rs` checks that the file is what this generates.

use crate::variables::{Causality, VarType, Variability, Variable, TABLE};
use std::fmt::Write as _;

/// The FMI type of a variable as modelDescription.xml declares it.
pub fn type_name(v: &Variable) -> &'static str {
    match v.ty {
        VarType::Real => "Real",
        VarType::Integer if v.enumeration.is_some() => "Enumeration",
        VarType::Integer => "Integer",
        VarType::Boolean => "Boolean",
    }
}

/// The FMI variability's name.
pub fn variability_name(v: &Variable) -> &'static str {
    match v.variability {
        Variability::Fixed => "fixed",
        Variability::Tunable => "tunable",
        Variability::Discrete => "discrete",
        Variability::Continuous => "continuous",
    }
}

/// The FMI causality's name.
pub fn causality_name(c: Causality) -> &'static str {
    match c {
        Causality::Parameter => "parameter",
        Causality::Input => "input",
        Causality::Output => "output",
    }
}

fn kind(v: &Variable) -> String {
    format!("{}, {}", type_name(v), variability_name(v))
}

/// A variable's range as a reader reads it: an enumeration's items by value ("0 quasiStatic,
/// 1 dynamic"), else "[min, max]", "≥ min" or "≤ max".
pub fn range(v: &Variable) -> String {
    if let Some(e) = v.enumeration {
        let first = v.min.unwrap_or(0.0) as i64;
        return e
            .items
            .iter()
            .enumerate()
            .map(|(k, (n, _))| format!("{} {n}", first + k as i64))
            .collect::<Vec<_>>()
            .join(", ");
    }
    let f = |x: f64| {
        if v.ty == VarType::Integer {
            format!("{}", x as i64)
        } else {
            format!("{x:?}")
        }
    };
    match (v.min, v.max) {
        (Some(a), Some(b)) => format!("[{}, {}]", f(a), f(b)),
        (Some(a), None) => format!("\u{2265} {}", f(a)),
        (None, Some(b)) => format!("\u{2264} {}", f(b)),
        (None, None) => String::new(),
    }
}

/// Markdown table cells hold no pipes or line breaks.
fn cell(s: &str) -> String {
    s.replace('|', "\\|").replace('\n', " ")
}

/// The whole of `docs/variables.md`.
pub fn markdown() -> String {
    let mut s = String::from(
        "# Variables\n\n\
         Every variable of the FMU, generated from `modelDescription/variables.json` (the table that\n\
         also makes `modelDescription.xml`; regenerate with `TRB_BLESS=1 cargo test --release --test variables_doc`).\n\
         Units are SI; the display unit is what importing tools may show. `roller[j].*` exists for\n\
         j = 1 … Z, the bearing's roller count; its value reference is the one given plus j − 1.\n\
         Start values depend on the bearing: the FMU's `documentation/index.html` lists them for the\n\
         packaged bearing. Signs and frames: `docs/model.md`, \"Frames and signs\".\n",
    );
    for (causality, title) in [
        (Causality::Input, "Inputs"),
        (Causality::Output, "Outputs"),
        (Causality::Parameter, "Parameters"),
    ] {
        let _ = write!(
            s,
            "\n## {title}\n\n| name | value reference | type | unit (display) | range | description |\n|---|---|---|---|---|---|\n"
        );
        for v in TABLE.iter().filter(|v| v.causality == causality) {
            let unit = match (v.unit, v.display_unit) {
                (Some(u), Some(d)) => format!("{u} ({d})"),
                (Some(u), None) => u.to_string(),
                _ => String::new(),
            };
            let _ = writeln!(
                s,
                "| `{}` | {} | {} | {} | {} | {} |",
                v.name.replace("{j}", "j"),
                v.vr,
                kind(v),
                cell(&unit),
                cell(&range(v)),
                cell(&v.description.replace("{j}", "j"))
            );
        }
    }
    s
}
