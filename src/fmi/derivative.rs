//! `fmi2GetDirectionalDerivative` by differences of the model's own solution.
//!
//! The derivative of the outputs u along a seed direction v of the continuous inputs k is
//! dv_unknown = (∂u/∂k)·v. It is taken by a central difference along v,
//!
//!   dv_unknown ≈ (u(k + t v) − u(k − t v)) / (2t),   t = min_i h_i / |v_i| over v_i ≠ 0,
//!
//! with h_i the model's difference step of input i ([`Model::difference_step`], scaled to the
//! input's physics), so that no input moves by more than its step. Where k ± t v leaves an input's
//! declared range (a load at 0, a value at its bound) that side is replaced by k itself: a
//! one-sided difference over t. Each call costs exactly **two** evaluations of the model
//! ([`Model::probe`], the outputs at the trial inputs starting from the model's history of the
//! last step — its warm start — which it restores afterwards), whatever the number of knowns and
//! unknowns; the truncation error is O(t²) (O(t) one-sided). A seed of zeros costs nothing.
//!
//! The instance's values are never touched: the trial inputs and outputs live in a scratch copy.
//!
//! Why differences and not analytical derivatives: the outputs are those of a discrete solution —
//! a contact search on sampled profiles, a load balance, FASTSIM's march with its adhesion/slip
//! switch per element — whose exact derivative is that of the whole chain; even in the creepages,
//! where FASTSIM is linear element by element, the slip elements and the load balance's creep
//! update make it a nonlinear function. A difference of the element's own solution is consistent
//! with the outputs the host gets, at a known cost.

use super::model::{Model, ModelError};
use super::variables::{Values, VarInfo};

