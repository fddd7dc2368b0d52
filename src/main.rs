//! `trb`: package the FMU (`fmu`) or run a scenario without FMI (`simulate`).
fn main() {
    eprintln!("not yet implemented");
    std::process::exit(2);
}
