//! Package the shaft FMU: `cargo run --release --manifest-path examples/drivetrain/shaft/Cargo.toml [-- OUT.fmu]`
//! builds the cdylib and writes `target/fmu/Shaft.fmu` next to it (binaries for this
//! machine only: linux64, win64 or darwin64).

use std::io::Write;
use std::path::PathBuf;
use zip::write::SimpleFileOptions;
use zip::{CompressionMethod, ZipWriter};

fn main() {
    if let Err(e) = run() {
        eprintln!("error: {e}");
        std::process::exit(1);
    }
}

fn run() -> Result<(), String> {
    let exe = std::env::current_exe().map_err(|e| format!("current_exe: {e}"))?;
    let dir = exe.parent().ok_or("no directory of the executable")?.to_path_buf();
    let (platform, lib, ext) = if cfg!(target_os = "windows") {
        ("win64", "shaft.dll", "dll")
    } else if cfg!(target_os = "macos") {
        ("darwin64", "libshaft.dylib", "dylib")
    } else {
        ("linux64", "libshaft.so", "so")
    };
    let lib_path = dir.join(lib);
    let binary =
        std::fs::read(&lib_path).map_err(|e| format!("{}: {e} (build the library first: cargo build --release)", lib_path.display()))?;
    let out = match std::env::args_os().nth(1) {
        Some(p) => PathBuf::from(p),
        None => dir.parent().ok_or("no target directory")?.join("fmu").join("Shaft.fmu"),
    };
    if let Some(parent) = out.parent() {
        std::fs::create_dir_all(parent).map_err(|e| format!("{}: {e}", parent.display()))?;
    }
    let file = std::fs::File::create(&out).map_err(|e| format!("{}: {e}", out.display()))?;
    let mut zip = ZipWriter::new(file);
    let opts = SimpleFileOptions::default().compression_method(CompressionMethod::Deflated);
    let err = |e: zip::result::ZipError| format!("{}: {e}", out.display());
    zip.start_file("modelDescription.xml", opts).map_err(err)?;
    zip.write_all(shaft::model_description::model_description().as_bytes())
        .map_err(|e| e.to_string())?;
    zip.start_file(format!("binaries/{platform}/Shaft.{ext}"), opts).map_err(err)?;
    zip.write_all(&binary).map_err(|e| e.to_string())?;
    zip.finish().map_err(err)?;
    println!("{}", out.display());
    Ok(())
}
