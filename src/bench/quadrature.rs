//! The reference of the `free` scene that does not use the integrator:
//! Housner free rocking solved by energy conservation and quadrature
//! (docs/model.md §9).
//!
//! From rest at amplitude Θ₀ the block reaches Θ = 0 after
//! τ_q = ∫₀^{Θ₀} ψ dΘ / √(2(cos(ψ(1−Θ₀)) − cos(ψ(1−Θ)))), with speed
//! |w| = √(2(cos(ψ(1−Θ₀)) − cos ψ)); the impact multiplies it by Housner's
//! r and the next amplitude follows from energy again.

/// Quarter period from rest at `theta0`, by the substitution
/// Θ = Θ₀(1 − v²) (no endpoint singularity) and
/// cos A − cos(A+δ) = 2 sin(A + δ/2) sin(δ/2) (no cancellation), with
/// composite Simpson over 20,000 intervals (error ~1e-15).
pub fn quarter_period(psi: f64, theta0: f64) -> f64 {
    let a = psi * (1.0 - theta0);
    let f = |v: f64| {
        if v == 0.0 {
            return 2.0 * psi * theta0 / (2.0 * a.sin() * psi * theta0).sqrt();
        }
        let d = psi * theta0 * v * v;
        2.0 * psi * theta0 * v / (4.0 * (a + 0.5 * d).sin() * (0.5 * d).sin()).sqrt()
    };
    let n = 20_000;
    let h = 1.0 / n as f64;
    let mut s = f(0.0) + f(1.0);
    for i in 1..n {
        s += f(i as f64 * h) * if i % 2 == 1 { 4.0 } else { 2.0 };
    }
    s * h / 3.0
}

/// Impact times of Housner free rocking from rest at `theta0` up to `tau_end`.
pub(crate) fn impact_times(psi: f64, housner_r: f64, theta0: f64, tau_end: f64) -> Vec<f64> {
    let mut out = Vec::new();
    let mut theta = theta0;
    let mut tau = quarter_period(psi, theta);
    while tau <= tau_end && out.len() < 10_000 {
        out.push(tau);
        let w = (4.0 * (psi * (1.0 - 0.5 * theta)).sin() * (0.5 * psi * theta).sin()).sqrt() * housner_r;
        theta = 1.0 - (psi.cos() + 0.5 * w * w).acos() / psi;
        // Stop once the amplitude is negligible (or no longer a number).
        if theta.is_nan() || theta <= 1e-12 {
            break;
        }
        tau += 2.0 * quarter_period(psi, theta);
    }
    out
}
