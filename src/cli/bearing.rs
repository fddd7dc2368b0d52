//! `trb bearing`: bearing files. `show NAME` prints a preset as a bearing file (the presets'
//! JSON format, exactly as packaged), so that a user can start one of their own from it;
//! `estimate` builds one from catalogue data alone (`trb::catalogue`); `schema` prints the
//! file's JSON Schema.

use super::CliError;
use clap::{Args, Subcommand};
use std::path::PathBuf;
use trb::bearing::{Bearing, PRESETS};
use trb::catalogue::Catalogue;

#[derive(Debug, Clone, Args)]
pub struct BearingArgs {
    #[command(subcommand)]
    pub command: BearingCommand,
}

#[derive(Debug, Clone, Subcommand)]
pub enum BearingCommand {
    /// Print a preset as a bearing file (JSON), to stdout or to --out.
    Show(ShowArgs),
    /// Build a bearing file of a single-row tapered roller bearing from its catalogue data
    /// (the catalogues' symbols, mm and N); prints the estimated geometry. Without --out the
    /// file goes to stdout and the table to stderr.
    Estimate(EstimateArgs),
    /// Print the JSON Schema of a bearing file (presets/bearing.schema.json), to stdout or to
    /// --out.
    Schema(SchemaArgs),
}

#[derive(Debug, Clone, Args)]
pub struct SchemaArgs {
    /// Write the schema here instead of to stdout.
    #[arg(long, value_name = "FILE.json")]
    pub out: Option<PathBuf>,
}

#[derive(Debug, Clone, Args)]
pub struct EstimateArgs {
    /// Bore diameter d (mm).
    #[arg(long = "d", value_name = "MM", allow_negative_numbers = true)]
    pub d: f64,
    /// Outside diameter D (mm).
    #[arg(long = "D", value_name = "MM", allow_negative_numbers = true)]
    pub outside_d: f64,
    /// Total width T (mm).
    #[arg(long = "T", value_name = "MM", allow_negative_numbers = true)]
    pub t: f64,
    /// Cone (inner ring) width B (mm).
    #[arg(long = "B", value_name = "MM", allow_negative_numbers = true)]
    pub b: Option<f64>,
    /// Cup (outer ring) width C (mm).
    #[arg(long = "C", value_name = "MM", allow_negative_numbers = true)]
    pub c: Option<f64>,
    /// Basic dynamic radial load rating C_r (N).
    #[arg(long = "Cr", value_name = "N", allow_negative_numbers = true)]
    pub c_r: f64,
    /// Calculation factor e (e = 1.5 tan of the contact angle).
    #[arg(long = "e", allow_negative_numbers = true)]
    pub e: f64,
    /// Axial load factor Y (checked against e: Y = 0.6 / e).
    #[arg(long = "Y", allow_negative_numbers = true)]
    pub y: Option<f64>,
    /// Basic static radial load rating C_0r (N), reported against the geometry's.
    #[arg(long = "C0r", value_name = "N", allow_negative_numbers = true)]
    pub c_0r: Option<f64>,
    /// Number of rollers, when the maker gives it.
    #[arg(long = "Z", allow_negative_numbers = true)]
    pub z: Option<i64>,
    /// The bearing's name in the file (default: the envelope, "d x D x T").
    #[arg(long)]
    pub name: Option<String>,
    /// Write the bearing file here instead of to stdout.
    #[arg(long, value_name = "FILE.json")]
    pub out: Option<PathBuf>,
}

#[derive(Debug, Clone, Args)]
pub struct ShowArgs {
    #[arg(help = format!("The preset's name: {}", trb::bearing::preset_names()))]
    pub name: String,
    /// Write the file here instead of to stdout.
    #[arg(long, value_name = "FILE.json")]
    pub out: Option<PathBuf>,
}

pub fn run(args: BearingArgs) -> Result<(), CliError> {
    match args.command {
        BearingCommand::Show(show) => run_show(show),
        BearingCommand::Estimate(estimate) => run_estimate(estimate),
        BearingCommand::Schema(args) => write_or_print(&trb::bearing::bearing_file_schema(), args.out),
    }
}

fn run_estimate(args: EstimateArgs) -> Result<(), CliError> {
    let catalogue = Catalogue {
        d: args.d,
        outside_d: args.outside_d,
        t: args.t,
        b: args.b,
        c: args.c,
        c_r: args.c_r,
        e: args.e,
        y: args.y,
        c_0r: args.c_0r,
        z: args.z,
    };
    let estimate = catalogue.estimate().map_err(|faults| {
        let lines: Vec<String> = faults.0.iter().map(|f| format!("  --{f}")).collect();
        CliError::invalid(format!("bad catalogue data:\n{}", lines.join("\n")))
    })?;
    let name = args.name.unwrap_or_else(|| format!("{}x{}x{}", args.d, args.outside_d, args.t));
    let file = estimate.bearing_file(&catalogue, &name);
    // the file must read back as a valid bearing (the estimate stays inside the reader's checks)
    let text = serde_json::to_string_pretty(&file).map_err(|e| CliError::failed(e.to_string()))? + "\n";
    Bearing::from_json(&text).map_err(|e| CliError::failed(format!("the estimated bearing does not validate: {e}")))?;
    let table = format!(
        "{name}: internal geometry estimated from catalogue data\n{}",
        estimate.table(&catalogue)
    );
    match args.out {
        None => {
            eprint!("{table}");
            print!("{text}");
            Ok(())
        }
        Some(path) => {
            std::fs::write(&path, text).map_err(|e| CliError::failed(format!("cannot write {}: {e}", path.display())))?;
            print!("{table}");
            println!("  written to {}", path.display());
            Ok(())
        }
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
    write_or_print(text, args.out)
}

/// `text` to the file `out`, or to stdout.
fn write_or_print(text: &str, out: Option<PathBuf>) -> Result<(), CliError> {
    match out {
        None => {
            print!("{text}");
            Ok(())
        }
        Some(path) => std::fs::write(&path, text).map_err(|e| CliError::failed(format!("cannot write {}: {e}", path.display()))),
    }
}
