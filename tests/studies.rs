//! The studies' stated trends (MODEL.md section 8) on the product's quasi-static model:
//! [D19] roller skew and dry friction torque (32018X), [L22] roller diameter deviations
//! (32008), [Y22] triple-lobe cylindrical roller bearing (CRB-TRILOBE). Each case is one
//! quasi-static solve (`trb::quasi_static::studies`), the same model the FMU runs.

use trb::quasi_static::studies::*;

// ------------------------------------------------------------------------------------------
// [D19]
// ------------------------------------------------------------------------------------------

#[test]
fn d19_large_pocket_clearance_has_no_roller_cage_torque() {
    // mu = 0.5: with 0.3 mm the rollers reach their pockets; with 3 mm none does.
    let tight = d19(D19Preload::Force, 0.5, 0.3e-3).unwrap();
    assert!(
        tight.friction_torque_cage > 0.0 && tight.qc_max > 0.0,
        "{}",
        tight.friction_torque_cage
    );
    let wide = d19(D19Preload::Force, 0.5, 3.0e-3).unwrap();
    assert_eq!(wide.friction_torque_cage, 0.0);
    assert_eq!(wide.qc_max, 0.0);
    assert!(wide.skew_max < 3.0e-3 / (0.5 * 20.96e-3));
    // The parts add up and the skew is the same sign for every roller (the flange drives it).
    for o in [&tight, &wide] {
        let parts = o.friction_torque_raceway + o.friction_torque_flange + o.friction_torque_cage;
        assert!((parts - o.friction_torque).abs() <= 1e-12 * o.friction_torque);
        assert!((o.power_loss - o.friction_torque * 60.0 * std::f64::consts::PI / 30.0).abs() <= 1e-9 * o.power_loss);
    }
}

#[test]
fn d19_roller_cage_torque_grows_steeply_above_a_critical_friction_coefficient() {
    // Pocket clearance 0.9 mm: no pocket contact at low friction, then a steep rise.
    let cage: Vec<(f64, f64)> = [0.1, 0.3, 0.45, 0.5, 0.55, 0.6]
        .iter()
        .map(|&mu| (mu, d19(D19Preload::Force, mu, 0.9e-3).unwrap().friction_torque_cage))
        .collect();
    assert_eq!(cage[0].1, 0.0, "{cage:?}");
    assert_eq!(cage[1].1, 0.0, "{cage:?}");
    let last = cage.last().unwrap().1;
    assert!(last > 1.0, "{cage:?}");
    // Above the critical value the cage torque rises faster than the coefficient itself.
    let first_on = cage.iter().position(|c| c.1 > 0.0).expect("pocket contact");
    let (mu0, t0) = cage[first_on];
    assert!(first_on + 1 < cage.len(), "{cage:?}");
    let (mu1, t1) = cage[first_on + 1];
    assert!(t1 / t0 > 2.0 * mu1 / mu0, "{cage:?}");
    // Skew grows with mu below the pocket limit.
    let s1 = d19(D19Preload::Force, 0.1, 0.9e-3).unwrap().skew_max;
    let s2 = d19(D19Preload::Force, 0.2, 0.9e-3).unwrap().skew_max;
    assert!(s2 > 1.5 * s1 && s1 > 0.0, "{s1} {s2}");
}

#[test]
fn d19_force_preload_gives_lower_torque_than_displacement_preload() {
    for mu in [0.05, 0.1, 0.2] {
        let f = d19(D19Preload::Force, mu, 0.9e-3).unwrap();
        let d = d19(D19Preload::Displacement, mu, 0.9e-3).unwrap();
        assert!(
            f.friction_torque < d.friction_torque,
            "mu {mu}: force {} displacement {}",
            f.friction_torque,
            d.friction_torque
        );
    }
}

