//! `documentation/index.html` of the FMU: what the element models and what it does not,
//! the fidelity levels, the packaged bearing's data and documented defaults, every variable
//! of this bearing's FMU (from the variable table, with start values read back from the
//! generated modelDescription.xml), the sources, and how to use the FMU from fmpy.

use std::collections::HashMap;
use std::fmt::Write as _;
use trb::bearing::{Bearing, ContactLaw, Kind, LubricationModel};
use trb::model::ModelError;
use trb::model_description::model_identifier;
use trb::simulation::{AccessError, Simulation};
use trb::variables::{self, Causality, Variable};
use trb::variables_doc::{causality_name, range, type_name, variability_name};

/// The four studies the model is written from (full citations as in MODEL.md).
pub const SOURCES: &[(&str, &str)] = &[
    (
        "W25",
        "Wu, Kang, Deng, \"An analysis on negative effects of shaft deflection on angular misalignment \
         of rollers inside tapered roller bearing\", Lubricants 13(10):438, 2025. Dynamic TRB model \
         with shaft deflection: the core model of the element.",
    ),
    (
        "D19",
        "\"Dry-lubricated TRB frictional torque with roller skewing\", Friction 7(6):551\u{2013}563, 2019. \
         Quasi-static skew equilibrium with cage pocket limit; torque components.",
    ),
    (
        "Y22",
        "Yu et al., \"Contact load and preload characteristics of cylindrical roller bearings with \
         triple-lobe raceway\", Mechanics & Industry 23:19, 2022. Quasi-static CRB, lobed raceway, \
         damped Newton\u{2013}Raphson.",
    ),
    (
        "L22",
        "Liu, Fan, Wang, Liu, \"Friction torque of a TRB considering the geometric homogeneity of \
         rollers\", Lubricants 10(7):154, 2022. Quasi-static TRB with roller diameter deviations.",
    ),
];

pub fn esc(s: &str) -> String {
    s.replace('&', "&amp;")
        .replace('<', "&lt;")
        .replace('>', "&gt;")
        .replace('"', "&quot;")
}

fn xml_unescape(s: &str) -> String {
    s.replace("&quot;", "\"")
        .replace("&lt;", "<")
        .replace("&gt;", ">")
        .replace("&apos;", "'")
        .replace("&amp;", "&")
}

/// The value of attribute `name` in one XML tag text.
fn attr(tag: &str, name: &str) -> Option<String> {
    let needle = format!(" {name}=\"");
    let start = tag.find(&needle)? + needle.len();
    let end = tag[start..].find('"')? + start;
    Some(xml_unescape(&tag[start..end]))
}

/// Start values by variable name, read from the generated model description (each
/// `<ScalarVariable>` is followed by its type element carrying `start`).
pub fn start_values(xml: &str) -> HashMap<String, String> {
    let mut out = HashMap::new();
    let mut current: Option<String> = None;
    for line in xml.lines() {
        let line = line.trim();
        if line.starts_with("<ScalarVariable ") {
            current = attr(line, "name");
        } else if let Some(name) = current.take() {
            if let Some(start) = attr(line, "start") {
                out.insert(name, start);
            }
        }
    }
    out
}

fn mm(v: f64) -> String {
    format!("{} mm", trim(v * 1e3, 4))
}
fn deg(v: f64) -> String {
    format!("{} deg", trim(v.to_degrees(), 4))
}
fn um(v: f64) -> String {
    format!("{} \u{b5}m", trim(v * 1e6, 3))
}
/// A number with at most `digits` decimals and no trailing zeros.
fn trim(v: f64, digits: usize) -> String {
    let s = format!("{v:.digits$}");
    if s.contains('.') {
        s.trim_end_matches('0').trim_end_matches('.').to_string()
    } else {
        s
    }
}

/// Whether the model of `fidelity` (1 dynamic, 2 quasi-dynamic) can be initialised in this
/// build.
fn dynamic_status(bearing: &Bearing, fidelity: i32) -> String {
    let mut sim = Simulation::new(bearing.clone());
    if let Err(e) = sim.set_integer(variables::FIDELITY, fidelity) {
        return format!("not available in this build ({})", access_message(&e));
    }
    match sim.initialize(0.0) {
        Ok(_) => "available".into(),
        Err(ModelError::InvalidParameter { name, message }) if name == "fidelity" => {
            format!("<strong>not available in this build</strong>: {}", esc(&message))
        }
        Err(e) => format!(
            "available (initialisation at the default operating point reported: {})",
            esc(&e.to_string())
        ),
    }
}

