//! `trb fmu --portable`: cross-build the FMU's shared library for the two platforms of a
//! portable FMU, on a Linux x86_64 machine:
//!
//! - `linux64`, loading on glibc 2.17 and later: `cargo zigbuild --release --lib --target
//!   x86_64-unknown-linux-gnu.2.17` (zig links against glibc 2.17's symbol versions), with the
//!   Rust toolchain that built this program; target directory `<target>/cross-linux64`.
//! - `win64`: Debian's Rust (packages rustc-web, cargo-web, rust-web-src) builds the standard
//!   library from its sources for `x86_64-pc-windows-gnu` (`-Zbuild-std`, hence
//!   `RUSTC_BOOTSTRAP=1`) and links with mingw-w64's gcc; target directory
//!   `<target>/cross-win64`, so that the other rustc never touches the fingerprints of the
//!   rustup build in `<target>/release`.
//!
//! The tools come from `scripts/cross-setup.sh` (zig and cargo-zigbuild pinned from PyPI into
//! `.venv-cross`, the Debian packages by apt-get). Every tool is looked up before any build
//! starts; the missing ones are all named with how to install them (exit code 3).

use super::{paths, CliError};
use std::ffi::OsStr;
use std::path::{Path, PathBuf};
use std::process::Command;

/// The glibc-versioned target of the linux64 build (cargo-zigbuild's syntax).
pub const LINUX_TARGET: &str = "x86_64-unknown-linux-gnu.2.17";
/// The Windows target of the win64 build.
pub const WINDOWS_TARGET: &str = "x86_64-pc-windows-gnu";
/// The venv of scripts/cross-setup.sh, relative to the source directory.
pub const CROSS_VENV: &str = ".venv-cross";
/// Where Debian's packages put their Rust (rustc-web, cargo-web).
pub const DEBIAN_BIN: &str = "/usr/bin";
/// The oldest Debian rustc that builds the crate and its dependencies (rust-version of
/// Cargo.toml is 1.80; Debian 12's own rustc 1.63 is far too old).
const MIN_WINDOWS_RUSTC: (u32, u32) = (1, 80);

const SETUP_HINT: &str = "scripts/cross-setup.sh installs all of them (as root for the Debian packages)";

/// The two cross-built libraries.
#[derive(Debug, Clone)]
pub struct Built {
    pub linux64: PathBuf,
    pub win64: PathBuf,
}

/// The external programs the two builds need, found or not.
#[derive(Debug, Clone, Default)]
pub struct Tools {
    pub cargo_zigbuild: Option<PathBuf>,
    /// The Python of `.venv-cross` when it holds ziglang (cargo-zigbuild runs `python3 -m
    /// ziglang`), or `zig` on PATH.
    pub zig: Option<PathBuf>,
    pub debian_cargo: Option<PathBuf>,
    pub debian_rustc: Option<PathBuf>,
    /// `<Debian rustc sysroot>/lib/rustlib/src/rust/library` (rust-web-src).
    pub rust_src: Option<PathBuf>,
    pub mingw_gcc: Option<PathBuf>,
    /// Problems other than absence (a Debian rustc too old, ...).
    pub problems: Vec<String>,
}