#[test]
fn d19_friction_thrust_on_the_cone_acts_along_the_applied_axial_load() {
    // The rib friction drags the large roller end along with the cone (positive skew at
    // positive speed); a roller skewed so slides on the cone towards its small end, so the
    // friction thrust mu q |sin phi| of Eq. (7) acts on the cone along its generatrix towards
    // +x, with the applied axial load (docs/model.md, "Friction thrust"). The contact loads
    // then carry Fx plus the thrust (force preload), and the axial reaction is the contact
    // loads' axial sum minus the thrust (displacement preload). [D19] states the opposite
    // sense (the inner-race thrust offsets the axial load, its Eq. (9b)); docs/model.md
    // explains why the model does not follow it.
    let (ai, af) = (12.75_f64.to_radians(), (90.0_f64 - 13.15).to_radians());
    let sums = |o: &trb::model::Outputs, mu: f64| {
        let normal: f64 = o.qi.iter().zip(&o.qf).map(|(qi, qf)| qi * ai.sin() + qf * af.sin()).sum();
        let thrust: f64 = o.qi.iter().zip(&o.skew).map(|(qi, s)| mu * qi * s.sin().abs() * ai.cos()).sum();
        (normal, thrust)
    };
    for mu in [0.3, 0.5] {
        let f = d19(D19Preload::Force, mu, 0.9e-3).unwrap();
        let (normal, thrust) = sums(&f, mu);
        assert!(thrust > 0.01 * 12_970.0, "mu {mu}: thrust {thrust}");
        assert!(
            (normal - thrust - 12_970.0).abs() <= 1e-3 * thrust,
            "mu {mu}, force preload: contact loads' axial sum {normal}, thrust {thrust}"
        );
        let d = d19(D19Preload::Displacement, mu, 0.9e-3).unwrap();
        let (normal, thrust) = sums(&d, mu);
        assert!(
            (normal - thrust - d.reaction_fx).abs() <= 1e-3 * thrust,
            "mu {mu}, displacement preload: contact loads' axial sum {normal}, thrust {thrust}, reaction {}",
            d.reaction_fx
        );
    }
}

#[test]
fn d19_skew_off_keeps_the_in_plane_solution() {
    // skewModel = false is the default and leaves skew and pocket outputs at zero.
    let o = solve_case("32018X", 0.0, |_, _| {}).unwrap();
    assert_eq!(o.skew_max, 0.0);
    assert_eq!(o.qc_max, 0.0);
    assert_eq!(o.friction_torque_cage, 0.0);
}

// ------------------------------------------------------------------------------------------
// [L22]
// ------------------------------------------------------------------------------------------

#[test]
fn l22_ideal_bearing_shares_the_load_equally() {
    for fx in [10_000.0, 2_000.0] {
        let o = l22(0, fx, 1e-4, 1000.0).unwrap();
        let q0 = o.qo[0];
        assert!(o.qo.iter().all(|q| (q - q0).abs() <= 1e-9 * q0));
        assert!(variance(&o.qo) <= 1e-18 * q0 * q0);
    }
}

#[test]
fn l22_sorted_deviations_give_lower_variance_than_random_ones() {
    for fx in [10_000.0, 2_000.0] {
        for (random, sorted) in [(1, 2), (3, 4), (5, 6)] {
            let r = l22(random, fx, 1e-4, 1000.0).unwrap();
            let s = l22(sorted, fx, 1e-4, 1000.0).unwrap();
            assert!(
                variance(&s.qo) < variance(&r.qo),
                "Fx {fx}: series {sorted} {} vs {random} {}",
                variance(&s.qo),
                variance(&r.qo)
            );
        }
    }
}

#[test]
fn l22_maximum_load_rises_with_the_deviation_magnitude() {
    for fx in [10_000.0, 2_000.0] {
        let ideal = l22(0, fx, 1e-4, 1000.0).unwrap().qo_max;
        for family in [[1, 3, 5], [2, 4, 6]] {
            let mut last = ideal;
            for s in family {
                let q = l22(s, fx, 1e-4, 1000.0).unwrap().qo_max;
                assert!(q > last, "Fx {fx}, series {s}: {q} <= {last}");
                last = q;
            }
        }
    }
}

#[test]
fn l22_total_torque_changes_by_a_tiny_fraction() {
    for slip in [1e-4, 5e-4] {
        let ideal = l22(0, 10_000.0, slip, 1000.0).unwrap();
        for s in 1..=6 {
            let o = l22(s, 10_000.0, slip, 1000.0).unwrap();
            let rel = (o.friction_torque - ideal.friction_torque).abs() / ideal.friction_torque;
            assert!(rel < 0.02, "series {s}, slip {slip}: {:.4} %", 100.0 * rel);
            // ... while the most loaded roller slides harder.
            assert!(o.sliding_friction_max > ideal.sliding_friction_max, "series {s}");
        }
    }
}

