//! The verdict rules: for each kind of statement of the paper that a
//! number can check, what is compared and which verdict follows. The
//! sections of the report ([`super::bifurcation`], [`super::examples`],
//! [`super::across`]) write the tables; the rules live here so that each
//! can be tested on small inputs. The report states every rule beside the
//! table that uses it, so a change here wants the prose there changed too.
//!
//! Verdicts are *agrees*, *partly* and *differs* (the words the summary
//! counts, see [`super::tally`]), sometimes with a reason in brackets, or
//! "—" where a statement cannot be checked.

use super::markdown::{cascade_text, of, pct};
use crate::analysis::classify::Response;
use crate::analysis::lyapunov::{Lyapunov, LyapunovResult};
use crate::reproduce::diagrams::{Shares, intermittency_switches, is_period_doubling};
use crate::reproduce::response::{ResponseExample, TransientWindow};

/// The range tolerance for "about" in the paper's A_v ranges: 0.1, or one
/// grid step if coarser.
pub(super) fn range_tol(step: f64) -> f64 {
    step.max(0.1)
}

/// The exponents of a Lyapunov run, if it has finite ones.
pub(super) fn lyapunov_result(l: &Result<Lyapunov, String>) -> Option<&LyapunovResult> {
    match l {
        Ok(Lyapunov::Exponents(r)) => Some(r),
        Ok(Lyapunov::None { .. }) | Err(_) => None,
    }
}

/// The exponent to compare with the paper's: the steady one, or else that
/// of the chaotic transient before a tumble, with its window `(from, to,
/// tumble τ)`.
pub(super) fn best_exponent(r: &ResponseExample) -> Option<(&LyapunovResult, Option<TransientWindow>)> {
    if let Some(l) = lyapunov_result(&r.lyapunov) {
        return Some((l, None));
    }
    let t = r.transient_lyapunov.as_ref()?;
    lyapunov_result(&t.lyapunov).map(|l| (l, Some(t.window)))
}

/// Whether a quoted exponent `paper` matches ours in one of the two units:
/// within 3 standard errors or 15 % of the paper's value, whichever is
/// larger (the paper gives two digits and no error bar).
pub(super) fn lyapunov_verdict(paper: f64, r: &LyapunovResult) -> (String, bool) {
    let close = |ours: f64, err: f64| (ours - paper).abs() <= (3.0 * err).max(0.15 * paper.abs());
    let per_tau = close(r.largest_per_tau, r.stderr);
    let per_cycle = close(r.per_cycle, r.stderr_per_cycle);
    let sign = if r.largest_per_tau > 0.0 {
        "positive, as the paper's"
    } else {
        "not positive, unlike the paper's"
    };
    let text = match (per_tau, per_cycle) {
        (true, true) => format!("agrees (per τ and per cycle); {sign}"),
        (true, false) => format!("agrees per τ; {sign}"),
        (false, true) => format!("agrees per cycle; {sign}"),
        (false, false) => format!("differs in value in both units; {sign}"),
    };
    (text, per_tau || per_cycle)
}

/// The verdict on an exponent: by [`lyapunov_verdict`] where the paper
/// quotes one and we have one, `missing` where we have none, "—" where the
/// paper quotes none.
pub(super) fn exponent_verdict(paper: Option<f64>, ours: Option<&LyapunovResult>, missing: &str) -> String {
    match (paper, ours) {
        (Some(pl), Some(res)) => lyapunov_verdict(pl, res).0,
        (Some(_), None) => missing.to_string(),
        (None, _) => "—".to_string(),
    }
}

/// Whether one of our exponents is near a quoted one for the unit table:
/// within 15 % of the paper's value.
pub(super) fn near_quoted(ours: f64, paper: f64) -> bool {
    (ours - paper).abs() <= 0.15 * paper.abs()
}

/// Whether the two Lyapunov methods agree on one trajectory: their paired
/// difference within 3 standard errors, or within 0.01.
pub(super) fn methods_agree(difference: f64, stderr: f64) -> bool {
    difference.abs() <= 3.0 * stderr || difference.abs() <= 0.01
}

/// The verdict on an exponent quoted without its A_v: it agrees when it
/// lies within the range `lo`–`hi` of our exponents per τ, or within that
/// range per cycle (× `period`).
pub(super) fn exponent_range_verdict(paper: f64, lo: f64, hi: f64, period: f64) -> &'static str {
    let inside = |a: f64, b: f64| paper >= a && paper <= b;
    if inside(lo, hi) || inside(lo * period, hi * period) {
        "agrees (within our range)"
    } else {
        "differs (outside our range)"
    }
}