fn access_message(e: &AccessError) -> String {
    esc(&e.to_string())
}

const STYLE: &str = "body{font-family:system-ui,sans-serif;max-width:70em;margin:2em auto;padding:0 1em;line-height:1.45;color:#222}\
table{border-collapse:collapse;margin:0.5em 0 1.5em 0;font-size:0.92em}\
th,td{border:1px solid #bbb;padding:0.2em 0.5em;text-align:left;vertical-align:top}\
th{background:#eee}code,pre{font-family:ui-monospace,monospace;font-size:0.92em}\
pre{background:#f6f6f6;padding:0.7em;overflow-x:auto}td.num{text-align:right;white-space:nowrap}\
details{margin:0.3em 0 1em 0}summary{cursor:pointer}";

/// The documentation page of the FMU of `bearing` (`bearing_json` is the packaged text,
/// `xml`/`guid` the generated model description).
pub fn generate(bearing: &Bearing, bearing_json: &str, xml: &str, guid: &str) -> String {
    let z = bearing.roller_count;
    let starts = start_values(xml);
    let id = model_identifier(bearing);
    let mut h = String::new();
    let _ = writeln!(h, "<!DOCTYPE html>\n<html lang=\"en\">\n<head>\n<meta charset=\"utf-8\">");
    let _ = writeln!(h, "<title>{id} FMU \u{2014} bearing {}</title>", esc(&bearing.name));
    let _ = writeln!(h, "<style>{STYLE}</style>\n</head>\n<body>");
    let _ = writeln!(h, "<h1>{id}: tapered roller bearing element</h1>");
    let _ = writeln!(
        h,
        "<p>FMI 2.0 Co-Simulation FMU, version {}, packaged for bearing <strong>{}</strong> ({} rollers). \
         GUID <code>{}</code>.</p>",
        env!("CARGO_PKG_VERSION"),
        esc(&bearing.name),
        z,
        esc(guid)
    );
    let _ = writeln!(h, "<p>{}</p>", esc(&bearing.description));
    let _ = writeln!(
        h,
        "<p>Contents: <a href=\"#models\">what it models</a> \u{b7} <a href=\"#limits\">what it does not</a> \u{b7} \
         <a href=\"#fidelity\">fidelity levels</a> \u{b7} <a href=\"#bearing\">the bearing</a> \u{b7} \
         <a href=\"#drivetrain\">drivetrain block</a> \u{b7} \
         <a href=\"#variables\">variables</a> \u{b7} <a href=\"#fmpy\">use from fmpy</a> \u{b7} \
         <a href=\"#sources\">sources</a></p>"
    );

    // ----------------------------------------------------------------------------------
    let _ = writeln!(h, "<h2 id=\"models\">What the element models</h2>");
    let _ = writeln!(
        h,
        "<p>One rolling bearing between a rotating shaft (the cone, or inner ring) and a housing \
         (the cup, or outer ring), fixed or turning (<code>cupSpeed</code>: wheel hubs, idlers), as a \
         block for drivetrain and system simulation. The master \
         supplies the cone and cup speeds, the external forces on the cone (axial <code>Fx</code>, radial \
         <code>Fy</code>, <code>Fz</code>) or a prescribed axial displacement, and the shaft deflection \
         angles <code>xi</code>, <code>zeta</code>. The element returns the cone displacement, the \
         reaction forces and moments, the friction torque with its raceway, flange and cage parts, the \
         power loss, the roller loads, attitudes (tilt, skew) and moments of every roller, and the cage \
         speed. All values are SI (m, N, s, rad, Pa); angles display in deg and speeds in rpm.</p>"
    );
    let _ = writeln!(h, "<ul>");
    for item in [
        "Geometry: roller count, length, mean diameter and half-cone angle, spherical roller end, pitch \
         diameter, cone, cup and flange contact angles, roller crowning, mounted clearance, a lobed outer \
         raceway <code>rho(psi) = r0 + ee/2 - ee/2 cos(N psi)</code> [Y22] and per-roller diameter \
         deviations <code>roller[j].dD</code> [L22]. A cylindrical roller bearing is the same element with \
         zero contact angles and no flange load.",
        "Contacts: each roller/raceway line contact is cut into <code>slices</code> slices; only slices \
         with positive interference carry load. Line contact law per bearing: Johnson [W25] or Palmgren \
         (whole-roller stiffness divided by the slice count) [D19, Y22, L22]. Flange / spherical roller \
         end: Hertz point contact [W25]. Cage pocket (dynamic model): hydrodynamic / Hertz with damping [W25].",
        "Quasi-static equilibrium (fidelity 0): cone translations and every roller's displacement and \
         tilt from force and moment balance of sliced raceway loads, flange load, centrifugal force and \
         gyroscopic moment, solved by a damped Newton\u{2013}Raphson method with an exact Jacobian, \
         warm-started from the previous step [Y22]. Axial force preload or axial displacement preload.",
        "Lubrication and friction: EHL film thickness (Hamrock line contact, Chittenden point contact), \
         film ratio against the composite roughness, boundary / mixed / full-film traction, viscous flange \
         traction [W25]; or dry Coulomb friction with one coefficient <code>mu</code> [D19]. Quasi-static \
         friction torque with rolling resistance, sliding friction at a cage slip rate \
         <code>cageSlipRate</code> and flange sliding [L22, rederived from Harris 1966].",
        "Drivetrain block: with <code>causality</code> = 1 the cone's displacement relative to the cup \
         (<code>displacement.x/y/z</code>) is the input and the five reactions <code>reaction.Fx/Fy/Fz/My/Mz</code> \
         the outputs, at both fidelities; the 5\u{d7}5 tangent stiffness <code>stiffness[i,j]</code> \
         = d(reaction_i)/d(q_j), q = (x, y, z, xi, zeta), in both causalities. See \
         <a href=\"#drivetrain\">drivetrain block</a>.",
        "Fatigue rating: <code>rating.C</code> (ISO 281 basic dynamic load rating from the geometry), \
         <code>life.L10</code> (ISO 281 basic rating life at the carried loads' equivalent load and the \
         speed), <code>life.L10r</code> (ISO/TS 16281 basic reference rating life from the model's own \
         slice loads, so tilt, clearance, profile and diameter deviations count) and <code>life.L10m</code> \
         (ISO 281 modified rating life a_ISO L10 from the oil's viscosity ratio <code>oil.kappa</code> and the \
         contamination factor <code>contamination.eC</code>), in hours.",
        "Co-simulation semantics: sample and hold. <code>fmi2DoStep(t, h)</code> advances the cage and \
         the roller azimuths over <code>[t, t+h]</code> with the inputs held and solves the element at \
         <code>t+h</code>; outputs are algebraic in the inputs at fidelity 0, so reading an output after \
         setting an input re-solves first. Variable communication step sizes, FMU state get/set and \
         serialization are supported, and any number of instances may run, also on parallel threads.",
    ] {
        let _ = writeln!(h, "<li>{item}</li>");
    }
    let _ = writeln!(h, "</ul>");

    let _ = writeln!(h, "<h2 id=\"limits\">What it does not model</h2>\n<ul>");
    for item in [
        "Temperature: the bulk oil temperature is an input (<code>oilTemperature</code>) and the viscosity \
         follows it; the element computes no temperatures of its own (no thermal network, no flash \
         temperature) and no churning or oil-bath drag. Starvation follows the parameter \
         <code>supply</code>.",
        "Elastic rings, shaft and housing: the rings are rigid bodies apart from the local contact \
         deformation; the cup is the reference ring and turns at <code>cupSpeed</code>. The shaft deflection enters only as the imposed cone tilts \
         <code>xi</code>, <code>zeta</code> (the moments needed to hold them are the outputs \
         <code>reaction.My</code>, <code>reaction.Mz</code>), limited to \u{b1}0.5 deg.",
        "Wear, damage and surface temperature (flash temperature) are not computed; the lives are \
         ISO 281 / ISO/TS 16281 ratings with a1 = 1; a_ISO = 1 except in <code>life.L10m</code>.",
        "A cylindrical roller bearing carries no axial load in this model (<code>Fx</code> is ignored).",
        "The element has no continuous states exposed to the master; at fidelity 0 the only memory \
         between steps is the cage angle (roller azimuths) and the solver's warm start.",
    ] {
        let _ = writeln!(h, "<li>{item}</li>");
    }
    let _ = writeln!(h, "</ul>");

    // ----------------------------------------------------------------------------------
    let _ = writeln!(h, "<h2 id=\"fidelity\">Fidelity levels</h2>");
    let _ = writeln!(
        h,
        "<p>Chosen with the parameter <code>fidelity</code> (fixed before initialization).</p>"
    );
    let _ = writeln!(
        h,
        "<table><tr><th>level</th><th>name</th><th>state</th><th>use</th><th>in this FMU</th></tr>"
    );
    let _ = writeln!(
        h,
        "<tr><td>0</td><td>quasi-static</td><td>ring displacements and per-roller equilibrium solved at \
         every step (Newton)</td><td>drivetrain and system scenes, long runs</td>\
         <td>available (default)</td></tr>"
    );
    let _ = writeln!(
        h,
        "<tr><td>1</td><td>dynamic</td><td>full roller (6 DOF each), cage and cone dynamics integrated in \
         time [W25, after Gupta 1984], started from the level-0 solution</td><td>roller tilt and skew, \
         moments, transients</td><td>{}</td></tr>",
        dynamic_status(bearing, 1)
    );
    let _ = writeln!(
        h,
        "<tr><td>2</td><td>quasi-dynamic</td><td>each roller's seat, tilt, skew and place in its pocket in \
         balance at every communication point under the level-1 contact laws; roller spin and the cage's \
         speed and centre stepped by backward Euler over the communication step</td><td>roller skew, \
         spin and cage slip at the communication step of a drivetrain or rotor model</td><td>{}</td></tr>",
        dynamic_status(bearing, 2)
    );
    let _ = writeln!(h, "</table>");
    let _ = writeln!(
        h,
        "<p>Further switches, each a parameter: <code>lubrication</code> (EHL regimes or dry Coulomb), \
         <code>skewModel</code> (level 0: roller skew equilibrium with the cage pocket limit [D19]), \
         <code>gyroscopic</code>, <code>centrifugal</code>, <code>slices</code>, <code>tolerance</code>.</p>"
    );

    // ----------------------------------------------------------------------------------
    write_bearing(&mut h, bearing, bearing_json);

    // ----------------------------------------------------------------------------------
    write_drivetrain(&mut h);
    let _ = writeln!(h, "<h2 id=\"variables\">Variables</h2>");
    let _ = writeln!(
        h,
        "<p>All {} variables of this FMU ({} rollers; per-roller variables <code>roller[j].*</code> for \
         j = 1..{}). Values are in the unit shown; the display unit is what a tool may show instead. \
         Start values are those of modelDescription.xml, i.e. the packaged bearing's defaults.</p>",
        variables::expanded(z).len(),
        z,
        z
    );
    for (title, causality) in [
        ("Parameters", Causality::Parameter),
        ("Inputs", Causality::Input),
        ("Outputs", Causality::Output),
    ] {
        let _ = writeln!(h, "<h3>{title}</h3>");
        write_variable_table(&mut h, z, causality, &starts);
    }

    // ----------------------------------------------------------------------------------
    write_fmpy(&mut h, bearing);

    let _ = writeln!(h, "<h2 id=\"sources\">Sources</h2>\n<ul>");
    for (key, text) in SOURCES {
        let _ = writeln!(h, "<li id=\"{key}\">[{key}] {}</li>", esc(text));
    }
    let _ = writeln!(
        h,
        "<li>Further: T. A. Harris, Rolling Bearing Analysis (1966) for the quasi-static friction torque; \
         the full-film traction regression of Wang, Yang &amp; Wang, Tribotest 11 (2004); P. K. Gupta (1984) \
         for the dynamic roller equations.</li>"
    );
    let _ = writeln!(h, "</ul>");
    let _ = writeln!(h, "<p>Bearing data source: {}</p>", esc(&bearing.source));
    let _ = writeln!(h, "</body>\n</html>");
    h
}