// ------------------------------------------------------------------------------------------
// [Y22]
// ------------------------------------------------------------------------------------------

#[test]
fn y22_negative_clearance_gives_three_preload_zones() {
    for state in [Y22State::Single, Y22State::Double] {
        let o = y22(state, Y22_CLEARANCE, Y22_WAVEFORM, Y22_FY, Y22_RPM).unwrap();
        assert_eq!(loaded_lobe_zones(&o, state.cage_angle()), 3, "{}", state.label());
        assert!(y22_preloaded(&o, state));
    }
}

#[test]
fn y22_fewer_loaded_rollers_as_clearance_or_speed_rises() {
    for state in [Y22State::Single, Y22State::Double] {
        let mut last = usize::MAX;
        for c_um in [-20.0, -15.0, -10.0, -5.0, 0.0] {
            let n = y22(state, c_um * 1e-6, Y22_WAVEFORM, Y22_FY, Y22_RPM).unwrap().loaded_rollers as usize;
            assert!(n <= last, "{}: clearance {c_um} um: {n} > {last}", state.label());
            last = n;
        }
        let slow = y22(state, Y22_CLEARANCE, Y22_WAVEFORM, Y22_FY, 10_000.0).unwrap().loaded_rollers;
        let fast = y22(state, Y22_CLEARANCE, Y22_WAVEFORM, Y22_FY, 60_000.0).unwrap().loaded_rollers;
        assert!(fast < slow, "{}: {slow} at 10,000 rpm, {fast} at 60,000 rpm", state.label());
    }
}

#[test]
fn y22_double_pressed_state_loses_preload_first() {
    // Raise the clearance in 0.5 um steps: the double-pressed state loses its three preload
    // zones at a smaller clearance than the single-pressed state.
    let lost_at = |state: Y22State| {
        (0..=60)
            .map(|k| -20e-6 + 0.5e-6 * k as f64)
            .find(|&c| !y22_preloaded(&y22(state, c, Y22_WAVEFORM, Y22_FY, Y22_RPM).unwrap(), state))
            .expect("preload lost below +10 um")
    };
    let single = lost_at(Y22State::Single);
    let double = lost_at(Y22State::Double);
    assert!(
        double < single,
        "double-pressed loses preload at {double:e} m, single at {single:e} m"
    );
}

/// Rollers carrying more than 1 % of the largest roller load (the product's `loadedRollers`
/// also counts contacts of hundredths of a newton opposite the load).
fn rollers_carrying_load(o: &trb::model::Outputs) -> usize {
    let max = o.qo.iter().cloned().fold(0.0, f64::max);
    o.qo.iter().filter(|&&q| q > 0.01 * max).count()
}

#[test]
fn d19_loaded_roller_counts() {
    // [D19] §3.2 (32018X, dry, Fr 35 kN, 0.9 mm pockets): 15 rollers in contact with the races
    // under displacement preload (0.01 mm), 13 under force preload (12 970 N), because in
    // [D19] the friction thrust along the inner race offsets part of the axial load. The
    // product has the 15 under displacement preload at every mu; under force preload it has
    // them while the thrust is small, and more as mu (and with it the thrust, which by the
    // skewed roller's kinematics loads the cone along Fx) grows: docs/validation.md.
    for mu in [0.1, 0.3, 0.5] {
        let d = d19(D19Preload::Displacement, mu, 0.9e-3).unwrap();
        assert_eq!(rollers_carrying_load(&d), 15, "displacement preload, mu {mu}");
    }
    let small = d19(D19Preload::Force, 0.05, 0.9e-3).unwrap();
    assert_eq!(rollers_carrying_load(&small), 15, "force preload, mu 0.05");
    let large = d19(D19Preload::Force, 0.5, 0.9e-3).unwrap();
    assert!(
        rollers_carrying_load(&large) > 15,
        "force preload, mu 0.5: {}",
        rollers_carrying_load(&large)
    );
}