/// The paper's class of a response example (`chaotic` as in
/// [`crate::reproduce::paper::PaperFigure::chaotic`]) and the verdict on
/// ours: only "chaotic" is a statement to check.
pub(super) fn class_verdict(chaotic: Option<bool>, ours: Response) -> (&'static str, &'static str) {
    match chaotic {
        Some(true) => ("chaotic", if ours == Response::Chaotic { "agrees" } else { "differs" }),
        Some(false) => ("not chaotic", "—"),
        None => ("not stated", "—"),
    }
}

/// The verdict on the neighbouring runs of an example the paper calls
/// chaotic (`neighbours` not empty): most chaotic agrees, some partly,
/// none differs.
pub(super) fn neighbours_verdict(chaotic: Option<bool>, neighbours: &[Response]) -> &'static str {
    let count = neighbours.iter().filter(|x| **x == Response::Chaotic).count();
    match chaotic {
        Some(true) if 2 * count >= neighbours.len() => "agrees (most are chaotic)",
        Some(true) if count > 0 => "partly (some are chaotic)",
        Some(true) => "differs (none is chaotic)",
        Some(false) | None => "—",
    }
}

/// The verdict on a quoted maximum amplitude ("about" `paper`): ±0.1.
pub(super) fn amplitude_verdict(paper: f64, ours: f64) -> &'static str {
    if (ours - paper).abs() <= 0.1 {
        "agrees (±0.1)"
    } else {
        "differs"
    }
}

/// Whether a variant explains a range of the paper's: it does when
/// `share` of the range's values match, at least 3/4 (the rule of a
/// chaotic range in [`crate::reproduce::diagrams::compare_ranges`]).
pub(super) fn explains(share: f64) -> bool {
    share >= 0.75
}

/// The verdict on the neighbouring runs of tumbled values: of `total`
/// runs, `still` rock on at the window's end, `chaotic` of them
/// chaotically.
pub(super) fn survival_verdict(still: usize, chaotic: usize, total: usize) -> String {
    if 2 * still >= total {
        "most rock on: a run of the paper's length could well show rocking here".to_string()
    } else if chaotic > 0 {
        format!(
            "a few ({}) rock on chaotically: chance alone does not explain the paper's range",
            pct(chaotic as f64 / total.max(1) as f64)
        )
    } else {
        "none rocks on".to_string()
    }
}

/// The outcome of the impact-ratio scan, from `(r, ranges that agree)` per
/// r in scan order and the number of the paper's ranges: the sentence for
/// the report and the verdict for the summary. An r reproduces the paper
/// when every range agrees; failing that, the first r with the most
/// agreeing ranges is named.
pub(super) fn ratio_scan_verdict(
    agreeing: &[(f64, usize)],
    ranges: usize,
    name: &dyn Fn(f64) -> String,
) -> (String, String) {
    let all: Vec<String> = agreeing
        .iter()
        .filter(|(_, a)| *a == ranges)
        .map(|(r, _)| name(*r))
        .collect();
    let mut best: Option<(f64, usize)> = None;
    for &(r, agree) in agreeing {
        if best.is_none_or(|b| agree > b.1) {
            best = Some((r, agree));
        }
    }
    if all.is_empty() {
        (
            format!(
                "No r in the scan reproduces every range; the most ranges ({} of {ranges}) agree at r = {}.",
                best.map_or(0, |b| b.1),
                best.map_or("—".to_string(), |b| name(b.0))
            ),
            "none found".to_string(),
        )
    } else {
        (
            format!("Every range agrees at r = {}.", all.join(", ")),
            format!("r = {}", all.join(", ")),
        )
    }
}

/// The outcome of checking one comparative statement.
pub(super) enum Check {
    /// Checked: what we found and whether it agrees.
    Done(String, bool),
    /// Not checkable, and why.
    Skip(String),
}

/// A statement whose figures were left out of the run.
pub(super) fn not_computed() -> Check {
    Check::Skip("not computed (--only)".to_string())
}

/// The verdict word of a check.
pub(super) fn check_verdict(check: &Check) -> &'static str {
    match check {
        Check::Done(_, true) => "agrees",
        Check::Done(_, false) => "differs",
        Check::Skip(_) => "—",
    }
}

/// "The periodic region of `x` is wider than that of `y`."
pub(super) fn periodic_wider(x: &Shares, y: &Shares) -> Check {
    Check::Done(
        format!("periodic {} vs {}", of(x.periodic, x.count), of(y.periodic, y.count)),
        x.periodic > y.periodic,
    )
}

/// "The periodic region of `x` is narrower than that of `y`."
pub(super) fn periodic_narrower(x: &Shares, y: &Shares) -> Check {
    Check::Done(
        format!("periodic {} vs {}", of(x.periodic, x.count), of(y.periodic, y.count)),
        x.periodic < y.periodic,
    )
}

/// "The tumbling region of `x` is narrower than that of `y`."
pub(super) fn tumbling_narrower(x: &Shares, y: &Shares) -> Check {
    Check::Done(
        format!("tumbled {} vs {}", of(x.tumbled, x.count), of(y.tumbled, y.count)),
        x.tumbled < y.tumbled,
    )
}

