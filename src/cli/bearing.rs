//! `trb bearing`: bearing files. `show NAME` prints a preset as a bearing file (the presets'
//! JSON format, exactly as packaged), so that a user can start one of their own from it.

use super::CliError;
use clap::{Args, Subcommand};
use std::path::PathBuf;
use trb::bearing::{Bearing, PRESETS};

#[derive(Debug, Clone, Args)]
pub struct BearingArgs {
    #[command(subcommand)]
    pub command: BearingCommand,
}

#[derive(Debug, Clone, Subcommand)]
pub enum BearingCommand {
    /// Print a preset as a bearing file (JSON), to stdout or to --out.
    Show(ShowArgs),
}

#[derive(Debug, Clone, Args)]
pub struct ShowArgs {
    /// The preset's name.
    pub name: String,
    /// Write the file here instead of to stdout.
    #[arg(long, value_name = "FILE.json")]
    pub out: Option<PathBuf>,
}

pub fn run(args: BearingArgs) -> Result<(), CliError> {
    match args.command {
        BearingCommand::Show(show) => run_show(show),
    }
}

fn run_show(args: ShowArgs) -> Result<(), CliError> {
    // the name as `Bearing::preset` takes it (any case), the error naming the presets
    Bearing::preset(&args.name).map_err(|e| CliError::invalid(e.to_string()))?;
    let text = PRESETS
        .iter()
        .find(|(n, _)| n.eq_ignore_ascii_case(&args.name))
        .map(|(_, t)| *t)
        .expect("a preset that parsed");
    match args.out {
        None => {
            print!("{text}");
            Ok(())
        }
        Some(path) => std::fs::write(&path, text).map_err(|e| CliError::failed(format!("cannot write {}: {e}", path.display()))),
    }
}