impl Tools {
    /// Look every tool up: `venv` (the cross venv), the directories of `path` (a PATH value)
    /// and `debian_bin` (Debian's Rust).
    pub fn find(venv: &Path, path: Option<&OsStr>, debian_bin: &Path) -> Tools {
        let venv_bin = venv.join("bin");
        let mut tools = Tools {
            cargo_zigbuild: executable(&venv_bin.join("cargo-zigbuild")).or_else(|| which("cargo-zigbuild", path)),
            ..Tools::default()
        };
        let venv_python = venv_bin.join("python3");
        tools.zig = if executable(&venv_python).is_some() && runs(Command::new(&venv_python).args(["-m", "ziglang", "version"])) {
            Some(venv_python)
        } else {
            which("zig", path)
        };
        tools.debian_cargo = executable(&debian_bin.join("cargo"));
        tools.debian_rustc = executable(&debian_bin.join("rustc"));
        if let Some(rustc) = &tools.debian_rustc {
            match rustc_version(rustc) {
                Some((version, parsed)) if parsed < MIN_WINDOWS_RUSTC => tools.problems.push(format!(
                    "{} is {version}, older than {}.{} (Debian 12's `rustc` package): apt-get install rustc-web cargo-web rust-web-src",
                    rustc.display(),
                    MIN_WINDOWS_RUSTC.0,
                    MIN_WINDOWS_RUSTC.1
                )),
                Some(_) => {}
                None => tools.problems.push(format!("{} --version failed", rustc.display())),
            }
            tools.rust_src = sysroot(rustc)
                .map(|s| s.join("lib/rustlib/src/rust/library"))
                .filter(|lib| lib.join("std").is_dir());
        }
        tools.mingw_gcc = which("x86_64-w64-mingw32-gcc", path);
        tools
    }

    /// One line per missing tool, with the command that installs it.
    pub fn missing(&self) -> Vec<String> {
        let mut out = Vec::new();
        if self.cargo_zigbuild.is_none() {
            out.push(format!(
                "cargo-zigbuild (links the linux64 library for glibc 2.17) not found in {CROSS_VENV}/bin nor on PATH: \
                 pip install -r scripts/cross-requirements.txt into {CROSS_VENV}"
            ));
        }
        if self.zig.is_none() {
            out.push(format!(
                "zig (the ziglang package from PyPI) not found in {CROSS_VENV} nor on PATH: \
                 pip install -r scripts/cross-requirements.txt into {CROSS_VENV}"
            ));
        }
        if self.debian_cargo.is_none() || self.debian_rustc.is_none() {
            out.push(format!(
                "Debian's Rust (builds the win64 library with the standard library from source) not found as \
                 {DEBIAN_BIN}/cargo and {DEBIAN_BIN}/rustc: apt-get install rustc-web cargo-web rust-web-src"
            ));
        } else if self.rust_src.is_none() {
            out.push(
                "the standard library sources of Debian's rustc (for -Zbuild-std) not found: apt-get install rust-web-src".to_string(),
            );
        }
        if self.mingw_gcc.is_none() {
            out.push("x86_64-w64-mingw32-gcc (the win64 linker) not found on PATH: apt-get install gcc-mingw-w64-x86-64".to_string());
        }
        out.extend(self.problems.iter().cloned());
        out
    }
}

/// Build both libraries, or say which tools are missing (exit code 3) before building anything.
pub fn build() -> Result<Built, CliError> {
    if !cfg!(all(target_os = "linux", target_arch = "x86_64")) {
        return Err(CliError::invalid("--portable builds on Linux x86_64 only"));
    }
    let root = source_dir()?;
    let target = paths::target_dir()?;
    let path = std::env::var_os("PATH");
    let tools = Tools::find(&root.join(CROSS_VENV), path.as_deref(), Path::new(DEBIAN_BIN));
    let missing = tools.missing();
    if !missing.is_empty() {
        return Err(CliError::missing_tool(format!(
            "fmu --portable needs tools that are missing:\n  - {}\n{SETUP_HINT}",
            missing.join("\n  - ")
        )));
    }
    let linux64 = build_linux64(&root, &target, &tools, path.as_deref())?;
    let win64 = build_win64(&root, &target, &tools)?;
    Ok(Built { linux64, win64 })
}

/// The crate's source directory (the portable builds compile it again).
fn source_dir() -> Result<PathBuf, CliError> {
    let dir = PathBuf::from(env!("CARGO_MANIFEST_DIR"));
    if dir.join("Cargo.toml").is_file() && dir.join("src").is_dir() {
        Ok(dir)
    } else {
        Err(CliError::failed(format!(
            "--portable compiles the crate again, but its sources are not at {} any more",
            dir.display()
        )))
    }
}

