//! Shared helpers of the commands that write documents (`study`, `stress`, `bench`): markdown
//! tables, the generated section of a hand-written document, and where a run happened
//! (machine and commit) for the reports.

use super::CliError;
use std::fmt::Write as _;
use std::path::Path;

/// A markdown table.
pub fn table(head: &[&str], rows: &[Vec<String>]) -> String {
    let mut s = format!("| {} |\n|{}\n", head.join(" | "), "---|".repeat(head.len()));
    for r in rows {
        let _ = writeln!(s, "| {} |", r.join(" | "));
    }
    s
}

/// Replace the text between `begin` and `end` in `path` with `generated`, keeping the
/// hand-written rest. A missing file is created with `title`; a file without the markers
/// gets the section appended.
pub fn replace_section(path: &Path, begin: &str, end: &str, title: &str, generated: &str) -> Result<(), CliError> {
    let old = std::fs::read_to_string(path).unwrap_or_default();
    let section = format!("{begin}\n{generated}\n{end}");
    let text = match (old.find(begin), old.find(end)) {
        (Some(b), Some(e)) if e > b => format!("{}{section}{}", &old[..b], &old[e + end.len()..]),
        _ if old.is_empty() => format!("# {title}\n\n{section}\n"),
        _ => format!("{}\n{section}\n", old.trim_end()),
    };
    std::fs::write(path, text).map_err(|e| CliError::failed(format!("cannot write {}: {e}", path.display())))
}

/// Replace the section of `path` between `begin` and `end` (as [`replace_section`]) with
/// `header` and, per fidelity in `fidelities`, its part between the markers
/// `<!-- {prefix}:fidelity-N:begin -->` and `<!-- {prefix}:fidelity-N:end -->`: the new text
/// of `parts` where the command ran that fidelity, else the part the document already has
/// (so that a run of one fidelity keeps the others' results).
pub fn replace_section_parts(
    path: &Path,
    (begin, end, title): (&str, &str, &str),
    prefix: &str,
    header: &str,
    parts: &[(i32, String)],
    fidelities: std::ops::RangeInclusive<i32>,
) -> Result<(), CliError> {
    let old = std::fs::read_to_string(path).unwrap_or_default();
    let old_section = match (old.find(begin), old.find(end)) {
        (Some(b), Some(e)) if e > b => &old[b..e],
        _ => "",
    };
    let mut generated = header.trim_end().to_string();
    for f in fidelities {
        let (part_begin, part_end) = (
            format!("<!-- {prefix}:fidelity-{f}:begin -->"),
            format!("<!-- {prefix}:fidelity-{f}:end -->"),
        );
        let part = match parts.iter().find(|(g, _)| *g == f) {
            Some((_, text)) => Some(format!("{part_begin}\n{}\n{part_end}", text.trim_end())),
            None => match (old_section.find(&part_begin), old_section.find(&part_end)) {
                (Some(b), Some(e)) if e > b => Some(old_section[b..e + part_end.len()].to_string()),
                _ => None,
            },
        };
        if let Some(part) = part {
            if !generated.is_empty() {
                generated.push_str("\n\n");
            }
            generated.push_str(&part);
        }
    }
    replace_section(path, begin, end, title, &generated)
}

/// One line naming the machine: CPU model, logical cores, memory, operating system.
pub fn machine() -> String {
    let read = |p: &str| std::fs::read_to_string(p).unwrap_or_default();
    let cpuinfo = read("/proc/cpuinfo");
    let cpu = cpuinfo
        .lines()
        .find(|l| l.starts_with("model name"))
        .and_then(|l| l.split_once(':'))
        .map(|(_, v)| v.trim().to_string())
        .unwrap_or_else(|| std::env::consts::ARCH.to_string());
    let cores = std::thread::available_parallelism().map(|n| n.get()).unwrap_or(1);
    let mem_gib = read("/proc/meminfo")
        .lines()
        .find(|l| l.starts_with("MemTotal:"))
        .and_then(|l| l.split_whitespace().nth(1))
        .and_then(|kb| kb.parse::<f64>().ok())
        .map(|kb| kb / 1024.0 / 1024.0);
    let os = read("/etc/os-release")
        .lines()
        .find(|l| l.starts_with("PRETTY_NAME="))
        .map(|l| l.trim_start_matches("PRETTY_NAME=").trim_matches('"').to_string())
        .unwrap_or_else(|| std::env::consts::OS.to_string());
    let mut s = format!("{cpu}, {cores} logical cores");
    if let Some(m) = mem_gib {
        let _ = write!(s, ", {m:.0} GiB");
    }
    let _ = write!(s, ", {os}");
    s
}

/// Output of a command run in the crate's directory, trimmed (empty if it fails).
fn command_output(program: &str, args: &[&str]) -> String {
    std::process::Command::new(program)
        .args(args)
        .current_dir(env!("CARGO_MANIFEST_DIR"))
        .output()
        .ok()
        .filter(|o| o.status.success())
        .map(|o| String::from_utf8_lossy(&o.stdout).trim().to_string())
        .unwrap_or_default()
}

/// The commit the program was run from (short hash, "+ local changes" when the tree is not
/// clean), or "unknown" outside a git checkout.
pub fn commit() -> String {
    let hash = command_output("git", &["rev-parse", "--short", "HEAD"]);
    if hash.is_empty() {
        return "unknown".into();
    }
    let dirty = !command_output("git", &["status", "--porcelain", "--untracked-files=no"]).is_empty();
    if dirty {
        format!("{hash} + local changes")
    } else {
        hash
    }
}

/// The compiler that built this program, e.g. "rustc 1.95.0 (...)" (as `rustc --version`
/// reports it on this machine).
pub fn compiler() -> String {
    let v = command_output("rustc", &["--version"]);
    if v.is_empty() {
        "rustc (version unknown)".into()
    } else {
        v
    }
}

/// Today's date and time in UTC as the system's `date` prints it ("2026-11-21 15:40 UTC").
pub fn date() -> String {
    let d = command_output("date", &["-u", "+%Y-%m-%d %H:%M UTC"]);
    if d.is_empty() {
        "unknown".into()
    } else {
        d
    }
}