fn write_bearing(h: &mut String, b: &Bearing, json: &str) {
    let _ = writeln!(h, "<h2 id=\"bearing\">The bearing: {}</h2>", esc(&b.name));
    let _ = writeln!(h, "<p>{}<br>Source: {}</p>", esc(&b.description), esc(&b.source));
    let kind = match b.kind {
        Kind::Tapered => "tapered roller bearing",
        Kind::Cylindrical => "cylindrical roller bearing",
    };
    let law = match b.contact_law {
        ContactLaw::Johnson => "Johnson line contact (Johnson 1985, in the slice form of [W25])",
        ContactLaw::JohnsonW25 => "Johnson line contact as [W25] Eq. (1) prints it (twice as stiff as Johnson's)",
        ContactLaw::Palmgren => "Palmgren slices [D19, Y22, L22]",
    };
    let lub = match b.lubrication {
        LubricationModel::Ehl => "EHL regimes (lubrication = 0)",
        LubricationModel::Dry => "dry Coulomb (lubrication = 1)",
    };
    let mat = |m: &trb::bearing::Material| format!("E = {} GPa, nu = {}, density {} kg/m\u{b3}", trim(m.e / 1e9, 3), m.nu, m.density);
    let mut rows: Vec<(&str, String)> = vec![
        ("kind", kind.into()),
        (
            "bore \u{d7} outside diameter \u{d7} width",
            format!("{} \u{d7} {} \u{d7} {}", mm(b.bore), mm(b.outside_diameter), mm(b.width)),
        ),
        ("number of rollers Z", b.roller_count.to_string()),
        ("roller length (effective)", mm(b.roller_length)),
        ("roller mean diameter", mm(b.roller_mean_diameter)),
        ("roller half-cone angle", deg(b.roller_half_angle)),
        (
            "roller end sphere radius",
            if b.roller_end_radius > 0.0 {
                mm(b.roller_end_radius)
            } else {
                "none".into()
            },
        ),
        ("pitch diameter", mm(b.pitch_diameter)),
        ("cone (inner) contact angle", deg(b.cone_angle)),
        ("cup (outer) contact angle", deg(b.cup_angle)),
        (
            "flange contact angle (to the radial plane)",
            b.flange_angle.map(deg).unwrap_or_else(|| "no flange contact".into()),
        ),
        ("rollers", mat(&b.roller_material)),
        ("rings", mat(&b.ring_material)),
        ("cage", mat(&b.cage_material)),
        ("line contact law", law.into()),
        (
            "cage",
            format!(
                "pocket clearance {}, guide clearance {}, land width {} at radius {}, mass {} kg",
                mm(b.pocket_clearance),
                mm(b.guide_clearance),
                mm(b.land_width),
                mm(b.land_radius),
                b.cage_mass
            ),
        ),
        ("oil", format!("eta0 = {} Pa s, alpha = {:e} 1/Pa", b.eta0, b.alpha)),
        ("composite roughness", um(b.roughness)),
        ("lubrication model", lub.into()),
        ("Coulomb mu (dry), flange mu0", format!("{}, {}", b.mu, b.flange_mu0)),
        (
            "cage slip rate (quasi-static torque)",
            format!("{} %", trim(b.cage_slip_rate * 100.0, 4)),
        ),
        ("roller crown drop", um(b.crown_drop)),
        ("mounted radial clearance", um(b.clearance)),
    ];
    if b.outer_lobes > 0 {
        rows.push((
            "lobed outer raceway",
            format!("{} lobes, waveform value ee = {}", b.outer_lobes, um(b.outer_waveform)),
        ));
    } else {
        rows.push(("outer raceway", "round".into()));
    }
    rows.push(("slices per roller, tolerance", format!("{}, {:e}", b.slices, b.tolerance)));
    rows.push((
        "default operating point (input start values)",
        format!(
            "{} rpm, Fx = {} N, Fy = {} N, Fz = {} N, xi = {}, zeta = {}, {} preload (axialDisplacement = {})",
            trim(b.speed * 30.0 / std::f64::consts::PI, 3),
            trim(b.fx, 3),
            trim(b.fy, 3),
            trim(b.fz, 3),
            deg(b.xi),
            deg(b.zeta),
            if b.displacement_preload { "displacement" } else { "force" },
            um(b.axial_displacement)
        ),
    ));
    let _ = writeln!(h, "<table><tr><th>quantity</th><th>value</th></tr>");
    for (k, v) in rows {
        let _ = writeln!(h, "<tr><td>{}</td><td>{}</td></tr>", esc(k), esc(&v));
    }
    let _ = writeln!(h, "</table>");
    let _ = writeln!(h, "<h3>Documented defaults</h3>");
    if b.documented_defaults.is_empty() {
        let _ = writeln!(h, "<p>None: every value comes from the source.</p>");
    } else {
        let _ = writeln!(h, "<p>Values the source does not give, and how they were chosen:</p>\n<ul>");
        for d in &b.documented_defaults {
            let _ = writeln!(h, "<li>{}</li>", esc(d));
        }
        let _ = writeln!(h, "</ul>");
    }
    let _ = writeln!(
        h,
        "<details><summary>The packaged bearing file (<code>resources/bearing.json</code>)</summary>\n<pre>{}</pre></details>",
        esc(json)
    );
    let _ = writeln!(
        h,
        "<p>The presets <code>resources/presets/*.json</code> are shipped for reference; this FMU is built \
         for the bearing above (its variable list depends on the roller count).</p>"
    );
}

