//! Integration tests of the `trb` command line: `fmu` packaging and `simulate` scenarios,
//! run as a separate process like a user does.

use std::collections::BTreeSet;
use std::io::Read;
use std::path::{Path, PathBuf};
use std::process::{Command, Output};
use trb::bearing::{Bearing, PRESETS};
use trb::model_description;

const EXE: &str = env!("CARGO_BIN_EXE_trb");

/// A scratch directory of its own for each test, removed when dropped.
struct Scratch(PathBuf);

impl Scratch {
    fn new(test: &str) -> Scratch {
        let dir = std::env::temp_dir().join(format!("trb-cli-{}-{test}", std::process::id()));
        let _ = std::fs::remove_dir_all(&dir);
        std::fs::create_dir_all(&dir).unwrap();
        Scratch(dir)
    }
    fn path(&self, name: &str) -> PathBuf {
        self.0.join(name)
    }
    fn write(&self, name: &str, text: &str) -> PathBuf {
        let p = self.path(name);
        std::fs::write(&p, text).unwrap();
        p
    }
}

impl Drop for Scratch {
    fn drop(&mut self) {
        let _ = std::fs::remove_dir_all(&self.0);
    }
}

fn trb(args: &[&str]) -> Output {
    Command::new(EXE).args(args).output().expect("run trb")
}

fn stderr(o: &Output) -> String {
    String::from_utf8_lossy(&o.stderr).into_owned()
}

fn stdout(o: &Output) -> String {
    String::from_utf8_lossy(&o.stdout).into_owned()
}

fn p(path: &Path) -> &str {
    path.to_str().unwrap()
}

fn read_zip(path: &Path) -> std::collections::BTreeMap<String, Vec<u8>> {
    let mut archive = zip::ZipArchive::new(std::fs::File::open(path).unwrap()).unwrap();
    let mut out = std::collections::BTreeMap::new();
    for i in 0..archive.len() {
        let mut f = archive.by_index(i).unwrap();
        let mut bytes = Vec::new();
        f.read_to_end(&mut bytes).unwrap();
        out.insert(f.name().to_string(), bytes);
    }
    out
}

fn xml_guid(xml: &str) -> String {
    xml.split(" guid=\"").nth(1).unwrap().split('"').next().unwrap().to_string()
}

