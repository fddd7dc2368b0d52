//! The lubricant supply (`supply`, `supply.level`; `tribology::supply`, docs/model.md,
//! "Lubricant supply"): starved films that tend to the flooded ones, the friction torque
//! against SKF's frictional-moment model with the same supply, and the energy books of the
//! dynamic model under every supply.

mod common;

use trb::bearing::Bearing;
use trb::model::Outputs;
use trb::simulation::Simulation;
use trb::variables as var;

const RPM: f64 = std::f64::consts::PI / 30.0;

/// The element of preset `name` at `rpm` and axial load `fa` with the integer parameters `ints`
/// and real parameters `reals` set, initialised (fidelity 0 unless `ints` says otherwise).
fn element(name: &str, rpm: f64, fa: f64, ints: &[(u32, i32)], reals: &[(u32, f64)]) -> Simulation {
    let reals: Vec<(u32, f64)> = reals.iter().copied().chain([(var::SPEED, rpm * RPM), (var::FX, fa)]).collect();
    common::element(name, ints, &reals)
}

fn outputs(name: &str, rpm: f64, fa: f64, ints: &[(u32, i32)], reals: &[(u32, f64)]) -> Outputs {
    element(name, rpm, fa, ints, reals).outputs().unwrap().clone()
}

/// Both film ratios rise continuously and monotonically with the inlet layer and reach the
/// flooded ones; with a layer far above the flooded film every output is the flooded
/// element's but for the rolling resistance's replenishment, and with a flooded supply bit for
/// bit, at both fidelities. Grease's own layer halves the raceway films and thins the rib's
/// (a compact contact) more.
#[test]
fn the_starved_films_tend_to_the_flooded_ones() {
    for name in ["32008", "TRB130x230"] {
        let flooded = outputs(name, 1500.0, 5e3, &[], &[]);
        let mut last = (0.0, 0.0);
        for level in [0.02, 0.05, 0.1, 0.2, 0.5, 0.9, 1.0, 1.1, 2.0, 5.0] {
            let o = outputs(name, 1500.0, 5e3, &[(var::SUPPLY, 2)], &[(var::SUPPLY_LEVEL, level)]);
            let (race, rib) = (o.film_ratio_raceway, o.film_ratio_flange);
            eprintln!("{name}, level {level}: film ratio raceway {race:.4}, rib {rib:.4}");
            // (the raceway film, a line contact, reaches the flooded one at about r = 1.5)
            assert!(
                race >= last.0 && rib > last.1,
                "{name}: level {level}: {race}, {rib} after {last:?}"
            );
            assert!(level > 1.5 || race > last.0, "{name}: level {level}: {race} after {}", last.0);
            assert!(race <= flooded.film_ratio_raceway * (1.0 + 1e-9) && rib <= flooded.film_ratio_flange * (1.0 + 1e-9));
            last = (race, rib);
        }
        // continuity: a relative step of 1e-6 in the layer moves the film ratios by less
        // than 1e-6 relative (the law's slope in r is below 1)
        let near = |level: f64| outputs(name, 1500.0, 5e3, &[(var::SUPPLY, 2)], &[(var::SUPPLY_LEVEL, level)]);
        let (a, c) = (near(0.7), near(0.7 * (1.0 + 1e-6)));
        assert!((c.film_ratio_raceway / a.film_ratio_raceway - 1.0).abs() < 1.5e-6);
        assert!((c.film_ratio_flange / a.film_ratio_flange - 1.0).abs() < 1.5e-6);
        // a layer of 1e6 flooded films gives the flooded films, bit for bit
        let thick = outputs(name, 1500.0, 5e3, &[(var::SUPPLY, 2)], &[(var::SUPPLY_LEVEL, 1e6)]);
        assert_eq!(thick.film_ratio_raceway.to_bits(), flooded.film_ratio_raceway.to_bits());
        assert_eq!(thick.film_ratio_flange.to_bits(), flooded.film_ratio_flange.to_bits());
        // the supplies' own layers: grease runs on half the flooded film (the rib on less),
        // an oil bath, a jet and oil-air on full films
        for supply in [1, 2, 3] {
            let o = outputs(name, 1500.0, 5e3, &[(var::SUPPLY, supply)], &[]);
            let race = o.film_ratio_raceway / flooded.film_ratio_raceway;
            let rib = o.film_ratio_flange / flooded.film_ratio_flange;
            eprintln!("{name}, supply {supply}: raceway film x {race:.3}, rib film x {rib:.3}");
            if supply == 2 {
                assert!(
                    (race - 0.5).abs() < 1e-9 && rib < race && rib > 0.45,
                    "{name}, grease: {race}, {rib}"
                );
            } else {
                assert!(race == 1.0 && rib == 1.0, "{name}, supply {supply}: {race}, {rib}");
            }
            // ISO 281's viscosity ratio takes the oil's (for grease the base oil's) viscosity
            assert_eq!(o.oil_kappa.to_bits(), flooded.oil_kappa.to_bits());
        }
    }
    // the dynamic model: a thick layer gives the flooded films (the rolling resistance keeps
    // the supply's replenishment)
    let run = |reals: &[(u32, f64)], supply: i32| {
        let mut s = element("32008", 1500.0, 5e3, &[(var::FIDELITY, 1), (var::SUPPLY, supply)], reals);
        s.do_step(0.0, 1e-3).unwrap();
        s.do_step(1e-3, 1e-3).unwrap();
        s.outputs().unwrap().clone()
    };
    let (thick, flooded) = (run(&[(var::SUPPLY_LEVEL, 1e6)], 2), run(&[], 0));
    assert!((thick.film_ratio_flange / flooded.film_ratio_flange - 1.0).abs() < 1e-3);
    assert!(thick.friction_torque < flooded.friction_torque);
}

