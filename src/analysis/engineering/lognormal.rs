//! The lognormal fragility curve P(failure | IM = x) = Φ(ln(x/θ̂)/β),
//! fitted by maximum likelihood to counts of failures at intensity levels
//! (the binomial likelihood of Baker 2015, "Efficient analytical fragility
//! function fitting using dynamic structural analysis", Earthquake
//! Spectra 31(1)), with its confidence band.
//!
//! Method: with η = a + b·ln x (a = −ln θ̂/β, b = 1/β) the model is a
//! probit regression, whose log-likelihood is concave in (a, b); Fisher
//! scoring with step halving therefore climbs to the maximum from any
//! start, and the maximum is unique when it exists. It does not exist
//! (β → 0 or θ̂ out of range) when the data are separated: every level with
//! a survivor lies at or below every level with a failure; [`fit`] says so
//! instead of returning a number. The covariance of (a, b) is the inverse
//! of the Fisher information at the maximum; the delta method carries it
//! to ln θ̂, to ln β and to η(x), and the 95 % intervals are
//! exp(ln θ̂ ± 1.96 se), β·exp(±1.96 se(ln β)) (so β stays > 0), and the
//! pointwise band Φ(η(x) ± 1.96 se(η(x))).
//!
//! Φ is computed here (no special-function crate): erf by its
//! all-positive Taylor series for |x| < 2 and erfc by its continued
//! fraction beyond; the relative error of either tail is about 1e-13 or less
//! (tested against tabulated values).

use std::f64::consts::{FRAC_1_SQRT_2, PI};

/// z of a two-sided 95 % interval, Φ⁻¹(0.975).
pub(crate) const Z95: f64 = 1.959_963_984_540_054;

/// erfc(x) for x ≥ 0: 1 − erf by the series below 2, the continued
/// fraction (evaluated by Lentz's method) above.
fn erfc_nonneg(x: f64) -> f64 {
    if x < 2.0 {
        // erf x = (2/√π) e^{−x²} Σ_n 2ⁿ x^{2n+1} / (1·3·…·(2n+1)): all
        // terms positive, so no cancellation.
        let mut term = x;
        let mut sum = x;
        let x2 = x * x;
        let mut n = 0.0;
        while term > 1e-17 * sum {
            n += 1.0;
            term *= 2.0 * x2 / (2.0 * n + 1.0);
            sum += term;
        }
        1.0 - 2.0 / PI.sqrt() * (-x2).exp() * sum
    } else {
        // erfc x = e^{−x²}/√π · 1/(x + (1/2)/(x + 1/(x + (3/2)/(x + …)))).
        let tiny = 1e-300;
        let mut f = x;
        let mut c = x;
        let mut d = 0.0;
        for k in 1..2000 {
            let a = 0.5 * f64::from(k);
            d = x + a * d;
            d = if d.abs() < tiny { tiny } else { d };
            c = x + a / c;
            c = if c.abs() < tiny { tiny } else { c };
            d = 1.0 / d;
            let delta = c * d;
            f *= delta;
            if (delta - 1.0).abs() < 1e-16 {
                break;
            }
        }
        (-x * x).exp() / (PI.sqrt() * f)
    }
}

/// The standard normal cumulative distribution Φ(z), accurate in both
/// tails (Φ(−z) is computed directly, never as 1 − Φ(z)).
pub(crate) fn normal_cdf(z: f64) -> f64 {
    let x = z * FRAC_1_SQRT_2;
    if x >= 0.0 {
        1.0 - 0.5 * erfc_nonneg(x)
    } else {
        0.5 * erfc_nonneg(-x)
    }
}

/// The standard normal density φ(z).
pub(crate) fn normal_pdf(z: f64) -> f64 {
    (-0.5 * z * z).exp() / (2.0 * PI).sqrt()
}

/// Failures among runs at one intensity level.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct LevelCount {
    /// The intensity x, > 0 (units of the intensity measure).
    pub level: f64,
    /// Runs at this level (the fit ignores levels with none).
    pub runs: u64,
    /// Failed runs, ≤ `runs`.
    pub failures: u64,
}

/// A fitted lognormal fragility curve.
#[derive(Clone, Copy, Debug, PartialEq, serde::Serialize)]
pub struct LognormalFit {
    /// Median θ̂: the intensity at which half the runs fail (units of the
    /// intensity measure).
    pub median: f64,
    /// Logarithmic standard deviation β, > 0.
    pub beta: f64,
    /// 95 % interval of the median, exp(ln θ̂ ± 1.96 se).
    pub median_ci95: [f64; 2],
    /// 95 % interval of β, β·exp(±1.96 se(ln β)).
    pub beta_ci95: [f64; 2],
    /// Standard error of ln θ̂.
    pub se_ln_median: f64,
    /// Standard error of ln β.
    pub se_ln_beta: f64,
    /// The maximised log-likelihood (binomial, without the constant
    /// ln C(n, z) terms).
    pub log_likelihood: f64,
    /// Fisher-scoring iterations taken.
    pub iterations: u32,
    /// Covariance of (a, b), η = a + b ln x: [var a, cov ab, var b].
    #[serde(skip)]
    cov: [f64; 3],
}