/// A command with the flags that would make a cross build non-portable removed from the
/// environment (`RUSTFLAGS=-C target-cpu=native` and the like) and `CARGO_TARGET_DIR` set.
fn cargo_command(program: &Path, target_dir: &Path) -> Command {
    let mut cmd = Command::new(program);
    for var in [
        "RUSTFLAGS",
        "CARGO_ENCODED_RUSTFLAGS",
        "CARGO_BUILD_RUSTFLAGS",
        "RUSTC_WRAPPER",
        "RUSTC_WORKSPACE_WRAPPER",
    ] {
        cmd.env_remove(var);
    }
    cmd.env("CARGO_TARGET_DIR", target_dir);
    cmd
}

fn build_linux64(root: &Path, target: &Path, tools: &Tools, path: Option<&OsStr>) -> Result<PathBuf, CliError> {
    let zigbuild = tools.cargo_zigbuild.as_deref().expect("checked");
    let target_dir = target.join("cross-linux64");
    // cargo-zigbuild runs `cargo` and `python3 -m ziglang` from PATH: first the venv (its
    // python3), then the toolchain that built this program (cargo run sets CARGO), so that an
    // older or Debian cargo earlier on PATH is not picked up.
    let mut dirs: Vec<PathBuf> = Vec::new();
    if let Some(zig) = &tools.zig {
        dirs.extend(zig.parent().map(Path::to_path_buf));
    }
    if let Some(cargo) = std::env::var_os("CARGO").map(PathBuf::from) {
        dirs.extend(cargo.parent().map(Path::to_path_buf));
    }
    dirs.extend(path.map(std::env::split_paths).into_iter().flatten());
    let new_path = std::env::join_paths(dirs).map_err(|e| CliError::failed(format!("PATH: {e}")))?;

    let mut cmd = cargo_command(zigbuild, &target_dir);
    cmd.env("PATH", new_path)
        .args([
            "zigbuild",
            "--release",
            "--lib",
            "--locked",
            "--target",
            LINUX_TARGET,
            "--manifest-path",
        ])
        .arg(root.join("Cargo.toml"));
    eprintln!(
        "building linux64 (glibc >= 2.17): cargo zigbuild --release --lib --target {LINUX_TARGET} (in {})",
        target_dir.display()
    );
    run(&mut cmd, "cargo zigbuild (linux64)")?;
    let lib = target_dir.join("x86_64-unknown-linux-gnu/release/libtrb.so");
    existing(lib, "cargo zigbuild")
}

fn build_win64(root: &Path, target: &Path, tools: &Tools) -> Result<PathBuf, CliError> {
    let cargo = tools.debian_cargo.as_deref().expect("checked");
    let rustc = tools.debian_rustc.as_deref().expect("checked");
    let gcc = tools.mingw_gcc.as_deref().expect("checked");
    let target_dir = target.join("cross-win64");
    let mut cmd = cargo_command(cargo, &target_dir);
    // Not the rustup toolchain: Debian's cargo with Debian's rustc (which has the std
    // sources); cargo run's RUSTUP_TOOLCHAIN and CARGO must not leak into it.
    cmd.env_remove("RUSTUP_TOOLCHAIN")
        .env_remove("CARGO")
        .env("RUSTC", rustc)
        .env("RUSTDOC", rustc.with_file_name("rustdoc"))
        .env("RUSTC_BOOTSTRAP", "1")
        .env("CARGO_TARGET_X86_64_PC_WINDOWS_GNU_LINKER", gcc)
        .args([
            "build",
            "-Zbuild-std=std,panic_unwind",
            "--release",
            "--lib",
            "--locked",
            "--target",
            WINDOWS_TARGET,
        ])
        .arg("--manifest-path")
        .arg(root.join("Cargo.toml"));
    eprintln!(
        "building win64: {} build -Zbuild-std=std,panic_unwind --release --lib --target {WINDOWS_TARGET} (in {})",
        cargo.display(),
        target_dir.display()
    );
    run(&mut cmd, "Debian's cargo (win64)")?;
    let lib = target_dir.join(WINDOWS_TARGET).join("release/trb.dll");
    existing(lib, "Debian's cargo")
}