/// Causality, signs, stiffness and life, with the names a user of bearing-analysis tools and
/// of ISO 281 / ISO/TS 16281 knows.
fn write_drivetrain(h: &mut String) {
    let _ = writeln!(h, "<h2 id=\"drivetrain\">Drivetrain block: causality, stiffness, life</h2>");
    let _ = writeln!(
        h,
        "<p>Frame: x is the bearing axis (towards the small roller ends), y and z radial; the origin on \
         the axis in the plane of the roller centres. A shaft model that owns the journal's motion sets \
         <code>causality</code> = 1, passes the cone's displacement relative to the cup \
         (<code>displacement.x/y/z</code>, m) and tilts (<code>xi</code>, <code>zeta</code>, rad) and \
         applies the opposite of the reactions to its journal. With <code>causality</code> = 0 (default) \
         the forces go in and <code>cone.x/y/z</code> come out. At fidelity 1 a prescribed cone jumps to \
         its inputs at every communication point (held over the step); rollers and cage stay dynamic.</p>"
    );
    let _ = writeln!(
        h,
        "<table><tr><th>this FMU</th><th>meaning and sign</th><th>usual name (ISO 281, ISO/TS 16281, bearing tools)</th></tr>"
    );
    for (ours, meaning, usual) in [
        (
            "reaction.Fx",
            "axial load the bearing carries; > 0 pushes the cone into the cup (loads the bearing)",
            "axial load F_a",
        ),
        (
            "reaction.Fy, reaction.Fz",
            "radial load components the bearing carries (= Fy, Fz in force causality)",
            "radial load F_r = |(F_y, F_z)|",
        ),
        (
            "reaction.My, reaction.Mz",
            "moment the shaft applies to hold the tilts (positive work with xi, zeta)",
            "tilting moment M",
        ),
        (
            "displacement.x / cone.x",
            "axial displacement of the cone relative to the cup, > 0 into the bearing",
            "axial deflection δ_a (inner ring relative to outer)",
        ),
        (
            "displacement.y/z / cone.y/z",
            "radial displacement of the cone relative to the cup",
            "radial deflection δ_r",
        ),
        ("xi, zeta", "tilts of the cone about y and z", "misalignment / tilt angle"),
        (
            "stiffness[i,j]",
            "d(reaction_i)/d(q_j), q = (x, y, z, xi, zeta), rollers re-equilibrated (tangent)",
            "bearing stiffness matrix K (5\u{d7}5, e.g. c_rr, c_aa, c_tt)",
        ),
        (
            "rating.C",
            "ISO 281 C_r from the geometry (b_m = 1.1, f_c of Table 7, α = cup angle)",
            "basic dynamic load rating C_r",
        ),
        (
            "life.L10",
            "ISO 281 (C_r/P)^(10/3) in hours at the relative ring speed, P = X F_r + Y F_a",
            "basic rating life L_10h",
        ),
        (
            "life.L10r",
            "ISO/TS 16281 from the slice (lamina) loads, a1 = a_ISO = 1, in hours",
            "basic reference rating life L_10r",
        ),
        (
            "life.L10m, life.aISO, oil.kappa",
            "ISO 281 a_ISO L10 in hours, a1 = 1; e_C = contamination.eC",
            "modified rating life L_10mh, a_ISO, kappa",
        ),
        (
            "frictionTorque, powerLoss",
            "torque between the rings (to drive the cone when the cup stands), dissipated power = torque x (speed - cupSpeed)",
            "frictional moment M, power loss",
        ),
    ] {
        let _ = writeln!(
            h,
            "<tr><td><code>{ours}</code></td><td>{}</td><td>{}</td></tr>",
            esc(meaning),
            esc(usual)
        );
    }
    let _ = writeln!(h, "</table>");
    let _ = writeln!(
        h,
        "<p>Tools that put the bearing axis on z map this FMU's x to their z and (y, z) to their (x, y). \
         The stiffness is analytic at fidelity 0 (static condensation of the Newton Jacobian); with \
         <code>skewModel</code> it is central differences of the skew model's own reactions (computed \
         when read); at fidelity 1 it is the quasi-static linearisation about the current cone position. \
         Lives are capped at 1e12 h when the rings do not turn relative to each other or carry no \
         load.</p>"
    );
    write_tool_names(h);
}

