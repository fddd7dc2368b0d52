//! The model calls the pure-Rust `libm` crate (or `fastmath`) for every transcendental
//! function, never the f64 methods that go to the platform's C library: glibc and the
//! Windows CRT differ by 1-4 ulp on 0.1-8 % of arguments, which the dynamic model amplifies
//! to 1e-8 between the FMU's Linux and Windows binaries (tests/portable compares the two to
//! 1e-12). This guards the rule in the library sources (the `trb` program's own modules,
//! src/cli, and test modules are free to use std).

use std::path::Path;

const STD_METHODS: &[&str] = &[
    "sin", "cos", "tan", "sin_cos", "asin", "acos", "atan", "atan2", "exp", "exp2", "exp_m1", "ln", "ln_1p", "log10", "log2", "powf",
    "tanh", "sinh", "cosh", "asinh", "acosh", "atanh", "cbrt", "hypot",
];

fn library_sources(dir: &Path, out: &mut Vec<std::path::PathBuf>) {
    for entry in std::fs::read_dir(dir).expect("read src") {
        let path = entry.expect("entry").path();
        if path.is_dir() {
            if path.file_name().is_some_and(|n| n != "cli") {
                library_sources(&path, out);
            }
        } else if path.extension().is_some_and(|e| e == "rs") && path.file_name().is_some_and(|n| n != "main.rs" && n != "tests.rs") {
            out.push(path);
        }
    }
}

#[test]
fn the_library_calls_no_platform_libm() {
    let src = Path::new(env!("CARGO_MANIFEST_DIR")).join("src");
    let mut files = Vec::new();
    library_sources(&src, &mut files);
    assert!(files.len() > 20, "only {} library sources found", files.len());
    let mut found = Vec::new();
    for file in &files {
        let text = std::fs::read_to_string(file).expect("read source");
        let code = text.split("#[cfg(test)]").next().unwrap_or("");
        for (n, line) in code.lines().enumerate() {
            let line = line.split("//").next().unwrap_or("");
            for m in STD_METHODS {
                if line.contains(&format!(".{m}(")) {
                    found.push(format!("{}:{}: .{m}(", file.strip_prefix(&src).unwrap().display(), n + 1));
                }
            }
        }
    }
    assert!(
        found.is_empty(),
        "calls of the platform's libm (use libm::… or fastmath):\n{}",
        found.join("\n")
    );
}