/// One known of a directional derivative: its variable and its seed.
pub type Known = (&'static VarInfo, f64);

/// Fills `out[j]` with the derivative of the output `unknowns[j]` along the seed of `knowns` at
/// the inputs in `base` (see the module's text); `scratch` is overwritten (same variable table).
pub fn directional_derivative(
    model: &mut dyn Model,
    base: &Values,
    scratch: &mut Values,
    knowns: impl Iterator<Item = Known> + Clone,
    unknowns: impl Iterator<Item = &'static VarInfo> + Clone,
    out: &mut [f64],
) -> Result<(), ModelError> {
    let t = knowns
        .clone()
        .filter(|(_, seed)| *seed != 0.0)
        .map(|(var, seed)| model.difference_step(base, var) / seed.abs())
        .fold(f64::INFINITY, f64::min);
    if t == f64::INFINITY {
        out.fill(0.0);
        return Ok(());
    }
    if !(t.is_finite() && t > 0.0) {
        return Err(ModelError::Error(format!(
            "fmi2GetDirectionalDerivative: no usable difference step ({t}) along the seed"
        )));
    }
    let mut spread = 0.0;
    for side in [-1.0, 1.0] {
        copy_values(base, scratch);
        // A known listed twice moves by the sum of its seeds.
        for (var, seed) in knowns.clone() {
            scratch.reals[var.slot] += side * t * seed;
        }
        if knowns
            .clone()
            .all(|(var, _)| var.accepts_real(scratch.reals[var.slot]))
        {
            spread += t;
        } else {
            copy_values(base, scratch);
        }
        model.probe(scratch)?;
        for (o, var) in out.iter_mut().zip(unknowns.clone()) {
            let u = scratch.reals[var.slot];
            *o = if side < 0.0 { u } else { u - *o };
        }
    }
    if spread == 0.0 {
        return Err(ModelError::Error(format!(
            "fmi2GetDirectionalDerivative: a step of {t} along the seed leaves the inputs' \
             ranges on both sides"
        )));
    }
    for o in out.iter_mut() {
        *o /= spread;
    }
    Ok(())
}

/// The default difference step of the input `var` at `values`: 1e−6 of its magnitude, at least
/// 1e−6 of its unit ([`Model::difference_step`]).
pub fn default_step(values: &Values, var: &VarInfo) -> f64 {
    1e-6 * values.reals[var.slot].abs().max(1.0)
}

/// Copies every value of `from` into `to` (same table); allocates only for longer strings.
fn copy_values(from: &Values, to: &mut Values) {
    to.reals.copy_from_slice(&from.reals);
    to.integers.copy_from_slice(&from.integers);
    to.booleans.copy_from_slice(&from.booleans);
    for (t, f) in to.strings.iter_mut().zip(&from.strings) {
        t.clone_from(f);
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::fmi::model::Evaluation;
    use crate::fmi::variables::{Causality, Counts, Start, VarType, Variability};

    fn real(name: &'static str, slot: usize, causality: Causality, min: f64) -> VarInfo {
        VarInfo {
            name,
            vr: slot as u32,
            ty: VarType::Real,
            slot,
            causality,
            variability: Variability::Continuous,
            start: Start::Real(0.0),
            min: Some(min),
            max: None,
            min_exclusive: false,
            allowed: "",
            unit: "",
            description: "",
        }
    }

    static VARS: std::sync::LazyLock<[VarInfo; 3]> = std::sync::LazyLock::new(|| {
        [
            real("a", 0, Causality::Input, -10.0),
            real("b", 1, Causality::Input, 0.0),
            real("f", 2, Causality::Output, f64::NEG_INFINITY),
        ]
    });

    /// f = a³ + 5 b, with a history that counts the probes (and must be left alone).
    struct Cubic {
        probes: usize,
    }

    impl Model for Cubic {
        fn initialize(&mut self, _: &Values) -> Result<(), ModelError> {
            Ok(())
        }
        fn evaluate(&mut self, v: &mut Values, _: f64) -> Result<Evaluation, ModelError> {
            v.reals[2] = v.reals[0].powi(3) + 5.0 * v.reals[1];
            Ok(Evaluation::Ok)
        }
        fn probe(&mut self, v: &mut Values) -> Result<(), ModelError> {
            self.probes += 1;
            self.evaluate(v, 0.0).map(|_| ())
        }
        fn difference_step(&self, _: &Values, _: &VarInfo) -> f64 {
            1e-3
        }
    }

    fn derivative(a: f64, b: f64, seed: [f64; 2]) -> (f64, usize) {
        let vars: &'static [VarInfo; 3] = &VARS;
        let counts = Counts {
            real: 3,
            integer: 0,
            boolean: 0,
            string: 0,
        };
        let mut base = Values::from_start(vars, counts);
        base.reals[..2].copy_from_slice(&[a, b]);
        let mut scratch = base.clone();
        let mut model = Cubic { probes: 0 };
        let mut out = [f64::NAN];
        let knowns = vars[..2].iter().zip(seed);
        directional_derivative(
            &mut model,
            &base,
            &mut scratch,
            knowns,
            std::iter::once(&vars[2]),
            &mut out,
        )
        .unwrap();
        (out[0], model.probes)
    }

    #[test]
    fn central_difference_along_the_seed_costs_two_probes() {
        // d/dt (a + t)^3 + 5 (b + 2t) = 3a² + 10; central: + h² (h = 1e-3 along a, 5e-4 of
        // the seed's scale t since b's step 1e-3 / 2 is smaller).
        let (d, probes) = derivative(2.0, 1.0, [1.0, 2.0]);
        let t: f64 = 5e-4;
        assert!((d - (12.0 + 10.0 + t * t)).abs() < 1e-9, "{d}");
        assert_eq!(probes, 2);
        // A zero seed: nothing to evaluate.
        assert_eq!(derivative(2.0, 1.0, [0.0, 0.0]), (0.0, 0));
    }

    #[test]
    fn a_bound_makes_the_difference_one_sided() {
        // b = 0 at its minimum: forward difference 5 exactly (f is linear in b).
        let (d, probes) = derivative(2.0, 0.0, [0.0, 1.0]);
        assert!((d - 5.0).abs() < 1e-9, "{d}");
        assert_eq!(probes, 2);
        // a at its minimum −10 along a: forward difference 3a² + 3a h + h² = 300 − 0.03 + 1e-6.
        let (d, _) = derivative(-10.0, 0.0, [1.0, 0.0]);
        assert!((d - (300.0 - 0.03 + 1e-6)).abs() < 1e-6, "{d}");
    }
}