/// The names and conventions of two bearing-analysis tools users compare with, from their own
/// public documentation (MESYS: its manual's "Coordinate system" page; MASTA: the property
/// names of its Python API, mastapy, `SMT.MastaAPI.Bearings.BearingResults`).
fn write_tool_names(h: &mut String) {
    let _ = writeln!(h, "<h3 id=\"tools\">From MESYS and MASTA</h3>");
    let _ = writeln!(
        h,
        "<p><b>MESYS</b> (rolling bearing calculation): x is the axial direction, y points to the first \
         rolling element, the azimuth \u{3c8} is positive about x, moments are positive about their axes, \
         and the load acts on the inner ring, so a positive y load loads the rolling elements on the y \
         side. This FMU uses the same frame: the load inputs <code>Fx</code>, <code>Fy</code>, \
         <code>Fz</code> act on the cone (inner ring), \u{3c8} = 0 is +y and a positive <code>Fy</code> \
         loads the rollers there; roller 1 sits at <code>cage.angle0</code> (0 = on the y axis, MESYS's \
         default). MESYS's force/moment or displacement/rotation loading is <code>causality</code> = 0 \
         or 1. The one choice to check is the sense of x: here +x points from the large roller ends \
         to the small ones, so that a positive <code>Fx</code> loads the bearing; orient the MESYS \
         bearing so that its positive axial load does the same, or mirror through the y-z plane: flip \
         the x components of forces and displacements (<code>Fx</code>, <code>cone.x</code>, \
         <code>reaction.Fx</code>) and the y and z components of tilts and moments (<code>xi</code>, \
         <code>zeta</code>, <code>reaction.My/Mz</code>); speeds stay (examples/drivetrain mirrors its \
         second bearing this way).</p>"
    );
    let _ = writeln!(h, "<table><tr><th>MASTA (mastapy property)</th><th>this FMU</th><th>note</th></tr>");
    for (masta, ours, note) in [
        ("InnerRingAngularVelocity", "speed", "rad/s, about +x"),
        ("OuterRingAngularVelocity", "cupSpeed", "rad/s, about +x"),
        ("RelativeAngularVelocity", "speed \u{2212} cupSpeed", "lives and torque use it"),
        ("AxialDisplacementPreload", "axialDisplacement (preload = 1)", "m"),
        ("SpecifiedRadialInternalClearance", "clearance", "m, negative = interference"),
        ("RelativeAxialDisplacement", "cone.x (displacement.x)", "m"),
        ("RelativeRadialDisplacement", "|(cone.y, cone.z)|", "m"),
        ("RelativeMisalignment", "|(xi, zeta)|", "rad"),
        (
            "ForceOnInnerRace",
            "\u{2212}reaction.Fx/Fy/Fz/My/Mz",
            "the rollers' force on the cone; the API listing does not state its sign, so compare one axial case",
        ),
        ("DynamicEquivalentLoad (ISO 281)", "P of life.L10", "not an output: P = rating.C / L^(3/10), L = life.L10 \u{d7} 3600 |speed \u{2212} cupSpeed| / (2\u{3c0} 10^6) million revolutions"),
        ("BasicRatingLifeTime (ISO 281)", "life.L10", "hours"),
        ("ISOTS162812008BasicReferenceRatingLifeTime", "life.L10r", "hours, a1 = a_ISO = 1"),
        ("ModifiedRatingLife (ISO 281)", "life.L10m", "hours, a1 = 1"),
        ("FrictionalMoment", "frictionTorque", "N m, between the rings"),
        ("PowerLoss", "powerLoss", "W"),
    ] {
        let _ = writeln!(
            h,
            "<tr><td><code>{}</code></td><td><code>{}</code></td><td>{}</td></tr>",
            esc(masta),
            esc(ours),
            esc(note)
        );
    }
    let _ = writeln!(h, "</table>");
}

