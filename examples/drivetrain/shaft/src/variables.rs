//! The shaft FMU's variables: one table, read by the FMU (value references, start values,
//! what may be set when) and by the packager (modelDescription.xml). All variables are Real.
//!
//! Value references: parameters 0..17, the temperature input 90, bearing A's inputs 100..132, bearing B's 200..232,
//! outputs 300..335.

/// FMI causality of a variable.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Causality {
    Parameter,
    Input,
    Output,
}

/// One scalar variable of the FMU.
#[derive(Clone, Debug)]
pub struct Var {
    pub name: String,
    pub vr: u32,
    pub causality: Causality,
    /// Start value (parameters and inputs; outputs are calculated).
    pub start: f64,
    pub unit: &'static str,
    pub description: String,
}

// Parameters
pub const P_POS_A: u32 = 0;
pub const P_POS_B: u32 = 1;
pub const P_PRELOAD: u32 = 2;
pub const P_MESH_POS: u32 = 3;
pub const P_MESH_RADIUS: u32 = 4;
pub const P_MESH_FA: u32 = 5;
pub const P_MESH_FR: u32 = 6;
pub const P_MESH_FT: u32 = 7;
pub const P_MESH_MOD: u32 = 8;
pub const P_MESH_FREQ: u32 = 9;
pub const P_RELAX: u32 = 10;
pub const P_SPEED: u32 = 11;
pub const P_RAMP: u32 = 12;
pub const P_ALPHA: u32 = 13;
pub const P_RADIAL_LENGTH: u32 = 14;
pub const P_MAX_TRANSLATION: u32 = 15;
pub const P_MAX_TILT: u32 = 16;
/// Input: shaft minus housing temperature.
pub const IN_DELTA_T: u32 = 90;

/// First input of bearing A (B: +100): reaction Fx, Fy, Fz, My, Mz, then stiffness[i,j]
/// row by row, then cone.x/y/z.
pub const IN_A: u32 = 100;
pub const IN_B: u32 = 200;
pub const IN_REACTION: u32 = 0;
pub const IN_STIFFNESS: u32 = 5;
pub const IN_CONE: u32 = 30;

/// Outputs: bearing A's displacement.x/y/z, xi, zeta at 300.., B's at 310..
pub const OUT_A: u32 = 300;
pub const OUT_B: u32 = 310;
pub const OUT_MESH: u32 = 320; // mesh.Fx, mesh.Fy, mesh.Fz
pub const OUT_TORQUE: u32 = 323;
pub const OUT_RESIDUAL: u32 = 324; // residual.Fx .. residual.Mz
pub const OUT_Q: u32 = 329; // shaft.u, v, w, thetaY, thetaZ
pub const OUT_SPEED: u32 = 334;
pub const OUT_RESIDUAL_REL: u32 = 335;

/// Largest value reference + 1.
pub const N_VR: usize = 336;

const DOF: [&str; 5] = ["x", "y", "z", "xi", "zeta"];
const DOF_UNIT: [&str; 5] = ["m", "m", "m", "rad", "rad"];
const REACTION: [&str; 5] = ["Fx", "Fy", "Fz", "My", "Mz"];
const REACTION_UNIT: [&str; 5] = ["N", "N", "N", "N.m", "N.m"];

fn var(name: impl Into<String>, vr: u32, causality: Causality, start: f64, unit: &'static str, description: impl Into<String>) -> Var {
    Var {
        name: name.into(),
        vr,
        causality,
        start,
        unit,
        description: description.into(),
    }
}