/// `supply` = 0 (the default) is the element as it was before the supply existed, bit for bit:
/// the scenarios of `tests/fixtures/flooded/` (the default bearing quasi-static under load and
/// deflection ramps; a user's 30206 dynamic under combined load) print exactly the CSV files
/// that the element wrote before the parameter was added.
#[test]
fn the_flooded_supply_is_the_element_before_the_supply_bit_for_bit() {
    let dir = concat!(env!("CARGO_MANIFEST_DIR"), "/tests/fixtures/flooded");
    for case in ["quasi_static", "dynamic"] {
        let out = std::env::temp_dir().join(format!("trb-flooded-{case}-{}.csv", std::process::id()));
        let status = std::process::Command::new(env!("CARGO_BIN_EXE_trb"))
            .args(["simulate", &format!("{dir}/{case}.json"), "--quiet", "--out"])
            .arg(&out)
            .status()
            .unwrap();
        assert!(status.success(), "{case}");
        let now = std::fs::read_to_string(&out).unwrap();
        let before = std::fs::read_to_string(format!("{dir}/{case}.csv")).unwrap();
        let _ = std::fs::remove_file(&out);
        assert!(now == before, "{case}: the flooded element's results changed");
    }
}

/// The friction torque against SKF's frictional-moment model (`trb::skf_friction`) with the
/// same supply: SKF's K_rs for the supply (flooded: no starvation, phi_rs = 1) and the
/// preset's oil (for grease, its base oil), for 32008 (as SKF 32008 X) and the default
/// bearing (as SKF 32226), over speed and axial load.
/// - An oil bath, a jet and oil-air act on the rolling resistance alone, through SKF's
///   replenishment factor: the torque under each over the flooded torque is within ±10 % of
///   SKF's ratio, at every point. Grease also halves the films, which SKF's model does not
///   do: at low speed the product's greased torque rises (the rib's film falls into the mixed
///   regime) where SKF's falls, by up to 21 % of the flooded torque.
/// - From 1500 rpm the torque is within ±30 % of SKF's in every supply.
/// - At 500 rpm it is 0.52-0.88 of SKF's in every supply (measured 2026-11-28): the films are
///   mixed there (32008: rib film ratio 0.7-1.0), and the [W25] regime law gives the
///   asperities far less of the load than SKF's phi_bl weighting of mu_bl = 0.15 does
///   (docs/validation-notes.md, "Lubricant supply"). The bound below holds that state.
#[test]
fn the_torque_follows_skf_in_every_supply() {
    let worst = torque_over_skf(0, |n| if n >= 1500.0 { 0.7..=1.3 } else { 0.5..=1.3 });
    eprintln!("torque over SKF's: {:.3} to {:.3}", worst.0, worst.1);
}