#[test]
fn fmu_holds_exactly_the_required_entries_and_the_guid_of_its_bearing() {
    let s = Scratch::new("fmu");
    let out = s.path("TaperedRollerBearing.fmu");
    let o = trb(&["fmu", "--out", p(&out)]);
    assert!(o.status.success(), "trb fmu failed: {}", stderr(&o));
    assert!(!stderr(&o).contains("does not export"), "{}", stderr(&o));
    let entries = read_zip(&out);

    let mut want: BTreeSet<String> = [
        "modelDescription.xml",
        "binaries/linux64/TaperedRollerBearing.so",
        "resources/bearing.json",
        "documentation/index.html",
        "documentation/LICENSE.txt",
        "model.png",
    ]
    .iter()
    .map(|s| s.to_string())
    .collect();
    for (name, _) in PRESETS {
        want.insert(format!("resources/presets/{name}.json"));
    }
    want.insert("resources/presets/bearing.schema.json".to_string());
    let got: BTreeSet<String> = entries.keys().cloned().collect();
    assert_eq!(got, want);

    let bearing = Bearing::default_preset();
    let xml = String::from_utf8(entries["modelDescription.xml"].clone()).unwrap();
    let guid = model_description::guid(&bearing);
    assert_eq!(xml_guid(&xml), guid);
    assert_eq!(xml, model_description::generate(&bearing).0);
    assert!(xml.contains(r#"modelIdentifier="TaperedRollerBearing""#));
    assert!(xml.contains(r#"name="roller[17].Nfs""#) && !xml.contains(r#"name="roller[18].Nfs""#));

    // The packaged bearing is the preset text itself, and every preset is shipped verbatim.
    assert_eq!(entries["resources/bearing.json"], PRESETS[0].1.as_bytes());
    for (name, text) in PRESETS {
        assert_eq!(entries[&format!("resources/presets/{name}.json")], text.as_bytes(), "{name}");
    }
    assert_eq!(
        entries["resources/presets/bearing.schema.json"],
        trb::bearing::bearing_file_schema().as_bytes()
    );
    // The shared library is the crate's cdylib.
    let so = &entries["binaries/linux64/TaperedRollerBearing.so"];
    assert!(so.len() > 1000 && so.starts_with(b"\x7fELF"), "not an ELF shared library");

    // The documentation lists every variable and the sources.
    let html = String::from_utf8(entries["documentation/index.html"].clone()).unwrap();
    for (_, name, _) in trb::variables::expanded(bearing.roller_count) {
        assert!(html.contains(&format!("<code>{name}</code>")), "documentation misses {name}");
    }
    for key in ["[W25]", "[D19]", "[Y22]", "[L22]", "Lubricants 13(10):438", "fmpy", &guid] {
        assert!(html.contains(key), "documentation misses {key}");
    }
    for d in &bearing.documented_defaults {
        let escaped = d
            .replace('&', "&amp;")
            .replace('<', "&lt;")
            .replace('>', "&gt;")
            .replace('"', "&quot;");
        assert!(html.contains(&escaped), "documentation misses the documented default {d}");
    }

    // One summary line: path, bearing, rollers, GUID, size.
    let line = stdout(&o);
    assert_eq!(line.trim_end().lines().count(), 1, "{line}");
    for part in [p(&out), "TRB130x230", "17 rollers", guid.as_str()] {
        assert!(line.contains(part), "summary `{line}` misses {part}");
    }

    // Packaging is deterministic (a small stand-in library keeps this fast in debug builds,
    // where deflating the real one takes seconds).
    let lib = fake_library(&s);
    let (a, b) = (s.path("a.fmu"), s.path("b.fmu"));
    assert!(trb(&["fmu", "--library", p(&lib), "--out", p(&a)]).status.success());
    assert!(trb(&["fmu", "--library", p(&lib), "--out", p(&b)]).status.success());
    assert_eq!(std::fs::read(&a).unwrap(), std::fs::read(&b).unwrap());
    assert_eq!(
        read_zip(&a)["binaries/linux64/TaperedRollerBearing.so"],
        std::fs::read(&lib).unwrap()
    );
}

/// The section names and contents of an ELF64 little-endian file.
fn elf_sections(bytes: &[u8]) -> Vec<(String, &[u8])> {
    assert!(bytes.starts_with(b"\x7fELF\x02\x01"), "not a little-endian ELF64 file");
    let u16_at = |o: usize| u16::from_le_bytes(bytes[o..o + 2].try_into().unwrap()) as usize;
    let u32_at = |o: usize| u32::from_le_bytes(bytes[o..o + 4].try_into().unwrap()) as usize;
    let u64_at = |o: usize| u64::from_le_bytes(bytes[o..o + 8].try_into().unwrap()) as usize;
    let (shoff, shentsize, shnum, shstrndx) = (u64_at(0x28), u16_at(0x3a), u16_at(0x3c), u16_at(0x3e));
    let header = |i: usize| shoff + i * shentsize;
    let names = u64_at(header(shstrndx) + 0x18);
    (0..shnum)
        .map(|i| {
            let h = header(i);
            let name_at = names + u32_at(h);
            let end = bytes[name_at..].iter().position(|&b| b == 0).unwrap();
            let name = String::from_utf8_lossy(&bytes[name_at..name_at + end]).into_owned();
            // SHT_NOBITS (8) has no contents in the file
            let (offset, size) = (u64_at(h + 0x18), u64_at(h + 0x20));
            let contents = if u32_at(h + 4) == 8 {
                &bytes[0..0]
            } else {
                &bytes[offset..offset + size]
            };
            (name, contents)
        })
        .collect()
}

/// The CRC-32 that `.gnu_debuglink` records (IEEE 802.3, as zlib's crc32).
fn crc32(bytes: &[u8]) -> u32 {
    let mut crc = !0u32;
    for &b in bytes {
        crc ^= b as u32;
        for _ in 0..8 {
            crc = if crc & 1 == 1 { (crc >> 1) ^ 0xEDB8_8320 } else { crc >> 1 };
        }
    }
    !crc
}

fn objcopy_runs() -> bool {
    Command::new("objcopy").arg("--version").output().is_ok_and(|o| o.status.success())
}

#[test]
fn fmu_library_is_stripped_and_its_debug_information_kept_beside_the_fmu() {
    if !objcopy_runs() {
        eprintln!("skipping: no objcopy (binutils) on PATH; the FMU is packaged with its debug information");
        return;
    }
    let s = Scratch::new("strip");
    let out = s.path("Lean.fmu");
    let o = trb(&["fmu", "--out", p(&out)]);
    assert!(o.status.success(), "trb fmu failed: {}", stderr(&o));
    assert!(!stderr(&o).contains("could not be stripped"), "{}", stderr(&o));
    let debug_path = s.path("Lean.linux64.debug");
    assert!(stdout(&o).contains("debug symbols beside it: Lean.linux64.debug"), "{}", stdout(&o));
    if !cfg!(debug_assertions) {
        let size = std::fs::metadata(&out).unwrap().len();
        assert!(size <= 1_500_000, "the host-only FMU is {size} bytes, more than 1.5 MB");
    }

    // In the FMU: no debug sections, no static symbol table; the exported functions stay, and
    // .gnu_debuglink names the file beside the FMU with its CRC.
    let so = read_zip(&out).remove("binaries/linux64/TaperedRollerBearing.so").unwrap();
    let sections = elf_sections(&so);
    let names: Vec<&str> = sections.iter().map(|(n, _)| n.as_str()).collect();
    assert!(
        !names.iter().any(|n| n.starts_with(".debug_") || *n == ".symtab"),
        "packaged library keeps {names:?}"
    );
    assert!(names.contains(&".dynsym"), "{names:?}");
    for symbol in ["fmi2Instantiate", "fmi2DoStep", "fmi2GetVersion", "fmi2SerializeFMUstate"] {
        assert!(
            so.windows(symbol.len()).any(|w| w == symbol.as_bytes()),
            "{symbol} is not exported any more"
        );
    }
    let debug = std::fs::read(&debug_path).expect("the debug file beside the FMU");
    let link = sections.iter().find(|(n, _)| n == ".gnu_debuglink").expect(".gnu_debuglink").1;
    let name_end = link.iter().position(|&b| b == 0).unwrap();
    assert_eq!(&link[..name_end], b"Lean.linux64.debug");
    let crc_at = (name_end + 1).next_multiple_of(4);
    assert_eq!(u32::from_le_bytes(link[crc_at..crc_at + 4].try_into().unwrap()), crc32(&debug));
    // The debug file holds the line tables and the symbols.
    let debug_names: Vec<String> = elf_sections(&debug).into_iter().map(|(n, _)| n).collect();
    for section in [".debug_info", ".debug_line", ".symtab"] {
        assert!(
            debug_names.iter().any(|n| n == section),
            "the debug file lacks {section}: {debug_names:?}"
        );
    }

    // Packaging stays deterministic.
    let again = s.path("again/Lean.fmu");
    std::fs::create_dir_all(again.parent().unwrap()).unwrap();
    assert!(trb(&["fmu", "--out", p(&again)]).status.success());
    assert_eq!(std::fs::read(&out).unwrap(), std::fs::read(&again).unwrap());
    assert_eq!(debug, std::fs::read(s.path("again/Lean.linux64.debug")).unwrap());

    // Without a usable objcopy the library goes in as it is, with a warning, and a debug file
    // of an earlier packaging, which would not match, is removed.
    let o = Command::new(EXE)
        .args(["fmu", "--out", p(&out)])
        .env("OBJCOPY", s.path("no-such-objcopy"))
        .output()
        .unwrap();
    assert!(o.status.success(), "{}", stderr(&o));
    assert!(stderr(&o).contains("could not be stripped"), "{}", stderr(&o));
    assert!(!debug_path.exists(), "a stale debug file stays beside the FMU");
    let so = read_zip(&out).remove("binaries/linux64/TaperedRollerBearing.so").unwrap();
    assert!(elf_sections(&so).iter().any(|(n, _)| n == ".debug_info"));
}

/// A stand-in for the shared library, for tests about everything else in the archive.
fn fake_library(s: &Scratch) -> PathBuf {
    s.write("libfake.so", "\x7fELF stand-in exporting fmi2Instantiate fmi2DoStep fmi2GetVersion")
}

#[test]
fn fmu_of_preset_32008_has_23_rollers() {
    let s = Scratch::new("fmu32008");
    // --out may name an existing directory.
    let lib = fake_library(&s);
    let o = trb(&["fmu", "--bearing", "32008", "--library", p(&lib), "--out", p(&s.0)]);
    assert!(o.status.success(), "{}", stderr(&o));
    // ... to put the FMU in under its own model identifier.
    let fmu = s.path("TRB_32008.fmu");
    let entries = read_zip(&fmu);
    let xml = String::from_utf8(entries["modelDescription.xml"].clone()).unwrap();
    assert!(xml.contains(r#"modelName="TRB_32008""#) && xml.contains(r#"modelIdentifier="TRB_32008""#));
    assert!(entries.contains_key("binaries/linux64/TRB_32008.so"));
    assert!(!entries.contains_key("binaries/linux64/TaperedRollerBearing.so"));
    assert!(stdout(&o).contains(p(&fmu)) && stdout(&o).contains("modelIdentifier TRB_32008"));
    assert!(xml.contains(r#"name="roller[23].tilt""#));
    assert!(!xml.contains(r#"name="roller[24].tilt""#));
    let bearing = Bearing::preset("32008").unwrap();
    assert_eq!(xml_guid(&xml), model_description::guid(&bearing));
    assert_eq!(
        entries["resources/bearing.json"],
        PRESETS.iter().find(|(n, _)| *n == "32008").unwrap().1.as_bytes()
    );
    assert!(stdout(&o).contains("23 rollers"));
}

#[test]
fn fmu_of_a_bearing_file_packages_its_exact_text() {
    let s = Scratch::new("fmufile");
    let text = PRESETS[2].1.replace("\"name\": \"32008\"", "\"name\": \"MY-32008\"");
    let file = s.write("my.json", &text);
    let out = s.path("my.fmu");
    let lib = fake_library(&s);
    let o = trb(&["fmu", "--bearing", p(&file), "--library", p(&lib), "--out", p(&out)]);
    assert!(o.status.success(), "{}", stderr(&o));
    // (the stand-in library is no object file objcopy reads: it goes in as it is, saying so)
    let err = stderr(&o);
    assert!(
        !err.lines().any(|l| l.contains("warning") && !l.contains("could not be stripped")),
        "{err}"
    );
    let entries = read_zip(&out);
    assert_eq!(entries["resources/bearing.json"], text.as_bytes());
    assert!(stdout(&o).contains("MY-32008"));
}

#[test]
fn malformed_bearing_files_are_rejected_naming_the_field() {
    let s = Scratch::new("badbearing");
    let good = PRESETS[0].1;
    let missing = good.replace("  \"pitch_diameter_mm\": 177.91,\n", "");
    assert_ne!(missing, good);
    let wrong_type = good.replace("\"count\": 17", "\"count\": \"seventeen\"");
    assert_ne!(wrong_type, good);
    let bad_value = good.replace("\"length_mm\": 42.06", "\"length_mm\": -3");
    for (name, text, field) in [
        ("missing.json", missing, "pitch_diameter_mm"),
        ("wrong_type.json", wrong_type, "rollers.count"),
        ("bad_value.json", bad_value, "rollers.length_mm"),
        ("not_json.json", "{ this is not json".to_string(), "not_json.json"),
    ] {
        let file = s.write(name, &text);
        let out = s.path(&format!("{name}.fmu"));
        let o = trb(&["fmu", "--bearing", p(&file), "--out", p(&out)]);
        assert!(!o.status.success(), "{name} was accepted");
        let err = stderr(&o);
        assert!(err.contains(field), "{name}: stderr `{err}` does not name {field}");
        assert!(!err.contains("panicked"), "{name}: {err}");
        assert!(!out.exists(), "{name}: an FMU was written");
    }
    let o = trb(&["fmu", "--bearing", "NO-SUCH-BEARING"]);
    assert_eq!(o.status.code(), Some(2));
    assert!(stderr(&o).contains("NO-SUCH-BEARING"));
}

/// `--portable` cross-builds (tests/portable checks its FMU); here only what it refuses before
/// building anything: a bad bearing, and `--library` (the portable FMU builds its own).
#[test]
fn fmu_portable_refuses_a_bad_bearing_and_library_before_building() {
    let s = Scratch::new("fmuportable");
    let out = s.path("p.fmu");
    let o = trb(&["fmu", "--portable", "--bearing", "NO-SUCH-BEARING", "--out", p(&out)]);
    assert_eq!(o.status.code(), Some(2), "{}", stderr(&o));
    assert!(stderr(&o).contains("NO-SUCH-BEARING"), "{}", stderr(&o));
    let lib = fake_library(&s);
    let o = trb(&["fmu", "--portable", "--library", p(&lib), "--out", p(&out)]);
    assert_eq!(o.status.code(), Some(2), "{}", stderr(&o));
    assert!(stderr(&o).contains("--library"), "{}", stderr(&o));
    assert!(!out.exists());
}

const SMALL: &str = r#"{
  "description": "test: a short ramp",
  "bearing": "TRB130x230",
  "parameters": {"fidelity": 0, "slices": 12},
  "inputs": {
    "speed": 366.51914291880917,
    "Fx": 30000.0,
    "Fy": {"time": [0.0, 0.004, 0.01], "values": [0.0, 0.0, 10000.0]},
    "xi": {"time": [0.005, 0.01], "values": [0.0, 5.0e-5]}
  },
  "stop_time": 0.01,
  "step": 0.001,
  "outputs": ["frictionTorque", "cone.x", "Qo.max", "loadedRollers", "roller[17].Qi"]
}"#;

fn parse_csv(text: &str) -> (Vec<String>, Vec<Vec<f64>>) {
    let mut lines = text.lines();
    let head = lines.next().unwrap();
    let header = csv::ReaderBuilder::new()
        .has_headers(false)
        .from_reader(head.as_bytes())
        .records()
        .next()
        .unwrap()
        .unwrap()
        .iter()
        .map(str::to_string)
        .collect::<Vec<_>>();
    let rows = lines
        .map(|l| {
            l.split(',')
                .map(|v| v.parse::<f64>().unwrap_or_else(|_| panic!("`{v}` is not a number in `{l}`")))
                .collect::<Vec<_>>()
        })
        .collect();
    (header, rows)
}

/// The FMU's inputs in modelDescription order (the CSV's columns after `time`).
fn input_names() -> Vec<String> {
    trb::variables::expanded(1)
        .into_iter()
        .filter(|(_, _, v)| v.causality == trb::variables::Causality::Input)
        .map(|(_, n, _)| n)
        .collect()
}

#[test]
fn simulate_writes_header_and_n_plus_one_rows_reproducibly() {
    let s = Scratch::new("simulate");
    let scenario = s.write("small.json", SMALL);
    let csv = s.path("out.csv");
    let o = trb(&["simulate", p(&scenario), "--out", p(&csv), "--quiet"]);
    assert!(o.status.success(), "{}", stderr(&o));
    assert!(stdout(&o).is_empty(), "--quiet printed {}", stdout(&o));
    let text = std::fs::read_to_string(&csv).unwrap();
    let (header, rows) = parse_csv(&text);
    assert_eq!(
        header.join(","),
        format!(
            "time,{},frictionTorque,cone.x,Qo.max,loadedRollers,roller[17].Qi",
            input_names().join(",")
        )
    );
    assert_eq!(rows.len(), 11);
    for row in &rows {
        assert_eq!(row.len(), header.len());
        assert!(row.iter().all(|v| v.is_finite()), "{row:?}");
    }
    // Time grid ends exactly at stop_time; inputs follow the tables at the grid points.
    assert_eq!(rows[0][0], 0.0);
    assert_eq!(rows[10][0], 0.01);
    assert!(rows[4][5].abs() < 1e-9);
    assert_eq!(rows[10][5], 10000.0);
    assert!((rows[7][5] - 5000.0).abs() < 1e-9);
    assert_eq!(rows[10][2], 5.0e-5);
    // Integers are written as integers.
    let col = |name: &str| header.iter().position(|h| h == name).unwrap();
    let loaded = text.lines().nth(1).unwrap().split(',').nth(col("loadedRollers")).unwrap();
    assert!(!loaded.contains('.'), "loadedRollers written as `{loaded}`");
    // The load changes the outputs.
    let qo = col("Qo.max");
    assert!(rows[10][qo] > rows[0][qo]);

    let csv2 = s.path("out2.csv");
    let o = trb(&["simulate", p(&scenario), "--out", p(&csv2)]);
    assert!(o.status.success(), "{}", stderr(&o));
    assert!(stdout(&o).contains("11 rows"), "{}", stdout(&o));
    assert_eq!(
        std::fs::read(&csv).unwrap(),
        std::fs::read(&csv2).unwrap(),
        "re-run is not byte-identical"
    );
}

#[test]
fn simulate_writes_all_outputs_by_default() {
    let s = Scratch::new("alloutputs");
    let scenario = s.write("all.json", r#"{"bearing": "32008", "stop_time": 0.002, "step": 0.001}"#);
    let csv = s.path("all.csv");
    let o = trb(&["simulate", p(&scenario), "--out", p(&csv), "--quiet"]);
    assert!(o.status.success(), "{}", stderr(&o));
    let (header, rows) = parse_csv(&std::fs::read_to_string(&csv).unwrap());
    let outputs: Vec<String> = trb::variables::expanded(23)
        .into_iter()
        .filter(|(_, _, v)| v.causality == trb::variables::Causality::Output)
        .map(|(_, n, _)| n)
        .collect();
    let inputs = input_names();
    assert_eq!(header.len(), 1 + inputs.len() + outputs.len());
    assert_eq!(&header[1..1 + inputs.len()], &inputs[..]);
    assert_eq!(&header[1 + inputs.len()..], &outputs[..]);
    assert_eq!(rows.len(), 3);
}

#[test]
fn bad_scenarios_exit_2_naming_the_field() {
    let s = Scratch::new("badscenario");
    let cases: &[(&str, &str, &[&str])] = &[
        (
            "unknown_input.json",
            r#"{"stop_time": 0.01, "step": 0.001, "inputs": {"Fq": 1.0}}"#,
            &["inputs.Fq", "Fq"],
        ),
        (
            "unknown_parameter.json",
            r#"{"stop_time": 0.01, "step": 0.001, "parameters": {"slicez": 10}}"#,
            &["parameters.slicez"],
        ),
        (
            "unknown_output.json",
            r#"{"stop_time": 0.01, "step": 0.001, "outputs": ["frictionTorque", "torqueFriction"]}"#,
            &["outputs[1]", "torqueFriction"],
        ),
        (
            "non_increasing.json",
            r#"{"stop_time": 0.01, "step": 0.001, "inputs": {"Fy": {"time": [0.0, 0.005, 0.005], "values": [0, 1, 2]}}}"#,
            &["inputs.Fy.time", "strictly increasing"],
        ),
        ("zero_step.json", r#"{"stop_time": 0.01, "step": 0.0}"#, &["step"]),
        ("negative_step.json", r#"{"stop_time": 0.01, "step": -0.001}"#, &["step"]),
        (
            "wrong_type.json",
            r#"{"stop_time": 0.01, "step": 0.001, "parameters": {"slices": "many"}}"#,
            &["parameters.slices"],
        ),
        (
            "bool_type.json",
            r#"{"stop_time": 0.01, "step": 0.001, "parameters": {"skewModel": 1}}"#,
            &["parameters.skewModel"],
        ),
        (
            "out_of_range.json",
            r#"{"stop_time": 0.01, "step": 0.001, "parameters": {"slices": 0}}"#,
            &["slices"],
        ),
        (
            "real_range.json",
            r#"{"stop_time": 0.01, "step": 0.001, "parameters": {"mu": 5.0}}"#,
            &["mu"],
        ),
        (
            "roller_index.json",
            r#"{"stop_time": 0.01, "step": 0.001, "parameters": {"roller[18].dD": 0.0}}"#,
            &["roller[18].dD"],
        ),
        ("missing_stop.json", r#"{"step": 0.001}"#, &["stop_time"]),
        ("unknown_key.json", r#"{"stop_time": 0.01, "step": 0.001, "stop": 1}"#, &["stop"]),
        (
            "bad_bearing.json",
            r#"{"bearing": "nope.json", "stop_time": 0.01, "step": 0.001}"#,
            &["bearing", "nope.json"],
        ),
        ("not_json.json", r#"{"stop_time": 0.01,"#, &["not_json.json"]),
    ];
    for (name, text, needles) in cases {
        let file = s.write(name, text);
        let csv = s.path(&format!("{name}.csv"));
        let o = trb(&["simulate", p(&file), "--out", p(&csv)]);
        let err = stderr(&o);
        assert_eq!(o.status.code(), Some(2), "{name}: exit code {:?}, stderr {err}", o.status.code());
        for needle in *needles {
            assert!(err.contains(needle), "{name}: stderr `{err}` does not contain {needle}");
        }
        assert!(!err.contains("panicked"), "{name}: {err}");
        assert!(!csv.exists(), "{name}: a CSV was written for an invalid scenario");
    }
    // A scenario file that does not exist.
    let o = trb(&["simulate", p(&s.path("absent.json")), "--out", p(&s.path("x.csv"))]);
    assert_eq!(o.status.code(), Some(2));
}

#[test]
fn a_model_error_while_stepping_exits_1_naming_the_time_and_keeps_the_rows() {
    let s = Scratch::new("modelerror");
    // xi jumps beyond the model's range (+-0.5 deg) at t = 0.005.
    let scenario = s.write(
        "fail.json",
        r#"{"stop_time": 0.01, "step": 0.001, "outputs": ["cone.x"],
            "inputs": {"xi": {"time": [0.0, 0.0045, 0.005], "values": [0.0, 0.0, 0.02]}}}"#,
    );
    let csv = s.path("fail.csv");
    let o = trb(&["simulate", p(&scenario), "--out", p(&csv), "--quiet"]);
    let err = stderr(&o);
    assert_eq!(o.status.code(), Some(1), "{err}");
    assert!(err.contains("t = 0.005") && err.contains("xi"), "{err}");
    assert!(!err.contains("panicked"), "{err}");
    let (_, rows) = parse_csv(&std::fs::read_to_string(&csv).unwrap());
    assert_eq!(rows.len(), 5, "rows before the failure are kept");
}

#[test]
fn scenario_bearing_paths_are_relative_to_the_scenario_file() {
    let s = Scratch::new("relbearing");
    std::fs::create_dir_all(s.path("sub/bearings")).unwrap();
    s.write("sub/bearings/b.json", PRESETS[2].1);
    let scenario = s.write(
        "sub/rel.json",
        r#"{"bearing": "bearings/b.json", "stop_time": 0.001, "step": 0.001, "outputs": ["roller[23].Qi"]}"#,
    );
    let csv = s.path("rel.csv");
    let o = trb(&["simulate", p(&scenario), "--out", p(&csv), "--quiet"]);
    assert!(o.status.success(), "{}", stderr(&o));
    assert!(std::fs::read_to_string(&csv)
        .unwrap()
        .starts_with(&format!("time,{},roller[23].Qi\n", input_names().join(","))));
}

#[test]
fn every_shipped_scenario_runs() {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("scenarios");
    let s = Scratch::new("shipped");
    let mut files: Vec<PathBuf> = std::fs::read_dir(&dir)
        .unwrap()
        .map(|e| e.unwrap().path())
        .filter(|p| p.extension().is_some_and(|e| e == "json"))
        .collect();
    files.sort();
    assert!(files.len() >= 19, "expected the study scenarios in {}", dir.display());
    // Run them in parallel: each is an independent process.
    let children: Vec<(PathBuf, PathBuf, std::process::Child)> = files
        .into_iter()
        .map(|f| {
            let csv = s.path(&format!("{}.csv", f.file_stem().unwrap().to_string_lossy()));
            let child = Command::new(EXE)
                .args(["simulate", p(&f), "--out", p(&csv), "--quiet"])
                .stdout(std::process::Stdio::piped())
                .stderr(std::process::Stdio::piped())
                .spawn()
                .unwrap();
            (f, csv, child)
        })
        .collect();
    for (f, csv, child) in children {
        let o = child.wait_with_output().unwrap();
        assert!(o.status.success(), "{} failed: {}", f.display(), stderr(&o));
        let text = std::fs::read_to_string(&csv).unwrap();
        let (header, rows) = parse_csv(&text);
        assert!(rows.len() >= 2, "{}", f.display());
        assert!(header.iter().any(|h| h == "frictionTorque"), "{}", f.display());
        for row in &rows {
            assert!(row.iter().all(|v| v.is_finite()), "{}: non-finite value", f.display());
        }
    }
}

/// `bench --quick` on one scenario writes the generated section (targets, speedups, one
/// work-precision table) and its figure next to the document, keeping the hand-written text.
#[test]
fn bench_quick_writes_the_report_section_and_figure() {
    let dir = Scratch::new("bench_quick");
    let doc = dir.write("performance.md", "# Performance\n\nhand-written text\n");
    let o = trb(&["bench", "--quick", "--filter", "w25_axial", "--out", p(&doc)]);
    assert!(o.status.success(), "{}", stderr(&o));
    let text = std::fs::read_to_string(&doc).unwrap();
    assert!(text.starts_with("# Performance\n\nhand-written text\n"), "{text}");
    for needle in [
        "<!-- bench:begin -->",
        "quasi-static doStep",
        "one right-hand side",
        "FMU bookkeeping per doStep",
        "Speedup over the study's method",
        "#### w25_axial_3500rpm",
        "Gill RK + Milne–Hamming",
        "<!-- bench:end -->",
    ] {
        assert!(text.contains(needle), "no {needle:?} in {text}");
    }
    let svg = std::fs::read_to_string(dir.path("figures/bench_w25_axial_3500rpm.svg")).unwrap();
    assert!(svg.starts_with("<svg") && svg.contains("polyline"), "{svg}");
    // a second run replaces the section instead of appending another
    let o = trb(&["bench", "--quick", "--filter", "w25_axial", "--out", p(&doc)]);
    assert!(o.status.success(), "{}", stderr(&o));
    assert_eq!(std::fs::read_to_string(&doc).unwrap().matches("<!-- bench:begin -->").count(), 1);
    assert_eq!(trb(&["bench", "--repeats", "0"]).status.code(), Some(2));
}

/// `study validate --quick` writes validation.md with every section, both traction columns
/// and no non-finite number (about 30 s in release: three 10 ms dynamic runs per traction law).
#[test]
fn study_validate_quick_writes_every_section() {
    let dir = Scratch::new("validate_quick");
    let o = trb(&["study", "validate", "--quick", "--docs", p(&dir.0)]);
    assert!(o.status.success(), "{}", stderr(&o));
    let text = std::fs::read_to_string(dir.path("validation.md")).unwrap();
    for needle in [
        "# Validation",
        "## 1. [W25]",
        "### Fig. 6",
        "### Fig. 10",
        "### Fig. 11",
        "### Energy balance per run",
        "### The [W25] cases at the three fidelities",
        "**The reference's tolerance.**",
        "**Cage slip at light load.**",
        "## 2. [D19]",
        "## 3. [L22]",
        "### Table 3",
        "## 4. [Y22]",
        "## 5. Friction torque against the SKF",
        "## 6. [L22]'s friction torques",
        "## 7. In plain words",
        "## 8. Lubricant supply",
        "### Greased-bearing skew",
        "product, traction 0",
        "product, traction 1",
        "product (dry)",
    ] {
        assert!(text.contains(needle), "no {needle:?} in validation.md");
    }
    let words: Vec<&str> = text.split(|c: char| !c.is_alphanumeric()).collect();
    for bad in ["NaN", "nan", "inf", "Infinity"] {
        assert!(!words.contains(&bad), "{bad} in validation.md");
    }
    assert!(!text.contains("Not computed"), "a case failed:\n{text}");
}

/// `study defects --quick` writes defects.md and its figures for the cup, the cone and a roller;
/// the envelope of each spall's signal peaks at its kinematic defect frequency within 1 %
/// (the outer-race, the inner-race, twice the roller's spin; four 0.05 s dynamic runs).
#[test]
fn study_defects_quick_finds_the_defect_frequencies() {
    let dir = Scratch::new("defects_quick");
    let o = trb(&["study", "defects", "--quick", "--docs", p(&dir.0)]);
    assert!(o.status.success(), "{}", stderr(&o));
    let text = std::fs::read_to_string(dir.path("defects.md")).unwrap();
    for needle in [
        "## The characteristic frequencies",
        "## Cup (outer race)",
        "## Cone (inner race)",
        "## Roller",
        "## The healthy bearing",
        "| Z × FTF (kinematic) |",
    ] {
        assert!(text.contains(needle), "no {needle:?} in defects.md:\n{text}");
    }
    for location in ["cup", "cone", "roller"] {
        for name in ["time", "spectrum", "envelope"] {
            let svg = std::fs::read_to_string(dir.path(&format!("figures/defects_{location}_{name}.svg"))).unwrap();
            assert!(svg.starts_with("<svg") && svg.contains("polyline"), "{location} {name}: {svg}");
        }
    }
    // | BPFO | kinematic (Hz) | peak (Hz) | error (%) | ...: each location's own line
    for line in ["BPFO", "BPFI", "2 × BSF"] {
        let row = text
            .lines()
            .find(|l| l.starts_with(&format!("| {line} |")))
            .unwrap_or_else(|| panic!("no {line} row in:\n{text}"));
        let cells: Vec<&str> = row.split('|').map(str::trim).collect();
        let (kinematic, found): (f64, f64) = (cells[2].parse().unwrap(), cells[3].parse().unwrap());
        assert!((found / kinematic - 1.0).abs() < 0.01, "{row}");
    }
    let words: Vec<&str> = text.split(|c: char| !c.is_alphanumeric()).collect();
    for bad in ["NaN", "nan", "inf", "Infinity"] {
        assert!(!words.contains(&bad), "{bad} in defects.md");
    }
}

#[test]
fn bearing_show_prints_every_preset_as_a_file_fmu_accepts() {
    let s = Scratch::new("bearing_show");
    for (name, text) in trb::bearing::PRESETS {
        let o = trb(&["bearing", "show", name]);
        assert!(o.status.success(), "{name}: {}", stderr(&o));
        assert_eq!(stdout(&o), *text, "{name}: not the preset's text");
        // a file written with --out is a bearing file the FMU packager takes
        let file = s.path(&format!("{name}.json"));
        let o = trb(&["bearing", "show", &name.to_lowercase(), "--out", p(&file)]);
        assert!(o.status.success(), "{name}: {}", stderr(&o));
        let parsed = trb::bearing::Bearing::from_json(&std::fs::read_to_string(&file).unwrap()).unwrap();
        assert_eq!(parsed.name, *name);
    }
    let o = trb(&["bearing", "show", "no-such-bearing"]);
    assert_eq!(o.status.code(), Some(2));
    assert!(stderr(&o).contains("presets are"), "{}", stderr(&o));
}

/// `trb bearing estimate` with the catalogues' own flags: the table, a bearing file the FMU
/// packager takes, the same bearing from a file that carries the catalogue block, and bad data
/// refused with exit code 2 naming every bad field.
#[test]
fn bearing_estimate_builds_a_bearing_from_catalogue_data() {
    let s = Scratch::new("bearing_estimate");
    let file = s.path("30206.json");
    let flags = [
        "bearing", "estimate", "--d", "30", "--D", "62", "--T", "17.25", "--B", "16", "--C", "14", "--Cr", "43000", "--e", "0.37", "--Y",
        "1.6", "--name", "30206",
    ];
    let o = trb(&[&flags[..], &["--out", p(&file)]].concat());
    assert!(o.status.success(), "{}", stderr(&o));
    let table = stdout(&o);
    for needle in ["rollers Z", "roller mean diameter", "fill factor", "C_r from geometry", "43000 N"] {
        assert!(table.contains(needle), "no {needle:?} in\n{table}");
    }
    let estimated = trb::bearing::Bearing::from_json(&std::fs::read_to_string(&file).unwrap()).unwrap();
    assert_eq!(estimated.name, "30206");
    // without --out: the file on stdout, the table on stderr
    let o = trb(&flags);
    assert!(o.status.success() && stderr(&o).contains("rollers Z"), "{}", stderr(&o));
    assert_eq!(stdout(&o), std::fs::read_to_string(&file).unwrap());

    // a bearing file with the catalogue block packs into an FMU of the same bearing
    let block = s.path("30206-catalogue.json");
    std::fs::write(
        &block,
        r#"{"name": "30206", "kind": "tapered", "catalogue": {"d_mm": 30, "D_mm": 62, "T_mm": 17.25, "B_mm": 16, "C_mm": 14, "Cr_N": 43000, "e": 0.37, "Y": 1.6}}"#,
    )
    .unwrap();
    let fmu = s.path("30206.fmu");
    let lib = fake_library(&s);
    let o = trb(&["fmu", "--bearing", p(&block), "--library", p(&lib), "--out", p(&fmu)]);
    assert!(o.status.success(), "{}", stderr(&o));
    let xml = String::from_utf8(read_zip(&fmu)["modelDescription.xml"].clone()).unwrap();
    let last = format!(r#"name="roller[{}].tilt""#, estimated.roller_count);
    assert!(xml.contains(&last), "no {last}");
    let from_block = trb::bearing::Bearing::from_name_or_file(p(&block)).unwrap();
    assert_eq!(from_block.roller_count, estimated.roller_count);
    assert_eq!(from_block.roller_length, estimated.roller_length);
    assert_eq!(from_block.cone_angle, estimated.cone_angle);

    for (bad, fields) in [
        (vec!["--D", "25"], vec!["--D"]),
        (vec!["--T", "13"], vec!["--T"]),
        (vec!["--e", "1.4"], vec!["--e"]),
        (vec!["--Cr", "900000"], vec!["--Cr"]),
        (vec!["--d", "NaN", "--Cr", "-5"], vec!["--d", "--Cr"]),
    ] {
        let mut args: Vec<&str> = flags.to_vec();
        for pair in bad.chunks(2) {
            let at = args.iter().position(|a| *a == pair[0]).unwrap();
            args[at + 1] = pair[1];
        }
        let o = trb(&args);
        assert_eq!(o.status.code(), Some(2), "{bad:?}: {}", stderr(&o));
        for field in fields {
            assert!(stderr(&o).contains(&format!("{field}:")), "{bad:?}: {}", stderr(&o));
        }
    }
}

/// The `<ScalarVariable ...>` line of `name` and the type element on the line after it.
fn scalar_variable<'a>(xml: &'a str, name: &str) -> (&'a str, &'a str) {
    let needle = format!(r#"<ScalarVariable name="{name}" "#);
    let mut lines = xml.lines().skip_while(|l| !l.contains(&needle));
    let head = lines.next().unwrap_or_else(|| panic!("no variable {name}"));
    (head, lines.next().unwrap())
}

#[test]
fn fmu_enumerations_as_integers_declares_every_enumeration_an_integer() {
    let s = Scratch::new("fmuints");
    let lib = fake_library(&s);
    let (plain, ints) = (s.path("plain.fmu"), s.path("ints.fmu"));
    assert!(trb(&["fmu", "--library", p(&lib), "--out", p(&plain)]).status.success());
    let o = trb(&["fmu", "--enumerations-as-integers", "--library", p(&lib), "--out", p(&ints)]);
    assert!(o.status.success(), "{}", stderr(&o));
    let (plain, ints) = (read_zip(&plain), read_zip(&ints));
    let xml_of = |e: &std::collections::BTreeMap<String, Vec<u8>>| String::from_utf8(e["modelDescription.xml"].clone()).unwrap();
    let (plain_xml, xml) = (xml_of(&plain), xml_of(&ints));
    assert!(
        !plain.contains_key("resources/packaging.json"),
        "a plain FMU has no packaging options"
    );
    assert_eq!(ints["resources/packaging.json"], b"{\n  \"enumerations_as_integers\": true\n}\n");
    assert!(
        !xml.contains("<Enumeration") && !xml.contains("<TypeDefinitions>"),
        "an Enumeration is left"
    );

    let bearing = Bearing::default_preset();
    let mut enumerations = 0;
    for (vr, name, row) in trb::variables::expanded(bearing.roller_count) {
        let (plain_head, plain_type) = scalar_variable(&plain_xml, &name);
        let (head, ty) = scalar_variable(&xml, &name);
        assert!(head.contains(&format!(r#"valueReference="{vr}""#)), "{head}");
        if row.enumeration.is_none() {
            assert_eq!((head, ty), (plain_head, plain_type), "{name} changed");
            continue;
        }
        enumerations += 1;
        // Same range and start; the items' values and names in the description.
        let declared = format!(r#" declaredType="{}""#, row.enumeration.unwrap().name);
        assert_eq!(ty, plain_type.replace("<Enumeration", "<Integer").replace(&declared, ""), "{name}");
        assert!(ty.contains(r#" min="0""#) && ty.contains(" max=") && ty.contains(" start="), "{ty}");
        let items = trb::packaging::items(row);
        assert!(head.contains(&format!("(values: {items})")), "{head}");
    }
    assert!(enumerations >= 10, "{enumerations} enumeration parameters");
    let (head, ty) = scalar_variable(&xml, "fidelity");
    assert!(head.contains("(values: 0 quasiStatic, 1 dynamic, 2 quasiDynamic)"), "{head}");
    assert_eq!(ty.trim(), r#"<Integer min="0" max="2" start="0"/>"#);

    // One source of truth: the XML is the generator's with that switch, its GUID what the
    // binary expects from the packaged options.
    let packaging = trb::packaging::Packaging {
        enumerations_as_integers: true,
        start: Vec::new(),
    };
    let (want_xml, guid) = model_description::generate_with(&bearing, &packaging).unwrap();
    assert_eq!(xml, want_xml);
    assert_ne!(guid, model_description::guid(&bearing));
    assert!(stdout(&o).contains(&guid));
}

#[test]
fn fmu_set_packages_start_values_checked_against_the_variable() {
    let s = Scratch::new("fmuset");
    let lib = fake_library(&s);
    let out = s.path("set.fmu");
    let o = trb(&[
        "fmu",
        "--library",
        p(&lib),
        "--out",
        p(&out),
        "--set",
        "fidelity=2",
        "--set",
        "supply=grease",
        "--set",
        "mu=0.25",
        "--set",
        "skewModel=false",
        "--set",
        "roller[3].dD=-2e-6",
        "--set",
        "supply=oilAir",
    ]);
    assert!(o.status.success(), "{}", stderr(&o));
    let entries = read_zip(&out);
    let xml = String::from_utf8(entries["modelDescription.xml"].clone()).unwrap();
    for (name, start) in [
        ("fidelity", "2"),
        ("supply", "3"),
        ("mu", "0.25"),
        ("skewModel", "false"),
        ("roller[3].dD", "-2e-6"),
    ] {
        let (_, ty) = scalar_variable(&xml, name);
        assert!(ty.contains(&format!(r#" start="{start}""#)), "{name}: {ty}");
    }
    assert!(xml.contains(r#"<Enumeration declaredType="Fidelity" min="0" max="2" start="2"/>"#));
    let json: serde_json::Value = serde_json::from_slice(&entries["resources/packaging.json"]).unwrap();
    assert_eq!(
        json,
        serde_json::json!({"start": {"fidelity": 2, "mu": 0.25, "roller[3].dD": -2e-6, "skewModel": false, "supply": 3}})
    );
    // The documentation's variable table shows the packaged start.
    let html = String::from_utf8(entries["documentation/index.html"].clone()).unwrap();
    assert!(html.contains("roller[3].dD"));

    for (set, needle) in [
        ("nosuch=1", "unknown variable `nosuch`"),
        ("speed=100", "`speed` is an input, not a parameter"),
        ("powerLoss=1", "`powerLoss` is an output, not a parameter"),
        ("mu=high", "`mu`: expected a number"),
        ("mu=2.5", "`mu` = 2.5 is out of range: it must be [0, 2]"),
        (
            "fidelity=3",
            "`fidelity` = 3 is out of range: it must be [0, 2] (0 quasiStatic, 1 dynamic, 2 quasiDynamic)",
        ),
        (
            "fidelity=veryFast",
            "`fidelity`: expected an item of Fidelity: 0 quasiStatic, 1 dynamic, 2 quasiDynamic",
        ),
        ("slices=1", "`slices` = 1 is out of range"),
        ("skewModel=yes", "`skewModel`: expected true or false"),
        ("roller[18].dD=0", "unknown variable `roller[18].dD`"),
        ("fidelity", "not NAME=VALUE"),
    ] {
        let bad = s.path("bad.fmu");
        let o = trb(&["fmu", "--library", p(&lib), "--out", p(&bad), "--set", set]);
        assert_eq!(o.status.code(), Some(2), "--set {set}: {}", stderr(&o));
        assert!(stderr(&o).contains(needle), "--set {set}: `{}` misses {needle}", stderr(&o));
        assert!(!stderr(&o).contains("panicked"));
        assert!(!bad.exists(), "--set {set}: an FMU was written");
    }
}

#[test]
fn fmu_of_another_bearing_goes_by_default_to_its_own_file() {
    let s = Scratch::new("fmuownfile");
    let lib = fake_library(&s);
    let name = format!("CLI test {}", std::process::id());
    let text = PRESETS[2].1.replace("\"name\": \"32008\"", &format!("\"name\": \"{name}\""));
    let file = s.write("bearing.json", &text);
    let o = trb(&["fmu", "--bearing", p(&file), "--library", p(&lib)]);
    assert!(o.status.success(), "{}", stderr(&o));
    let id = format!("TRB_CLI_test_{}", std::process::id());
    assert_eq!(model_description::model_identifier(&Bearing::from_json(&text).unwrap()), id);
    // <target dir>/fmu/<modelIdentifier>.fmu, named in the summary
    let target = Path::new(EXE).parent().unwrap().parent().unwrap();
    let fmu = target.join("fmu").join(format!("{id}.fmu"));
    let written = fmu.is_file();
    let _ = std::fs::remove_file(&fmu);
    let _ = std::fs::remove_file(fmu.with_extension("linux64.debug"));
    assert!(written, "{} not written; stdout {}", fmu.display(), stdout(&o));
    assert!(
        stdout(&o).starts_with(&format!("{}: modelIdentifier {id}, bearing {name}", fmu.display())),
        "{}",
        stdout(&o)
    );
}

/// The comma-separated names in `text` between `before` and the next `)`, whitespace (and
/// the help's line wrapping) collapsed.
fn listed_after(text: &str, before: &str) -> Vec<String> {
    let flat = text.split_whitespace().collect::<Vec<_>>().join(" ");
    let rest = flat.split(before).nth(1).unwrap_or_else(|| panic!("`{before}` not in `{flat}`"));
    rest.split(')').next().unwrap().split(", ").map(str::to_string).collect()
}

#[test]
fn presets_agree_in_the_table_the_help_the_error_and_the_readme() {
    let table: Vec<String> = PRESETS.iter().map(|(n, _)| n.to_string()).collect();
    assert!(table.contains(&"TRB130x230-W25".to_string()));
    let help = trb(&["fmu", "--help"]);
    assert!(help.status.success());
    assert_eq!(listed_after(&stdout(&help), "a preset ("), table, "fmu --help");
    let show = trb(&["bearing", "show", "--help"]);
    let line = stdout(&show)
        .lines()
        .find(|l| l.contains("The preset's name: "))
        .unwrap_or_default()
        .to_string();
    assert_eq!(
        listed_after(&format!("{line})"), "The preset's name: "),
        table,
        "bearing show --help"
    );
    let unknown = trb(&["fmu", "--bearing", "NO-SUCH-PRESET"]);
    assert_eq!(listed_after(&stderr(&unknown), "neither a preset ("), table, "the error message");
    // README, "Presets and your bearing": the first column of its table, in any order.
    let readme = std::fs::read_to_string(concat!(env!("CARGO_MANIFEST_DIR"), "/README.md")).unwrap();
    let section = readme
        .split("## Presets and your bearing")
        .nth(1)
        .expect("README has the presets section");
    let mut listed: Vec<String> = section
        .lines()
        .skip_while(|l| !l.starts_with('|'))
        .take_while(|l| l.starts_with('|'))
        .filter_map(|l| l.strip_prefix("| `"))
        .map(|l| l.split('`').next().unwrap().to_string())
        .collect();
    let mut want = table.clone();
    listed.sort();
    want.sort();
    assert_eq!(listed, want, "README's preset table");
}

#[test]
fn demo_says_which_files_and_plot_it_writes() {
    let s = Scratch::new("demo");
    let csv = s.path("demo.csv");
    let o = trb(&["demo", "--skip-dynamic", "--csv", p(&csv)]);
    assert!(o.status.success(), "{}", stderr(&o));
    let first = stdout(&o).lines().next().unwrap_or_default().to_string();
    assert!(
        first.starts_with(&format!("Writes {}", p(&csv))) && first.contains("no plot"),
        "{first}"
    );
    assert!(csv.is_file());
}
