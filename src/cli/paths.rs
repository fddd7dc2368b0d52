//! Where things are: the cargo target directory (derived from this executable's location),
//! the FMU shared library next to the executable, and the FMI platform folder.

use super::CliError;
use std::path::{Path, PathBuf};

/// FMI 2.0 platform folder of `binaries/` for the platform this program was built for.
pub const PLATFORM: &str = if cfg!(all(target_os = "linux", target_pointer_width = "64")) {
    "linux64"
} else if cfg!(all(target_os = "linux", target_pointer_width = "32")) {
    "linux32"
} else if cfg!(all(target_os = "macos", target_pointer_width = "64")) {
    "darwin64"
} else if cfg!(all(windows, target_pointer_width = "64")) {
    "win64"
} else if cfg!(windows) {
    "win32"
} else {
    "unknown"
};

/// File name cargo gives the crate's cdylib (`[lib] name = "trb"`).
pub const CDYLIB_NAME: &str = if cfg!(windows) {
    "trb.dll"
} else if cfg!(target_os = "macos") {
    "libtrb.dylib"
} else {
    "libtrb.so"
};

/// Extension of a shared library inside the FMU.
pub const SHARED_LIB_EXT: &str = if cfg!(windows) {
    "dll"
} else if cfg!(target_os = "macos") {
    "dylib"
} else {
    "so"
};

/// Directory holding the running executable (cargo's profile directory, e.g. `target/release`).
pub fn exe_dir() -> Result<PathBuf, CliError> {
    let exe = std::env::current_exe().map_err(|e| CliError::failed(format!("cannot locate this executable: {e}")))?;
    exe.parent()
        .map(Path::to_path_buf)
        .ok_or_else(|| CliError::failed(format!("executable {} has no parent directory", exe.display())))
}

/// The cargo target directory this executable was built into: the parent of the profile
/// directory (`target/release/trb` -> `target`), or one more level up for a cross build
/// (`target/<triple>/release/trb`). Cargo marks its target directory with `CACHEDIR.TAG`,
/// which tells the two apart; `CARGO_TARGET_DIR` is honoured implicitly since the executable
/// lives inside it.
pub fn target_dir() -> Result<PathBuf, CliError> {
    let dir = exe_dir()?;
    Ok(target_dir_of(&dir))
}

fn target_dir_of(profile_dir: &Path) -> PathBuf {
    // Integration tests and examples run from `target/<profile>/deps` or `.../examples`.
    let profile_dir = match profile_dir.file_name().and_then(|n| n.to_str()) {
        Some("deps") | Some("examples") => profile_dir.parent().unwrap_or(profile_dir),
        _ => profile_dir,
    };
    let Some(parent) = profile_dir.parent() else {
        return profile_dir.to_path_buf();
    };
    if parent.join("CACHEDIR.TAG").is_file() {
        return parent.to_path_buf();
    }
    if let Some(grand) = parent.parent() {
        if grand.join("CACHEDIR.TAG").is_file() {
            return grand.to_path_buf();
        }
    }
    parent.to_path_buf()
}

/// Default location of the packaged FMU of model identifier `model_identifier`:
/// `<target dir>/fmu/<model_identifier>.fmu` (the default bearing's
/// `<target dir>/fmu/TaperedRollerBearing.fmu`).
pub fn default_fmu_path(model_identifier: &str) -> Result<PathBuf, CliError> {
    Ok(target_dir()?.join("fmu").join(format!("{model_identifier}.fmu")))
}

/// The crate's cdylib that cargo built with this executable.
///
/// Cargo compiles the library with all its crate types (`cdylib` and `rlib`) whenever the
/// binary needs it, also for `cargo run` and `cargo test`, but it copies ("uplifts") the
/// cdylib from `target/<profile>/deps/` to `target/<profile>/` only when the library itself
/// is a requested target (`cargo build`). So after `cargo run --release -- fmu` on a clean
/// target only `deps/libtrb.so` exists, and after `cargo build` followed by a library edit
/// and `cargo run`, the uplifted copy is stale. Hence: the newer of the two.
pub fn default_library() -> Result<PathBuf, CliError> {
    let dir = exe_dir()?;
    let candidates = [dir.join(CDYLIB_NAME), dir.join("deps").join(CDYLIB_NAME)];
    let newest = candidates
        .iter()
        .filter_map(|p| {
            let modified = std::fs::metadata(p).and_then(|m| m.modified()).ok()?;
            Some((modified, p))
        })
        .max_by_key(|(modified, _)| *modified)
        .map(|(_, p)| p.clone());
    // If neither exists, name the usual place in the error message.
    Ok(newest.unwrap_or_else(|| candidates[0].clone()))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn target_dir_is_the_parent_of_the_profile_dir() {
        let tmp = std::env::temp_dir().join(format!("trb-paths-{}", std::process::id()));
        let release = tmp.join("target").join("release");
        let cross = tmp.join("target").join("x86_64-unknown-linux-gnu").join("release");
        std::fs::create_dir_all(&release).unwrap();
        std::fs::create_dir_all(&cross).unwrap();
        std::fs::write(tmp.join("target").join("CACHEDIR.TAG"), "").unwrap();
        assert_eq!(target_dir_of(&release), tmp.join("target"));
        assert_eq!(target_dir_of(&release.join("deps")), tmp.join("target"));
        assert_eq!(target_dir_of(&cross), tmp.join("target"));
        std::fs::remove_dir_all(&tmp).unwrap();
    }
}