/// One point of a fitted curve with its band.
#[derive(Clone, Copy, Debug, PartialEq, serde::Serialize)]
pub struct BandPoint {
    /// Intensity x.
    pub level: f64,
    /// Φ(ln(x/θ̂)/β).
    pub p: f64,
    /// Lower end of the pointwise 95 % band.
    pub lo: f64,
    /// Upper end.
    pub hi: f64,
}

impl LognormalFit {
    /// The curve and its pointwise 95 % band at `level` (> 0).
    pub fn at(&self, level: f64) -> BandPoint {
        let u = level.ln();
        let (a, b) = self.ab();
        let eta = a + b * u;
        let var = self.cov[0] + 2.0 * u * self.cov[1] + u * u * self.cov[2];
        let sd = var.max(0.0).sqrt();
        BandPoint {
            level,
            p: normal_cdf(eta),
            lo: normal_cdf(eta - Z95 * sd),
            hi: normal_cdf(eta + Z95 * sd),
        }
    }

    fn ab(&self) -> (f64, f64) {
        (-self.median.ln() / self.beta, 1.0 / self.beta)
    }
}

/// Why no curve was fitted.
#[derive(Clone, Debug, PartialEq, Eq, thiserror::Error)]
pub enum FitError {
    /// Fewer than two levels with runs.
    #[error("needs runs at two or more intensity levels")]
    TooFewLevels,
    /// No run failed.
    #[error("no run failed: the median is above the largest level")]
    NoFailures,
    /// Every run failed.
    #[error("every run failed: the median is below the smallest level")]
    AllFailed,
    /// Separated data: the maximum likelihood is at β → 0.
    #[error(
        "the data separate (no failure below {failed_from}, no survivor above {survived_up_to}): the likelihood grows as beta -> 0, so no lognormal fit; more records would give one"
    )]
    Separated {
        /// Largest level with a survivor.
        survived_up_to: String,
        /// Smallest level with a failure.
        failed_from: String,
    },
    /// The best fit decreases with intensity (b ≤ 0).
    #[error("the failure fraction does not increase with intensity: no lognormal fragility fits")]
    Decreasing,
    /// Fisher scoring did not converge.
    #[error("the maximum-likelihood fit did not converge")]
    NoConvergence,
}

/// Log-likelihood and, per level, (p, q = 1 − p, φ) at (a, b).
fn log_likelihood(data: &[(f64, f64, f64)], a: f64, b: f64) -> f64 {
    data.iter()
        .map(|&(u, n, z)| {
            let eta = a + b * u;
            let (p, q) = (normal_cdf(eta).max(1e-300), normal_cdf(-eta).max(1e-300));
            z * p.ln() + (n - z) * q.ln()
        })
        .sum()
}

/// Score and expected information at (a, b).
fn score_info(data: &[(f64, f64, f64)], a: f64, b: f64) -> ([f64; 2], [f64; 3]) {
    let mut s = [0.0; 2];
    let mut info = [0.0; 3];
    for &(u, n, z) in data {
        let eta = a + b * u;
        let (p, q) = (normal_cdf(eta).max(1e-300), normal_cdf(-eta).max(1e-300));
        let phi = normal_pdf(eta);
        let d = phi * (z / p - (n - z) / q);
        s[0] += d;
        s[1] += d * u;
        let w = n * phi * phi / (p * q);
        info[0] += w;
        info[1] += w * u;
        info[2] += w * u * u;
    }
    (s, info)
}

/// Inverse of the symmetric 2×2 matrix [m0 m1; m1 m2], if positive definite.
fn inverse(m: [f64; 3]) -> Option<[f64; 3]> {
    let det = m[0] * m[2] - m[1] * m[1];
    (det > 0.0 && m[0] > 0.0 && det.is_finite()).then(|| [m[2] / det, -m[1] / det, m[0] / det])
}