/// Under SKF's mixed law (`mixedLubrication` = 1: the asperities' share phi_bl of every
/// contact, SKF's mu_bl = 0.15) the low-speed gap of the film-ratio law closes: at 500 rpm the
/// torque is 0.70-1.40 of SKF's instead of 0.52-0.89, and from 1500 rpm it stays within ±30 %
/// (0.75-1.06). Measured 2026-11-28: 44 of the 48 points within ±30 %; the four outside are
/// the 32008 at 500 rpm and 8 kN, 1.35-1.40 in every supply. There the rib's sliding carries
/// phi_bl = 0.25 of SKF's 0.15 at the rib's own load and lever arm, which is more than SKF's
/// empirical sliding load G_sl = S_1 d_m^0.82 (F_r + S_2 Y F_a) gives; the raceways add
/// nothing measurable (the same figures with the film-ratio law at the raceways).
#[test]
fn under_skfs_mixed_law_the_torque_follows_skf_at_every_speed() {
    let worst = torque_over_skf(1, |n| if n >= 1500.0 { 0.7..=1.3 } else { 0.7..=1.45 });
    eprintln!("torque over SKF's under SKF's mixed law: {:.3} to {:.3}", worst.0, worst.1);
}

/// The product's torque over SKF's frictional moment with the same supply, for the 32008 and
/// TRB130x230 over speed, load and supply, under mixed law `mixed`; each ratio must lie in
/// `bounds(speed in rpm)`, and each supply's effect over SKF's replenishment within ±10 %
/// where the films stay full. The smallest and largest ratios.
fn torque_over_skf(mixed: i32, bounds: impl Fn(f64) -> std::ops::RangeInclusive<f64>) -> (f64, f64) {
    use trb::skf_friction as skf;
    let cases = [
        (
            "32008",
            skf::series_32008(),
            vec![
                (500.0, 2e3),
                (1500.0, 2e3),
                (3000.0, 2e3),
                (500.0, 8e3),
                (1500.0, 8e3),
                (3000.0, 8e3),
            ],
        ),
        (
            "TRB130x230",
            skf::trb130x230_series(),
            vec![
                (500.0, 30e3),
                (1500.0, 30e3),
                (3500.0, 30e3),
                (4500.0, 30e3),
                (3500.0, 12e3),
                (3500.0, 39e3),
            ],
        ),
    ];
    let k_rs = [
        0.0,
        skf::K_RS_OIL_BATH_OR_JET,
        skf::K_RS_GREASE_OR_OIL_AIR,
        skf::K_RS_GREASE_OR_OIL_AIR,
    ];
    let mut worst = (f64::INFINITY, 0.0_f64);
    for (name, bearing, points) in cases {
        let b = Bearing::preset(name).unwrap();
        for &(n, fa) in &points {
            let mut flooded = (0.0, 0.0);
            for (supply, &k) in k_rs.iter().enumerate() {
                let lub = skf::Lubrication {
                    k_rs: k,
                    ..skf::Lubrication::oil_bath(b.eta0, None)
                };
                let ints = [(var::SUPPLY, supply as i32), (var::MIXED_LUBRICATION, mixed)];
                let torque = outputs(name, n, fa, &ints, &[]).friction_torque;
                let skf_moment = skf::frictional_moment(&bearing, &lub, n * RPM, 0.0, fa);
                let reference = skf_moment.total;
                if supply == 0 {
                    flooded = (torque, reference);
                }
                let ratio = torque / reference;
                let effect = (torque / flooded.0) / (reference / flooded.1);
                eprintln!(
                    "{name}, mixed law {mixed}, supply {supply}, {n} rpm, Fa {} kN: {torque:.3} N m, SKF {reference:.3} N m ({ratio:.3}; the supply's effect over SKF's {effect:.3}; phi_bl {:.3})",
                    fa * 1e-3,
                    skf_moment.phi_bl
                );
                if supply != 2 {
                    // full films: the supply acts through SKF's replenishment alone
                    assert!(
                        (effect - 1.0).abs() < 0.1,
                        "{name}, supply {supply}, {n} rpm, {fa} N: effect {effect}"
                    );
                }
                assert!(
                    bounds(n).contains(&ratio),
                    "{name}, supply {supply}, {n} rpm, {fa} N: {torque} against {reference}"
                );
                worst = (worst.0.min(ratio), worst.1.max(ratio));
            }
        }
    }
    worst
}

