//! Output values of the last successful solve, read without solving.
//!
//! `Simulation::get_real`/`get_integer` re-solve first when inputs changed (direct
//! feedthrough). When that solve fails, or in states where no solve may happen (StepFailed,
//! Error, Terminated), the FMU still hands out the last valid (finite) outputs. Simulation
//! has no by-value-reference read of `last_outputs()`, so this maps output value references
//! to `Outputs` fields; a test checks that it agrees with `Simulation::get_real` for every
//! output variable, so the two cannot drift apart silently.

use crate::simulation::Simulation;
use crate::variables::{self as var, Causality, VarType};

/// The Real value of `vr` without solving: parameters and inputs as set, outputs as of the
/// last successful solve. None for an unknown or non-Real value reference.
pub fn real(sim: &mut Simulation, vr: u32) -> Option<f64> {
    let (row, j) = var::lookup(vr, sim.n_rollers())?;
    if row.ty != VarType::Real {
        return None;
    }
    if row.causality != Causality::Output {
        return sim.get_real(vr).ok();
    }
    let o = sim.last_outputs();
    Some(match row.vr {
        var::FRICTION_TORQUE => o.friction_torque,
        var::FRICTION_TORQUE_RACEWAY => o.friction_torque_raceway,
        var::FRICTION_TORQUE_FLANGE => o.friction_torque_flange,
        var::FRICTION_TORQUE_CAGE => o.friction_torque_cage,
        var::POWER_LOSS => o.power_loss,
        var::CONE_X => o.cone_x,
        var::CONE_Y => o.cone_y,
        var::CONE_Z => o.cone_z,
        var::REACTION_FX => o.reaction_fx,
        var::REACTION_MY => o.reaction_my,
        var::REACTION_MZ => o.reaction_mz,
        var::TILT_MAX => o.tilt_max,
        var::TILT_MEAN => o.tilt_mean,
        var::SKEW_MAX => o.skew_max,
        var::SKEW_MEAN => o.skew_mean,
        var::QI_MAX => o.qi_max,
        var::QO_MAX => o.qo_max,
        var::QF_MAX => o.qf_max,
        var::CAGE_SPEED => o.cage_speed,
        var::SOLVER_RESIDUAL => o.solver_residual,
        var::ROLLER_TILT => o.tilt[j],
        var::ROLLER_SKEW => o.skew[j],
        var::ROLLER_QI => o.qi[j],
        var::ROLLER_QO => o.qo[j],
        var::ROLLER_QF => o.qf[j],
        var::ROLLER_QC => o.qc[j],
        var::ROLLER_AZIMUTH => o.azimuth[j],
        var::ROLLER_NIT => o.nit[j],
        var::ROLLER_NOT => o.not[j],
        var::ROLLER_NFT => o.nft[j],
        var::ROLLER_NIS => o.nis[j],
        var::ROLLER_NOS => o.nos[j],
        var::ROLLER_NFS => o.nfs[j],
        _ => return None,
    })
}

/// The Integer value of `vr` without solving (see [`real`]).
pub fn integer(sim: &mut Simulation, vr: u32) -> Option<i32> {
    let (row, _) = var::lookup(vr, sim.n_rollers())?;
    if row.ty != VarType::Integer {
        return None;
    }
    if row.causality != Causality::Output {
        return sim.get_integer(vr).ok();
    }
    let o = sim.last_outputs();
    Some(match row.vr {
        var::LOADED_ROLLERS => o.loaded_rollers,
        var::SOLVER_ITERATIONS => o.solver_iterations,
        _ => return None,
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::bearing::Bearing;

    #[test]
    fn agrees_with_simulation_for_every_variable() {
        let bearing = Bearing::default_preset();
        let z = bearing.roller_count;
        let mut sim = Simulation::new(bearing);
        sim.set_real(var::FY, 5000.0).unwrap();
        sim.set_real(var::XI, 5e-5).unwrap();
        sim.initialize(0.0).unwrap();
        sim.do_step(0.0, 1e-3).unwrap();
        for (vr, name, row) in var::expanded(z) {
            match row.ty {
                VarType::Real => {
                    let want = sim.get_real(vr).unwrap();
                    let got = real(&mut sim, vr).unwrap_or_else(|| panic!("{name} not mapped"));
                    assert_eq!(got.to_bits(), want.to_bits(), "{name}");
                }
                VarType::Integer => {
                    let want = sim.get_integer(vr).unwrap();
                    assert_eq!(integer(&mut sim, vr), Some(want), "{name}");
                }
                VarType::Boolean => {}
            }
        }
        assert_eq!(real(&mut sim, 999_999), None);
        assert_eq!(real(&mut sim, var::FIDELITY), None);
        assert_eq!(integer(&mut sim, var::SPEED), None);
    }
}