/// The table, in modelDescription order.
pub fn variables() -> Vec<Var> {
    use Causality::*;
    let mut v = vec![
        var("bearingA.position", P_POS_A, Parameter, -0.15, "m", "Axial position of bearing A's pitch-plane centre on the shaft (bearing frame = shaft frame)"),
        var("bearingB.position", P_POS_B, Parameter, 0.15, "m", "Axial position of bearing B's pitch-plane centre (mirrored frame: x_B = -X, xi_B = -thetaY, zeta_B = -thetaZ)"),
        var("preload.displacement", P_PRELOAD, Parameter, 40e-6, "m", "Axial preload by displacement: the total interference of the pair, delta/2 added to each bearing's displacement.x"),
        var("mesh.position", P_MESH_POS, Parameter, 0.05, "m", "Axial position of the gear mesh point"),
        var("mesh.radius", P_MESH_RADIUS, Parameter, 0.2, "m", "Pitch radius of the gear: the mesh point is at (mesh.position, mesh.radius, 0)"),
        var("mesh.Fa", P_MESH_FA, Parameter, 8000.0, "N", "Mean axial mesh force on the shaft (+X)"),
        var("mesh.Fr", P_MESH_FR, Parameter, 20000.0, "N", "Mean radial mesh force on the shaft (+Y)"),
        var("mesh.Ft", P_MESH_FT, Parameter, 40000.0, "N", "Mean tangential mesh force on the shaft (+Z): torque mesh.radius * Ft about X"),
        var("mesh.modulation", P_MESH_MOD, Parameter, 0.2, "1", "Relative amplitude m of the mesh force: F(t) = F0 r(t) (1 + m sin(2 pi f t))"),
        var("mesh.frequency", P_MESH_FREQ, Parameter, 1.0, "Hz", "Frequency f of the mesh force modulation"),
        var("relaxation", P_RELAX, Parameter, 1.0, "1", "Fraction of the Newton step taken per communication step (1: full Newton)"),
        var("shaft.speed", P_SPEED, Parameter, 300.0, "rad/s", "Shaft (cone) speed, passed to the bearings through the output speed"),
        var("mesh.rampTime", P_RAMP, Parameter, 0.0, "s", "The mesh force ramps up linearly over this time: r(t) = min(1, t/rampTime) (0: no ramp)"),
        var("thermal.expansion", P_ALPHA, Parameter, 11.7e-6, "1/K", "Linear thermal expansion coefficient of shaft and cones (steel)"),
        var(
            "thermal.radialLength",
            P_RADIAL_LENGTH,
            Parameter,
            0.0,
            "m",
            "Sum over the two bearings of cone raceway radius / tan(contact angle): the cones' radial growth as axial interference (0: the axial growth of the shaft only)",
        ),
        var("maxStep.translation", P_MAX_TRANSLATION, Parameter, 20e-6, "m", "Trust region: largest change of a bearing's translation per communication step"),
        var("maxStep.tilt", P_MAX_TILT, Parameter, 5e-4, "rad", "Trust region: largest change of a bearing's tilt per communication step"),
        var(
            "thermal.deltaT",
            IN_DELTA_T,
            Input,
            0.0,
            "K",
            "Shaft minus housing temperature: preload interference delta + thermal.expansion * deltaT * (thermal.radialLength - (bearingB.position - bearingA.position))",
        ),
    ];
    for (bearing, base) in [("bearingA", IN_A), ("bearingB", IN_B)] {
        for (k, r) in REACTION.iter().enumerate() {
            v.push(var(
                format!("{bearing}.reaction.{r}"),
                base + IN_REACTION + k as u32,
                Input,
                0.0,
                REACTION_UNIT[k],
                format!("{r} carried by {bearing} in its own frame (its output reaction.{r})"),
            ));
        }
        for i in 0..5 {
            for j in 0..5 {
                let unit = match (i < 3, j < 3) {
                    (true, true) => "N/m",
                    (true, false) => "N/rad",
                    (false, true) => "N",
                    (false, false) => "N.m/rad",
                };
                v.push(var(
                    format!("{bearing}.stiffness[{},{}]", i + 1, j + 1),
                    base + IN_STIFFNESS + (5 * i + j) as u32,
                    Input,
                    0.0,
                    unit,
                    format!(
                        "d(reaction.{})/d({}) of {bearing} in its own frame (its output stiffness[{},{}])",
                        REACTION[i],
                        DOF[j],
                        i + 1,
                        j + 1
                    ),
                ));
            }
        }
        for (k, c) in ["x", "y", "z"].iter().enumerate() {
            v.push(var(
                format!("{bearing}.cone.{c}"),
                base + IN_CONE + k as u32,
                Input,
                0.0,
                "m",
                format!("{bearing}'s cone displacement along {c} in its own frame (its output cone.{c}: the displacement its reactions belong to)"),
            ));
        }
    }
    for (bearing, base) in [("bearingA", OUT_A), ("bearingB", OUT_B)] {
        for (k, d) in DOF.iter().enumerate() {
            let name = if k < 3 {
                format!("{bearing}.displacement.{d}")
            } else {
                format!("{bearing}.{d}")
            };
            v.push(var(
                name,
                base + k as u32,
                Output,
                0.0,
                DOF_UNIT[k],
                format!("Input {d} of {bearing} in its own frame"),
            ));
        }
    }
    for (k, c) in ["Fx", "Fy", "Fz"].iter().enumerate() {
        v.push(var(
            format!("mesh.{c}"),
            OUT_MESH + k as u32,
            Output,
            0.0,
            "N",
            format!("Mesh force {c} on the shaft now (at the end of the step)"),
        ));
    }
    v.push(var(
        "torque",
        OUT_TORQUE,
        Output,
        0.0,
        "N.m",
        "Torque of the mesh force about the shaft axis, mesh.radius * mesh.Fz",
    ));
    for (k, r) in REACTION.iter().enumerate() {
        v.push(var(
            format!("residual.{r}"),
            OUT_RESIDUAL + k as u32,
            Output,
            0.0,
            REACTION_UNIT[k],
            format!("Shaft equilibrium residual {r} (applied load minus bearing reactions, about X = 0) at the state the bearing inputs belong to"),
        ));
    }
    for (k, (q, unit)) in [("u", "m"), ("v", "m"), ("w", "m"), ("thetaY", "rad"), ("thetaZ", "rad")]
        .iter()
        .enumerate()
    {
        v.push(var(
            format!("shaft.{q}"),
            OUT_Q + k as u32,
            Output,
            0.0,
            unit,
            format!("Shaft displacement {q} at X = 0"),
        ));
    }
    v.push(var(
        "speed",
        OUT_SPEED,
        Output,
        0.0,
        "rad/s",
        "Shaft speed (shaft.speed), for the bearings' speed inputs",
    ));
    v.push(var(
        "residual.relative",
        OUT_RESIDUAL_REL,
        Output,
        0.0,
        "1",
        "|residual| / |applied load|, moments divided by the bearing span (without an applied load: relative to the larger bearing reaction)",
    ));
    v
}
