//! `trb`: package the FMU (`fmu`), run a scenario without FMI (`simulate`), or both at once
//! on the demonstration scenario (`demo`). See `trb --help`.

mod cli;

use clap::Parser;

fn main() {
    let args = cli::Cli::parse();
    if let Err(e) = cli::run(args) {
        eprintln!("error: {e}");
        std::process::exit(e.code);
    }
}