fn write_variable_table(h: &mut String, z: usize, causality: Causality, starts: &HashMap<String, String>) {
    let head = "<tr><th>name</th><th>value reference</th><th>type</th><th>causality</th><th>variability</th>\
                <th>unit</th><th>display unit</th><th>range</th><th>start</th><th>description</th></tr>";
    let all = variables::expanded(z);
    let row = |vr: u32, name: &str, v: &Variable| -> String {
        let j = if v.per_roller { (vr - v.vr) as usize + 1 } else { 0 };
        format!(
            "<tr><td><code>{}</code></td><td class=\"num\">{vr}</td><td>{}</td><td>{}</td><td>{}</td><td>{}</td><td>{}</td><td>{}</td><td class=\"num\">{}</td><td>{}</td></tr>",
            esc(name),
            type_name(v),
            causality_name(v.causality),
            variability_name(v),
            esc(v.unit.unwrap_or("")),
            esc(v.display_unit.unwrap_or("")),
            esc(&range(v)),
            esc(starts.get(name).map(String::as_str).unwrap_or(if v.causality == Causality::Output { "\u{2014}" } else { "" })),
            esc(&v.description_for(j)),
        )
    };
    // Scalars in one table.
    let _ = writeln!(h, "<table>{head}");
    for (vr, name, v) in all.iter().filter(|(_, _, v)| v.causality == causality && !v.per_roller) {
        let _ = writeln!(h, "{}", row(*vr, name, v));
    }
    let _ = writeln!(h, "</table>");
    // Per-roller rows, one collapsible table per table row.
    let per_roller: Vec<&Variable> = variables::TABLE
        .iter()
        .filter(|v| v.causality == causality && v.per_roller)
        .collect();
    for v in per_roller {
        let _ = writeln!(
            h,
            "<details><summary><code>{}</code> for j = 1..{z} (value references {}..{}): {}</summary>\n<table>{head}",
            esc(v.name),
            v.vr,
            v.vr + z as u32 - 1,
            esc(&v.description.replace("{j}", "j"))
        );
        for (vr, name, w) in all.iter().filter(|(_, _, w)| std::ptr::eq(*w, v)) {
            let _ = writeln!(h, "{}", row(*vr, name, w));
        }
        let _ = writeln!(h, "</table></details>");
    }
}