/// "The chaotic region of `x` is wider than that of `y`" (chaotic or
/// quasiperiodic values).
pub(super) fn chaotic_wider(x: &Shares, y: &Shares) -> Check {
    Check::Done(
        format!("chaotic {} vs {}", of(x.aperiodic, x.count), of(y.aperiodic, y.count)),
        x.aperiodic > y.aperiodic,
    )
}

/// "Intermittency": periodic and chaotic values intermingled, read as at
/// least 4 switches between them along the sweep.
pub(super) fn intermittent(values: &[(f64, Response)]) -> Check {
    let s = intermittency_switches(values);
    Check::Done(format!("{s} periodic↔aperiodic switches"), s >= 4)
}

/// "Period doubling (1,1) → (1,2) → (1,4) → chaos", read by
/// [`is_period_doubling`].
pub(super) fn period_doubling(values: &[(f64, Response)]) -> Check {
    Check::Done(cascade_text(values), is_period_doubling(values))
}

/// "The maximum amplitude of `a` is larger than that of `b`", each as
/// `(max |Θ|, tumble τ)`: not comparable when both tumble, since both then
/// reach |Θ| = 1.
pub(super) fn amplitude_larger(a: (f64, Option<f64>), b: (f64, Option<f64>)) -> Check {
    match (a.1, b.1) {
        (Some(ta), Some(tb)) => Check::Skip(format!(
            "not comparable: both tumble (τ = {ta:.1} and {tb:.1}), so both reach |Θ| = 1"
        )),
        _ => Check::Done(format!("max |Θ| {:.3} vs {:.3}", a.0, b.0), a.0 > b.0),
    }
}

/// "The response reached a tumbling level", read as max |Θ| ≥ 0.9.
pub(super) fn tumbling_level(max_abs_theta: f64, tumble_tau: Option<f64>) -> Check {
    Check::Done(
        format!(
            "max |Θ| {max_abs_theta:.3}{}",
            tumble_tau.map_or(String::new(), |t| format!(", tumbled at τ = {t:.1}"))
        ),
        max_abs_theta >= 0.9,
    )
}

/// "Lower friction gives a smaller maximum amplitude", on three examples
/// in order of decreasing friction: strictly decreasing.
pub(super) fn amplitude_decreasing([a, b, c]: [f64; 3]) -> Check {
    Check::Done(format!("max |Θ| {a:.3} > {b:.3} > {c:.3}?"), a > b && b > c)
}

/// An example's figure and its exponent per τ with a label (" (transient)"
/// or ""), if it has one.
pub(super) type Exponent<'a> = (u32, Option<(f64, &'a str)>);

/// "λ is larger with sliding": every exponent of `with` (examples that
/// slide) above that of `without`; not checkable where one is missing.
pub(super) fn lambda_larger(without: Exponent, with: &[Exponent]) -> Check {
    let Some((la, ta)) = without.1 else {
        return Check::Skip(format!("Fig. {} has no exponent", without.0));
    };
    let mut lb = Vec::new();
    for (figure, l) in with {
        match l {
            Some(x) => lb.push(*x),
            None => return Check::Skip(format!("Fig. {figure} has no exponent")),
        }
    }
    let text = format!(
        "λ {la:.3}{ta} without sliding vs {} with (per τ)",
        lb.iter()
            .map(|(x, t)| format!("{x:.3}{t}"))
            .collect::<Vec<_>>()
            .join(", ")
    );
    Check::Done(text, lb.iter().all(|x| x.0 > la))
}

/// "The attractor is inclined toward negative Θ'", read as a negative mean
/// Θ' of the Poincaré points (`mean` = (mean Θ, mean Θ')).
pub(super) fn inclined(mean: Option<(f64, f64)>) -> Check {
    match mean {
        Some((_, b)) => Check::Done(format!("mean Θ' = {b:.3}"), b < 0.0),
        None => Check::Skip("no Poincaré points".to_string()),
    }
}

/// "The attractor is asymmetrical about Θ = 0", read as |mean Θ| above 5 %
/// of the largest |Θ| of the `points` (Θ, Θ'); `tumbled` notes that they
/// are the transient's.
pub(super) fn asymmetrical(mean: Option<(f64, f64)>, points: &[(f64, f64)], tumbled: bool) -> Check {
    match mean {
        Some((m, _)) => {
            let top = points.iter().map(|p| p.0.abs()).fold(0.0, f64::max);
            Check::Done(
                format!(
                    "mean Θ = {m:.3}, largest |Θ| {top:.3}{}",
                    if tumbled {
                        " (points of the transient before the tumble)"
                    } else {
                        ""
                    }
                ),
                m.abs() > 0.05 * top,
            )
        }
        None => Check::Skip("no Poincaré points".to_string()),
    }
}