fn run(cmd: &mut Command, what: &str) -> Result<(), CliError> {
    let status = cmd
        .status()
        .map_err(|e| CliError::failed(format!("cannot run {what} ({}): {e}", cmd.get_program().to_string_lossy())))?;
    if status.success() {
        Ok(())
    } else {
        Err(CliError::failed(format!("{what} failed ({status}); its output is above")))
    }
}

fn existing(lib: PathBuf, what: &str) -> Result<PathBuf, CliError> {
    if lib.is_file() {
        Ok(lib)
    } else {
        Err(CliError::failed(format!("{what} succeeded but {} is missing", lib.display())))
    }
}

fn executable(p: &Path) -> Option<PathBuf> {
    use std::os::unix::fs::PermissionsExt as _;
    let meta = std::fs::metadata(p).ok()?;
    (meta.is_file() && meta.permissions().mode() & 0o111 != 0).then(|| p.to_path_buf())
}

fn which(name: &str, path: Option<&OsStr>) -> Option<PathBuf> {
    std::env::split_paths(path?).find_map(|dir| executable(&dir.join(name)))
}

fn runs(cmd: &mut Command) -> bool {
    cmd.stdout(std::process::Stdio::null())
        .stderr(std::process::Stdio::null())
        .status()
        .is_ok_and(|s| s.success())
}

fn output_of(program: &Path, args: &[&str]) -> Option<String> {
    let out = Command::new(program).args(args).env_remove("RUSTUP_TOOLCHAIN").output().ok()?;
    out.status
        .success()
        .then(|| String::from_utf8_lossy(&out.stdout).trim().to_string())
}

/// `rustc 1.96.0 (...)` -> ("rustc 1.96.0 (...)", (1, 96)).
fn rustc_version(rustc: &Path) -> Option<(String, (u32, u32))> {
    let text = output_of(rustc, &["--version"])?;
    let parsed = parse_rustc_version(&text)?;
    Some((text, parsed))
}

fn parse_rustc_version(text: &str) -> Option<(u32, u32)> {
    let version = text.split_whitespace().nth(1)?;
    let mut parts = version.split('.');
    Some((parts.next()?.parse().ok()?, parts.next()?.parse().ok()?))
}

fn sysroot(rustc: &Path) -> Option<PathBuf> {
    output_of(rustc, &["--print", "sysroot"]).map(PathBuf::from)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn rustc_versions_parse() {
        assert_eq!(
            parse_rustc_version("rustc 1.96.0 (ac68faa20 2026-05-25) (built from a source tarball)"),
            Some((1, 96))
        );
        assert_eq!(parse_rustc_version("rustc 1.63.0"), Some((1, 63)));
        assert!(parse_rustc_version("rustc").is_none());
    }

    #[test]
    fn every_missing_tool_is_named_with_its_install_command() {
        let empty = std::env::temp_dir().join(format!("trb-portable-empty-{}", std::process::id()));
        std::fs::create_dir_all(&empty).unwrap();
        let tools = Tools::find(&empty.join("venv"), Some(empty.as_os_str()), &empty);
        let missing = tools.missing();
        std::fs::remove_dir_all(&empty).unwrap();
        let text = missing.join("\n");
        assert_eq!(missing.len(), 4, "{text}");
        for needle in [
            "cargo-zigbuild",
            "pip install -r scripts/cross-requirements.txt",
            "zig (the ziglang package",
            "apt-get install rustc-web cargo-web rust-web-src",
            "apt-get install gcc-mingw-w64-x86-64",
        ] {
            assert!(text.contains(needle), "`{needle}` not in:\n{text}");
        }
    }
}
