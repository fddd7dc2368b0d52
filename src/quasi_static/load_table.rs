//! Functions of a contact's load, tabulated lazily on a uniform grid in ln(load) and read by
//! cubic (four-point Lagrange) interpolation: the per-slice friction laws of the quasi-static
//! model (a thermal Eyring film solve per slice) evaluated once per grid node and speed
//! instead of once per roller, slice and step.
//!
//! A node is computed the first time an interpolation needs it, always by the same law at the
//! same load, so a value read from the table is a function of the load and of what the table
//! was built for (speed, oil, geometry) alone, never of the order in which nodes were filled:
//! a restored FMU state reads the same bits from an empty table as from a full one.
//!
//! Error: four-point interpolation at spacing h has the error h⁴/24 · f⁗(ξ) · |t(t²−1)(t−2)|
//! ≤ 0.0234 h⁴ max|f⁗| over the four nodes (t the position between the inner nodes), 1.4e-6
//! |f⁗| at h = 1/16 (`tests`: a power law). Where a law has a kink (a `max` inside it) the
//! error is of order h times the jump of its slope. The caller tabulates what is smooth in
//! ln q (the friction laws' logarithms) and states the error it measured.

/// Spacing of the grid in ln(load).
pub(super) const STEP: f64 = 0.0625;
/// ln of the first node's load, 0.97 µN (ln 1 mN − 111 steps: the nodes of the table that
/// began at 1 mN, extended): lighter contacts are evaluated directly. Rollers outside the
/// load zone of a radially loaded bearing still touch with slice loads of a fraction of a
/// millinewton, every step; these stay on the table.
pub(super) const LN_FIRST: f64 = -13.845_255_278_982_137;
/// Nodes per tabulated line: 0.97 µN up to e^(−13.8 + 511/16) = 7e7 N.
pub(super) const NODES: usize = 512;

/// Two functions of the load for each of `lines` lines (slice positions), `NODES` nodes each.
#[derive(Debug, Clone, Default)]
pub(super) struct LoadTable {
    values: Vec<[f64; 2]>,
}

impl LoadTable {
    /// An empty table for `lines` lines (every node to be computed).
    pub(super) fn reset(&mut self, lines: usize) {
        self.values.clear();
        self.values.resize(lines * NODES, [f64::NAN; 2]);
    }

    /// The load of node `i`.
    fn node_load(i: usize) -> f64 {
        crate::fastmath::exp(LN_FIRST + STEP * i as f64)
    }

    /// Grid coordinate of a load with logarithm `ln_q`: node i lies at i.
    #[inline(always)]
    pub(super) fn grid(ln_q: f64) -> f64 {
        (ln_q - LN_FIRST) * (1.0 / STEP)
    }

    /// Whether grid coordinate `x` has the four nodes of its cubic on the grid.
    #[inline(always)]
    pub(super) fn on_grid(x: f64) -> bool {
        x >= 1.0 && x < (NODES - 2) as f64
    }

    /// The four nodes i - 1 .. i + 2 of line `line` around cell `i` (1 <= i < NODES - 2),
    /// those not yet computed by `law(q_node)`.
    #[inline]
    pub(super) fn nodes(&mut self, line: usize, i: usize, mut law: impl FnMut(f64) -> [f64; 2]) -> &[[f64; 2]] {
        let base = line * NODES + i - 1;
        for n in 0..4 {
            if self.values[base + n][0].is_nan() {
                self.values[base + n] = law(Self::node_load(i - 1 + n));
            }
        }
        &self.values[base..base + 4]
    }

    /// Every node's two values in one array: function c of node n of line l at
    /// 2 (l NODES + n) + c (NaN: not computed yet).
    #[inline(always)]
    pub(super) fn flat(&self) -> &[f64] {
        self.values.as_flattened()
    }

    /// Both functions of line `line` at load `q` > 0, `law(q_node)` computing a node; `None`
    /// outside the grid or where a law is not finite at a node (the caller then evaluates the
    /// law itself).
    #[inline]
    pub(super) fn get(&mut self, line: usize, q: f64, law: impl FnMut(f64) -> [f64; 2]) -> Option<[f64; 2]> {
        let x = Self::grid(crate::fastmath::ln(q));
        if !Self::on_grid(x) {
            return None;
        }
        let i = x as usize;
        let w = crate::fastmath::lagrange4_weights(x - i as f64);
        let v = self.nodes(line, i, law);
        let mut out = [0.0; 2];
        for c in 0..2 {
            out[c] = w[0] * v[0][c] + w[1] * v[1][c] + w[2] * v[2][c] + w[3] * v[3][c];
        }
        // a law that is not finite at a node (a zero read in logarithms) is left to the caller
        (out[0].is_finite() && out[1].is_finite()).then_some(out)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_power_law_is_read_within_the_stated_bound() {
        // tabulated as itself (not its logarithm): f = q^p, f⁗ = p⁴ f in ln q, the largest
        // over the four nodes at most e^(2|p|h) times the value at the point
        let mut t = LoadTable::default();
        for p in [-0.754, 0.246, 1.0, 1.5] {
            t.reset(1);
            let bound = 0.0234 * STEP.powi(4) * f64::powi(p, 4) * (2.0 * p.abs() * STEP).exp();
            let mut worst: f64 = 0.0;
            for n in 0..2000 {
                let q = 0.01 * 1.0071_f64.powi(n);
                let got = t.get(0, q, |qn| [qn.powf(p), 0.0]).unwrap()[0];
                worst = worst.max((got / q.powf(p) - 1.0).abs());
            }
            assert!(worst <= bound, "p = {p}: {worst:.3e} > {bound:.3e}");
            assert!(worst > 0.05 * bound, "p = {p}: the bound is not tight ({worst:.3e} vs {bound:.3e})");
        }
    }

    #[test]
    fn a_value_does_not_depend_on_which_nodes_were_filled_before() {
        let law = |q: f64| [q.sqrt() * (1.0 + 0.1 * q.ln().sin()), 1.0 / (1.0 + q)];
        let mut full = LoadTable::default();
        full.reset(1);
        for n in 0..500 {
            full.get(0, 0.5 * 1.03_f64.powi(n), law);
        }
        let mut empty = LoadTable::default();
        for n in (0..500).step_by(7) {
            let q = 0.5 * 1.03_f64.powi(n) * 1.001;
            empty.reset(1);
            let a = empty.get(0, q, law).unwrap();
            let b = full.get(0, q, law).unwrap();
            assert_eq!(a.map(f64::to_bits), b.map(f64::to_bits));
        }
    }

    #[test]
    fn loads_outside_the_grid_and_laws_that_are_not_finite_are_left_to_the_caller() {
        let mut t = LoadTable::default();
        t.reset(1);
        assert!(t.get(0, 1e-7, |_| [1.0, 1.0]).is_none());
        assert!(t.get(0, 1e9, |_| [1.0, 1.0]).is_none());
        assert!(t.get(0, 1.0, |_| [1.0, 1.0]).is_some());
        assert!(t.get(0, 10.0, |_| [f64::NEG_INFINITY, 0.0]).is_none());
    }
}