/// Fits the lognormal fragility to `counts` by maximum likelihood (see the
/// module docs). Levels must be > 0 and finite; levels without runs are
/// ignored.
pub fn fit(counts: &[LevelCount]) -> Result<LognormalFit, FitError> {
    let used: Vec<&LevelCount> = counts.iter().filter(|c| c.runs > 0).collect();
    let mut levels: Vec<f64> = used.iter().map(|c| c.level).collect();
    levels.sort_by(f64::total_cmp);
    levels.dedup();
    if levels.len() < 2 {
        return Err(FitError::TooFewLevels);
    }
    if used.iter().all(|c| c.failures == 0) {
        return Err(FitError::NoFailures);
    }
    if used.iter().all(|c| c.failures == c.runs) {
        return Err(FitError::AllFailed);
    }
    let survived_up_to = used
        .iter()
        .filter(|c| c.failures < c.runs)
        .map(|c| c.level)
        .fold(f64::NEG_INFINITY, f64::max);
    let failed_from = used
        .iter()
        .filter(|c| c.failures > 0)
        .map(|c| c.level)
        .fold(f64::INFINITY, f64::min);
    if survived_up_to <= failed_from {
        return Err(FitError::Separated {
            survived_up_to: format!("{survived_up_to}"),
            failed_from: format!("{failed_from}"),
        });
    }
    let data: Vec<(f64, f64, f64)> = used
        .iter()
        .map(|c| (c.level.ln(), c.runs as f64, c.failures as f64))
        .collect();
    // Start: β = 1 about the mean log level (any start climbs to the
    // maximum; this one is in its neighbourhood for typical data).
    let mean_u = data.iter().map(|d| d.0 * d.1).sum::<f64>() / data.iter().map(|d| d.1).sum::<f64>();
    let (mut a, mut b) = (-mean_u, 1.0);
    let mut ll = log_likelihood(&data, a, b);
    let mut iterations = 0;
    let mut converged = false;
    while iterations < 500 {
        iterations += 1;
        let (s, info) = score_info(&data, a, b);
        let Some(inv) = inverse(info) else {
            return Err(FitError::NoConvergence);
        };
        let step = [inv[0] * s[0] + inv[1] * s[1], inv[1] * s[0] + inv[2] * s[1]];
        let mut t = 1.0;
        let mut accepted = false;
        for _ in 0..60 {
            let (a1, b1) = (a + t * step[0], b + t * step[1]);
            let ll1 = log_likelihood(&data, a1, b1);
            if ll1.is_finite() && ll1 >= ll - 1e-12 * ll.abs() {
                (a, b, ll) = (a1, b1, ll1);
                accepted = true;
                break;
            }
            t *= 0.5;
        }
        let size = (t * step[0]).abs().max((t * step[1]).abs());
        if !accepted || size <= 1e-12 * (1.0 + a.abs().max(b.abs())) {
            converged = accepted || size <= 1e-9 * (1.0 + a.abs().max(b.abs()));
            break;
        }
    }
    if !(converged && a.is_finite() && b.is_finite()) {
        return Err(FitError::NoConvergence);
    }
    if b <= 0.0 {
        return Err(FitError::Decreasing);
    }
    let (_, info) = score_info(&data, a, b);
    let cov = inverse(info).ok_or(FitError::NoConvergence)?;
    let (beta, ln_median) = (1.0 / b, -a / b);
    // Delta method: ∇ln θ̂ = (−1/b, a/b²); ∇ln β = (0, −1/b).
    let (ga, gb) = (-1.0 / b, a / (b * b));
    let var_ln_median = ga * ga * cov[0] + 2.0 * ga * gb * cov[1] + gb * gb * cov[2];
    let var_ln_beta = cov[2] / (b * b);
    let (se_m, se_b) = (var_ln_median.max(0.0).sqrt(), var_ln_beta.max(0.0).sqrt());
    let fit = LognormalFit {
        median: ln_median.exp(),
        beta,
        median_ci95: [(ln_median - Z95 * se_m).exp(), (ln_median + Z95 * se_m).exp()],
        beta_ci95: [beta * (-Z95 * se_b).exp(), beta * (Z95 * se_b).exp()],
        se_ln_median: se_m,
        se_ln_beta: se_b,
        log_likelihood: ll,
        iterations,
        cov,
    };
    let numbers = [
        fit.median,
        fit.beta,
        fit.median_ci95[0],
        fit.median_ci95[1],
        fit.beta_ci95[0],
        fit.beta_ci95[1],
        fit.log_likelihood,
    ];
    if numbers.iter().all(|x| x.is_finite()) {
        Ok(fit)
    } else {
        Err(FitError::NoConvergence)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn normal_cdf_matches_tabulated_values() {
        // erfc(1), erf(0.5), erfc(3), erfc(5): standard tables (Abramowitz
        // & Stegun 7.1 / high-precision values).
        let cases = [
            (-std::f64::consts::SQRT_2, 0.5 * 0.157_299_207_050_285_13),
            (0.5 * std::f64::consts::SQRT_2, 0.5 * (1.0 + 0.520_499_877_813_046_5)),
            (-3.0 * std::f64::consts::SQRT_2, 0.5 * 2.209_049_699_858_544e-5),
            (-5.0 * std::f64::consts::SQRT_2, 0.5 * 1.537_459_794_428_035e-12),
            (-2.0 * std::f64::consts::SQRT_2, 0.5 * 4.677_734_981_047_266e-3),
            (Z95, 0.975),
            (0.0, 0.5),
        ];
        for (z, want) in cases {
            let got = normal_cdf(z);
            assert!((got - want).abs() <= 1e-13 * want, "Φ({z}) = {got}, want {want}");
        }
        for z in [-7.0, -2.9, -0.3, 0.0, 1.1, 2.82, 2.83, 6.5] {
            assert!((normal_cdf(z) + normal_cdf(-z) - 1.0).abs() < 1e-15, "{z}");
        }
        // Continuity at the switch between series and continued fraction.
        let x = 2.0 * std::f64::consts::SQRT_2;
        let step = normal_cdf(-x + 1e-12) - normal_cdf(-x - 1e-12);
        assert!((step - 2e-12 * normal_pdf(x)).abs() < 5e-13 * normal_cdf(-x), "{step}");
    }

    fn exact_counts(median: f64, beta: f64, runs: u64) -> Vec<LevelCount> {
        (1..=15)
            .map(|i| {
                let level = 0.1 * f64::from(i);
                let p = normal_cdf((level / median).ln() / beta);
                LevelCount {
                    level,
                    runs,
                    failures: (p * runs as f64).round() as u64,
                }
            })
            .collect()
    }

    #[test]
    fn recovers_known_parameters_from_expected_counts() {
        let f = fit(&exact_counts(0.55, 0.4, 1_000_000)).unwrap();
        assert!((f.median / 0.55 - 1.0).abs() < 1e-4, "{f:?}");
        assert!((f.beta / 0.4 - 1.0).abs() < 1e-4, "{f:?}");
        assert!(f.median_ci95[0] < 0.55 && 0.55 < f.median_ci95[1]);
        assert!(f.beta_ci95[0] < 0.4 && 0.4 < f.beta_ci95[1]);
        // A million runs per level: the intervals are narrow.
        assert!(f.median_ci95[1] / f.median_ci95[0] < 1.01, "{f:?}");
        let at = f.at(0.55);
        assert!((at.p - 0.5).abs() < 1e-4 && at.lo < at.p && at.p < at.hi);
    }

    #[test]
    fn recovers_parameters_from_sampled_counts_within_the_band() {
        // Deterministic pseudo-random binomial draws (a 64-bit LCG), 40 runs
        // per level, as a fragility study has: the true values lie inside
        // the 95 % intervals for this seed, and the estimates are close.
        let (median, beta) = (0.8, 0.5);
        let mut state: u64 = 0x2545_f491_4f6c_dd1d;
        let mut uniform = || {
            state = state
                .wrapping_mul(6_364_136_223_846_793_005)
                .wrapping_add(1_442_695_040_888_963_407);
            (state >> 11) as f64 / (1u64 << 53) as f64
        };
        let counts: Vec<LevelCount> = (1..=20)
            .map(|i| {
                let level = 0.1 * f64::from(i);
                let p = normal_cdf((level / median).ln() / beta);
                let failures = (0..40).filter(|_| uniform() < p).count() as u64;
                LevelCount {
                    level,
                    runs: 40,
                    failures,
                }
            })
            .collect();
        let f = fit(&counts).unwrap();
        assert!(f.median_ci95[0] < median && median < f.median_ci95[1], "{f:?}");
        assert!(f.beta_ci95[0] < beta && beta < f.beta_ci95[1], "{f:?}");
        assert!(
            (f.median / median - 1.0).abs() < 0.1 && (f.beta / beta - 1.0).abs() < 0.3,
            "{f:?}"
        );
    }

    #[test]
    fn separated_and_one_sided_data_are_not_fitted() {
        let c = |level, runs, failures| LevelCount { level, runs, failures };
        assert_eq!(fit(&[c(0.1, 5, 0), c(0.2, 5, 0)]), Err(FitError::NoFailures));
        assert_eq!(fit(&[c(0.1, 5, 5), c(0.2, 5, 5)]), Err(FitError::AllFailed));
        assert_eq!(fit(&[c(0.1, 5, 2)]), Err(FitError::TooFewLevels));
        assert!(matches!(
            fit(&[c(0.1, 5, 0), c(0.2, 5, 3), c(0.3, 5, 5)]),
            Err(FitError::Separated { .. })
        ));
        assert_eq!(fit(&[c(0.1, 5, 4), c(0.2, 5, 1)]), Err(FitError::Decreasing));
        // Not separated: a failure below a survivor.
        assert!(fit(&[c(0.1, 5, 0), c(0.2, 5, 1), c(0.3, 5, 4), c(0.4, 5, 5)]).is_ok());
    }
}
