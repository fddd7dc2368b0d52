//! The FMU's libraries without their debug information, which is kept beside the FMU.
//!
//! The release profile builds with line tables (`debug = 1`, for backtraces and profiles of the
//! tests and benchmarks), which make the cdylib about 20 MB of which 3 MB are code and data. The
//! FMU carries the library stripped by GNU objcopy, as Debian's packages are:
//!
//! - `objcopy --only-keep-debug LIB NAME.debug`: the DWARF sections and the symbol table;
//! - `objcopy --strip-unneeded --add-gnu-debuglink=NAME.debug LIB`: the library without them
//!   (its exported FMI functions stay in the dynamic symbol table), naming its debug file and
//!   that file's CRC in `.gnu_debuglink`; ELF libraries keep their build ID as well.
//!
//! gdb, valgrind and perf find the debug file beside the extracted library (or in its `.debug/`
//! directory) by that name; perf also by build ID (`perf buildid-cache --add NAME.debug`). The
//! win64 DLL is stripped the same way by mingw-w64's `x86_64-w64-mingw32-objcopy` (or a GNU
//! objcopy that reads PE, Debian's does). `OBJCOPY` names another objcopy. Without a usable
//! objcopy the library goes into the FMU as it is and the packager warns (the FMU is then about
//! four times larger, and works the same).

use std::ffi::OsStr;
use std::path::{Path, PathBuf};
use std::process::Command;
use std::sync::atomic::{AtomicUsize, Ordering};

/// A library split into what goes into the FMU and what stays beside it.
#[derive(Debug, Clone)]
pub struct Split {
    /// The library without debug sections and static symbols, naming its debug file.
    pub stripped: Vec<u8>,
    /// The debug sections and the symbol table (`objcopy --only-keep-debug`).
    pub debug: Vec<u8>,
}

/// The objcopy programs to try for a library of `platform`, first to last.
fn objcopy_candidates(platform: &str) -> Vec<PathBuf> {
    if let Some(program) = std::env::var_os("OBJCOPY").filter(|p| !p.is_empty()) {
        return vec![PathBuf::from(program)];
    }
    let mut names = Vec::new();
    if platform.starts_with("win") {
        names.push("x86_64-w64-mingw32-objcopy");
    }
    names.push("objcopy");
    names.into_iter().map(PathBuf::from).collect()
}

/// Split `library` (a `platform` library) with objcopy into its stripped form, whose
/// `.gnu_debuglink` names `debug_name`, and its debug file. Errors say why (no objcopy, not a
/// format objcopy reads, ...); the caller then packages the library as it is.
pub fn split(library: &Path, platform: &str, debug_name: &str) -> Result<Split, String> {
    static SERIAL: AtomicUsize = AtomicUsize::new(0);
    let dir = std::env::temp_dir().join(format!(
        "trb-strip-{}-{}",
        std::process::id(),
        SERIAL.fetch_add(1, Ordering::Relaxed)
    ));
    std::fs::create_dir_all(&dir).map_err(|e| format!("cannot create {}: {e}", dir.display()))?;
    let result = split_in(&dir, library, platform, debug_name);
    let _ = std::fs::remove_dir_all(&dir);
    result
}

fn split_in(dir: &Path, library: &Path, platform: &str, debug_name: &str) -> Result<Split, String> {
    // `--add-gnu-debuglink` records the debug file's base name and CRC.
    let debug = dir.join(debug_name);
    let stripped = dir.join("stripped");
    let debuglink = format!("--add-gnu-debuglink={}", debug.display());
    let keep_debug: [&OsStr; 3] = ["--only-keep-debug".as_ref(), library.as_os_str(), debug.as_os_str()];
    let strip: [&OsStr; 4] = [
        "--strip-unneeded".as_ref(),
        debuglink.as_ref(),
        library.as_os_str(),
        stripped.as_os_str(),
    ];
    let mut failures = Vec::new();
    'objcopy: for objcopy in objcopy_candidates(platform) {
        for args in [&keep_debug[..], &strip[..]] {
            let failure = match Command::new(&objcopy).args(args).output() {
                Ok(out) if out.status.success() => continue,
                Ok(out) => format!(
                    "{} {}: {}",
                    objcopy.display(),
                    args[0].to_string_lossy(),
                    String::from_utf8_lossy(&out.stderr).trim()
                ),
                Err(e) => format!("{}: {e}", objcopy.display()),
            };
            failures.push(failure);
            continue 'objcopy;
        }
        let read = |p: &Path| std::fs::read(p).map_err(|e| format!("cannot read {}: {e}", p.display()));
        return Ok(Split {
            stripped: read(&stripped)?,
            debug: read(&debug)?,
        });
    }
    Err(failures.join("; "))
}