/// Under every supply, and under both mixed laws, the dynamic model's energy books close:
/// over 3 ms of the 32008 at 3000 rpm (500 rpm under SKF's mixed law) with a radial load (the rollers' spin and skew ring through the load zone), the
/// work of the shaft equals the contacts' dissipation plus the change of kinetic energy
/// (trapezoid over 0.1 ms samples).
#[test]
fn the_energy_books_close_under_every_supply() {
    // every supply under the film-ratio law; grease and flooded oil under SKF's at 500 rpm,
    // where its asperities carry a quarter of every contact (phi_bl 0.25)
    for (supply, mixed, rpm) in [
        (0, 0, 3000.0),
        (1, 0, 3000.0),
        (2, 0, 3000.0),
        (3, 0, 3000.0),
        (0, 1, 500.0),
        (2, 1, 500.0),
    ] {
        let mut s = element(
            "32008",
            rpm,
            5e3,
            &[(var::FIDELITY, 1), (var::SUPPLY, supply), (var::MIXED_LUBRICATION, mixed)],
            &[(var::FY, 3e3)],
        );
        let speed = rpm * RPM;
        let power = |s: &mut Simulation| {
            let o = s.outputs().unwrap();
            (o.friction_torque * speed, o.power_loss)
        };
        let (mut input, mut loss) = power(&mut s);
        let ke0 = s.kinetic_energy();
        let (mut e_in, mut e_loss) = (0.0, 0.0);
        let dt = 1e-4;
        for k in 0..30 {
            s.do_step(k as f64 * dt, dt).unwrap();
            let (a, l) = power(&mut s);
            e_in += 0.5 * (a + input) * dt;
            e_loss += 0.5 * (l + loss) * dt;
            (input, loss) = (a, l);
        }
        let dke = s.kinetic_energy() - ke0;
        let residual = e_in - e_loss - dke;
        eprintln!(
            "supply {supply}, mixed law {mixed}: shaft work {e_in:.5e} J, dissipated {e_loss:.5e} J, kinetic energy change {dke:.3e} J"
        );
        assert!(
            residual.abs() < 0.02 * e_loss,
            "supply {supply}, mixed law {mixed}: residual {residual} J of {e_loss} J"
        );
    }
}

/// Grease on the 32008 at fidelity 1 (10 ms from the steady start under pure axial load): the
/// mean skew grows with the axial load at 500 and 3000 rpm, as measured in greased bearings
/// (Zhao et al., J. Tribol. 148 (2026) 024301), and grease skews the rollers more than flooded
/// oil at every point (its starved rib carries more friction). Measured 2026-11-28: 0.0091° to
/// 0.018° from 2 to 8 kN at 500 rpm, 0.0037° to 0.018° at 3000 rpm; flooded 0.0022-0.015°.
/// The measured growth with speed is not reproduced (the greased film is a fixed fraction of
/// the flooded one, so the rib is more mixed at low speed), nor the measured magnitude
/// (0.15-0.6°): docs/validation-notes.md, "Lubricant supply".
#[test]
fn grease_skews_the_rollers_more_and_more_with_axial_load() {
    let skew = |supply: i32, rpm: f64, fa: f64| {
        let mut s = element("32008", rpm, fa, &[(var::FIDELITY, 1), (var::SUPPLY, supply)], &[]);
        for k in 0..2 {
            s.do_step(k as f64 * 5e-3, 5e-3).unwrap();
        }
        s.outputs().unwrap().skew_mean.abs().to_degrees()
    };
    for rpm in [500.0, 3000.0] {
        let (light, heavy) = (skew(2, rpm, 2e3), skew(2, rpm, 8e3));
        let (light_oil, heavy_oil) = (skew(0, rpm, 2e3), skew(0, rpm, 8e3));
        eprintln!("{rpm} rpm: grease {light:.5} deg at 2 kN, {heavy:.5} at 8 kN; flooded {light_oil:.5}, {heavy_oil:.5}");
        assert!(heavy > 2.0 * light, "{rpm} rpm: {light} -> {heavy}");
        assert!(
            light > light_oil && heavy > heavy_oil,
            "{rpm} rpm: grease {light}, {heavy}; oil {light_oil}, {heavy_oil}"
        );
    }
}