fn write_fmpy(h: &mut String, b: &Bearing) {
    let rpm = b.speed * 30.0 / std::f64::consts::PI;
    let _ = writeln!(h, "<h2 id=\"fmpy\">Use from fmpy</h2>");
    let _ = writeln!(
        h,
        "<p>Inputs and parameters are set in SI units: <code>speed</code> in rad/s (rpm \u{d7} pi/30), \
         angles in rad, forces in N, lengths in m. Outputs are SI as well.</p>"
    );
    let example = format!(
        r#"import numpy as np
from fmpy import simulate_fmu

# inputs as a structured array: time, then FMU input names (SI units)
t = [0.0, 0.1, 0.2]
inputs = np.array(
    [(ti, {speed:?}, {fx:?}, fy) for ti, fy in zip(t, [0.0, 0.0, 20000.0])],
    dtype=[("time", float), ("speed", float), ("Fx", float), ("Fy", float)],
)
result = simulate_fmu(
    "{id}.fmu",
    fmi_type="CoSimulation",
    start_time=0.0, stop_time=0.2, output_interval=1e-3,
    start_values={{"slices": {slices}, "lubrication": {lub}}},  # parameters, FMU names
    input=inputs,
    output=["frictionTorque", "powerLoss", "cone.x", "Qo.max", "loadedRollers"],
)
print(result["time"][-1], result["frictionTorque"][-1])  # {rpm} rpm at t = 0"#,
        speed = b.speed,
        fx = b.fx,
        id = model_identifier(b),
        slices = b.slices,
        lub = match b.lubrication {
            LubricationModel::Ehl => 0,
            LubricationModel::Dry => 1,
        },
        rpm = trim(rpm, 3),
    );
    let _ = writeln!(h, "<pre>{}</pre>", esc(&example));
    let stepwise = format!(
        r#"from fmpy import read_model_description, extract
from fmpy.fmi2 import FMU2Slave

md = read_model_description("{id}.fmu")
vr = {{v.name: v.valueReference for v in md.modelVariables}}
fmu = FMU2Slave(guid=md.guid, unzipDirectory=extract("{id}.fmu"),
                modelIdentifier=md.coSimulation.modelIdentifier, instanceName="bearing")
fmu.instantiate()
fmu.setupExperiment(startTime=0.0)
fmu.enterInitializationMode()
fmu.setReal([vr["speed"], vr["Fx"]], [{speed:?}, {fx:?}])
fmu.exitInitializationMode()
t, h = 0.0, 1e-3
while t < 0.1:
    fmu.doStep(currentCommunicationPoint=t, communicationStepSize=h)
    t += h
    torque, = fmu.getReal([vr["frictionTorque"]])
fmu.terminate()
fmu.freeInstance()"#,
        id = model_identifier(b),
        speed = b.speed,
        fx = b.fx,
    );
    let _ = writeln!(
        h,
        "<p>Step by step, as a co-simulation master does:</p>\n<pre>{}</pre>",
        esc(&stepwise)
    );
    let _ = writeln!(
        h,
        "<p>Without FMI, the same model code runs from the command line of the project: \
         <code>trb simulate SCENARIO.json --out results.csv</code> (see <code>scenarios/README.md</code>); \
         its CSV replayed through this FMU gives the same numbers.</p>"
    );
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn start_values_are_read_from_the_model_description() {
        let b = Bearing::default_preset();
        let (xml, _) = trb::model_description::generate(&b);
        let starts = start_values(&xml);
        let speed: f64 = starts["speed"].parse().unwrap();
        assert_eq!(speed.to_bits(), b.speed.to_bits());
        assert_eq!(starts["slices"], b.slices.to_string());
        assert!(!starts.contains_key("frictionTorque"));
        assert!(starts.contains_key("roller[17].dD"));
    }
}
