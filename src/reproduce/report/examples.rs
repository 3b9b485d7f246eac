//! The sections on the response examples: each example's figures and
//! table against the paper's statements, the example with other impact
//! laws, and the table of the exponents in three units.

use std::fmt::Write as _;

use super::Row;
use super::claims::{
    amplitude_verdict, best_exponent, class_verdict, exponent_verdict, lyapunov_result, lyapunov_verdict, near_quoted,
    neighbours_verdict,
};
use super::markdown::{lyapunov_text, neighbours_text, paper_statements, peaks_text, response_word};
use crate::analysis::classify::Response;
use crate::analysis::lyapunov::{Lyapunov, LyapunovResult};
use crate::reproduce::Reproduction;
use crate::reproduce::diagrams::short;
use crate::reproduce::format::{block_and_impact, prefix, short_num, short_params};
use crate::reproduce::paper::{FIGURES, PaperFigure};
use crate::reproduce::response::{ResponseExample, TransientExponent, TransientWindow};
use crate::sim::Outcome;

/// The section of a response example: its figures, the paper's
/// statements and the table of quantities, paper against ours.
pub(super) fn response_section(out: &mut String, rows: &mut Vec<Row>, rep: &Reproduction, f: &PaperFigure) {
    let _ = writeln!(out, "## Fig. {}: {}\n", f.number, f.caption);
    let Some(r) = rep.response(f.number) else {
        out.push_str("Not computed.\n\n");
        return;
    };
    let p = prefix(f.number);
    let _ = writeln!(
        out,
        "(a) ![Fig. {n} (a) time history]({p}time_history.png)\n",
        n = f.number
    );
    if r.spectrum_paper.is_ok() {
        let _ = writeln!(
            out,
            "(b) ![Fig. {n} (b) spectrum, the paper's window]({p}spectrum_paper_window.png)\n",
            n = f.number
        );
    }
    if r.spectrum_long.is_ok() {
        let _ = writeln!(
            out,
            "(b) ![Fig. {n} (b) spectrum, a long window]({p}spectrum_long_window.png)\n",
            n = f.number
        );
    }
    let _ = writeln!(
        out,
        "(c) ![Fig. {n} (c) Poincaré map]({p}poincare.png)\n\n(SVG beside each PNG; the Poincaré points in `{p}poincare.csv`.)\n",
        n = f.number
    );
    paper_statements(out, f);
    let _ = writeln!(
        out,
        "**Ours** ({}; {}):\n",
        short_params(&r.config, true),
        block_and_impact(&r.config)
    );
    out.push_str("| quantity | paper | ours | verdict |\n|---|---|---|---|\n");
    let fig = f.number.to_string();
    let terminal = matches!(r.long_outcome, Outcome::Tumbled | Outcome::Flight);
    // The class.
    let mut ours_class = format!(
        "{}{}",
        response_word(r.response),
        match (&r.lyapunov, r.response) {
            (Ok(Lyapunov::Exponents(_)), Response::Chaotic | Response::Quasiperiodic) => " (decided by λ)",
            _ => "",
        }
    );
    if terminal {
        let _ = write!(ours_class, " at τ = {:.1}", r.long_tau_end);
    }
    let (paper_class, class_verdict) = class_verdict(f.chaotic, r.response);
    let transient_note = match (r.response, lyapunov_result(&r.lyapunov)) {
        (Response::Periodic { .. }, Some(l)) if l.largest_per_tau > 0.01 => {
            " — yet λ > 0 over the Lyapunov window: the run rocks chaotically for a long time before it settles (a chaotic transient)"
        }
        _ => "",
    };
    let _ = writeln!(
        out,
        "| response at the end of the long run (τ {}–{}) | {paper_class} | {ours_class}{transient_note} | {class_verdict} |",
        short_num(r.end_from),
        short_num(r.long_tau_end)
    );
    if f.chaotic.is_some() {
        rows.push(Row {
            figure: fig.clone(),
            claim: "response (end of the long run)".to_string(),
            paper: paper_class.to_string(),
            ours: ours_class.clone(),
            verdict: class_verdict.to_string(),
        });
    }
    // The neighbours.
    if !r.neighbours.is_empty() {
        let verdict = neighbours_verdict(f.chaotic, &r.neighbours);
        let _ = writeln!(
            out,
            "| neighbouring runs A_v·(1 + k·10⁻⁹), τ {}–{} | {paper_class} | {} | {verdict} |",
            r.settings.transient,
            r.settings.history_end,
            neighbours_text(r)
        );
        if f.chaotic.is_some() {
            rows.push(Row {
                figure: fig.clone(),
                claim: "neighbouring runs (A_v·(1 + k·10⁻⁹))".to_string(),
                paper: paper_class.to_string(),
                ours: neighbours_text(r),
                verdict: verdict.to_string(),
            });
        }
    }
    // The run's end.
    let ended = match r.tumble_tau {
        Some(t) => format!("tumbled at τ = {t:.2}"),
        None => format!("{:?}", r.outcome).to_lowercase(),
    };
    let long_ended = format!(
        "{} at τ = {}",
        format!("{:?}", r.long_outcome).to_lowercase(),
        short_num(r.long_tau_end)
    );
    let _ = writeln!(
        out,
        "| end of the paper's run (τ 0–{}) / of the long run (τ 0–{}) | blank = tumbling | {ended} / {long_ended} | — |",
        r.settings.history_end, r.settings.long_end
    );
    // Amplitude.
    let steady = r.max_abs_theta_steady.map_or("—".to_string(), |m| format!("{m:.3}"));
    let amp = format!(
        "{:.3} over τ 0–{}; {steady} over τ {}–{}; {:.3} over the long run",
        r.max_abs_theta, r.settings.history_end, r.settings.transient, r.settings.history_end, r.long_max_abs_theta
    );
    match f.max_amplitude {
        Some(pa) => {
            let verdict = amplitude_verdict(pa, r.max_abs_theta);
            let _ = writeln!(out, "| max \\|Θ\\| | about {pa} | {amp} | {verdict} |");
            rows.push(Row {
                figure: fig.clone(),
                claim: "max |Θ| (τ 0–800)".to_string(),
                paper: format!("about {pa}"),
                ours: format!("{:.3} (τ 600–800: {steady})", r.max_abs_theta),
                verdict: verdict.to_string(),
            });
        }
        None => {
            let _ = writeln!(out, "| max \\|Θ\\| | not quoted | {amp} | — |");
        }
    }
    // Lyapunov.
    let lt = lyapunov_text(&r.lyapunov);
    let quoted = f
        .lyapunov
        .map_or("not quoted".to_string(), |pl| format!("{pl} (units not stated)"));
    let main_verdict = exponent_verdict(f.lyapunov, lyapunov_result(&r.lyapunov), "differs (no steady exponent)");
    let _ = writeln!(
        out,
        "| largest Lyapunov exponent, τ {}–{} | {quoted} | {lt} | {main_verdict} |",
        r.settings.lyapunov_transient, r.settings.lyapunov_end
    );
    if let Some(TransientExponent {
        window: TransientWindow {
            from,
            to,
            tumble_tau: tumble,
        },
        lyapunov: l,
    }) = &r.transient_lyapunov
    {
        let v = exponent_verdict(f.lyapunov, lyapunov_result(l), "differs");
        let _ = writeln!(
            out,
            "| largest Lyapunov exponent of the chaotic transient, τ {from:.0}–{to:.0} (that run tumbles at τ = {tumble:.1}) | {quoted} | {} | {v} |",
            lyapunov_text(l)
        );
    }
    if let Some(pl) = f.lyapunov {
        let (ours, verdict) = match best_exponent(r) {
            Some((res, None)) => (
                format!("{:.3} per τ, {:.3} per cycle", res.largest_per_tau, res.per_cycle),
                lyapunov_verdict(pl, res).0,
            ),
            Some((res, Some(TransientWindow { from: a, to: b, .. }))) => (
                format!(
                    "chaotic transient before tumbling (τ {a:.0}–{b:.0}): {:.3} per τ, {:.3} per cycle",
                    res.largest_per_tau, res.per_cycle
                ),
                format!("{} (transient)", lyapunov_verdict(pl, res).0),
            ),
            None => (lt.clone(), "differs".to_string()),
        };
        rows.push(Row {
            figure: fig.clone(),
            claim: "largest Lyapunov exponent".to_string(),
            paper: format!("{pl}"),
            ours,
            verdict,
        });
    }
    if let Some((res, _)) = best_exponent(r) {
        let spectrum: Vec<String> = res
            .spectrum
            .iter()
            .zip(&res.spectrum_stderr)
            .map(|(l, e)| format!("{l:.3} ± {e:.3}"))
            .collect();
        let _ = writeln!(
            out,
            "| Lyapunov spectrum of (Θ, Θ', X') per τ | — | {}{} | — |",
            spectrum.join(", "),
            if res.collapsed > 0 {
                format!(
                    " and {} direction(s) at −∞ (slip velocity reset at sticking impacts)",
                    res.collapsed
                )
            } else {
                String::new()
            }
        );
    }
    let _ = writeln!(
        out,
        "| spectral peaks, ω/Ω_h, paper's window τ 12–28.4 | periodic: one line; chaotic: broadband | {} | — |",
        peaks_text(&r.spectrum_paper)
    );
    let _ = writeln!(
        out,
        "| spectral peaks, ω/Ω_h, τ {}–{}{} | — | {} | — |",
        short_num(r.steady_from),
        short_num(r.long_tau_end),
        if terminal { " (before the tumble)" } else { "" },
        peaks_text(&r.spectrum_long)
    );
    let mean = r
        .poincare_mean
        .map_or("—".to_string(), |(a, b)| format!("mean Θ = {a:.3}, mean Θ' = {b:.3}"));
    let _ = writeln!(
        out,
        "| Poincaré points from τ = {}{} | — | {} points; {mean} | — |",
        short_num(r.steady_from),
        if terminal { " to the tumble" } else { "" },
        r.poincare.len()
    );
    let _ = writeln!(
        out,
        "| impacts per forcing cycle; times N ≤ 0 (flight ignored) | — | {:.2}; {} | — |\n",
        r.impacts_per_cycle, r.flight_violations
    );
    variants_table(out, rows, rep, f, r);
}

/// The response example recomputed with other impact laws.
fn variants_table(out: &mut String, rows: &mut Vec<Row>, rep: &Reproduction, f: &PaperFigure, r: &ResponseExample) {
    let variants = rep.response_variants(f.number);
    if variants.is_empty() {
        return;
    }
    let _ = writeln!(
        out,
        "**Impact-law variants** (the preset's `ratio` law with r = 0.925 replaced; labelled VARIANT, never a default). The response is classified from the end of a run to τ = {}, the exponent by tangent dynamics over τ {}–{} (or over the rocking before a tumble):\n",
        r.settings.long_end, r.settings.lyapunov_transient, r.settings.lyapunov_end
    );
    out.push_str(
        "| impact law | response at the end | max \\|Θ\\| (τ 0–800) | largest exponent per τ |\n|---|---|---|---|\n",
    );
    let exponent = |main: &Result<Lyapunov, String>, tr: &Option<TransientExponent>| match (lyapunov_result(main), tr) {
        (Some(l), _) => format!("{:.3} ± {:.3}", l.largest_per_tau, l.stderr),
        (
            None,
            Some(TransientExponent {
                window: TransientWindow { from: a, to: b, .. },
                lyapunov: t,
            }),
        ) => match lyapunov_result(t) {
            Some(l) => format!(
                "{:.3} ± {:.3} (transient, τ {a:.0}–{b:.0})",
                l.largest_per_tau, l.stderr
            ),
            None => lyapunov_text(t),
        },
        (None, None) => lyapunov_text(main),
    };
    let _ = writeln!(
        out,
        "| preset: ratio r = 0.925 | {} | {:.3} | {} |",
        response_word(r.response),
        r.max_abs_theta,
        exponent(&r.lyapunov, &r.transient_lyapunov)
    );
    let mut chaotic: Vec<String> = Vec::new();
    for v in &variants {
        let end = match v.tumble_tau {
            Some(t) => format!("tumbled at τ = {t:.1}"),
            None => response_word(v.response),
        };
        let _ = writeln!(
            out,
            "| {} (`{}`) | {end} | {:.3} | {} |",
            v.variant.title().trim_start_matches("VARIANT: "),
            v.sets.join("` `"),
            v.max_abs_theta,
            exponent(&v.lyapunov, &v.transient_lyapunov)
        );
        if v.response == Response::Chaotic {
            chaotic.push(v.variant.slug());
        }
    }
    out.push('\n');
    if f.chaotic == Some(true) {
        let ours: Vec<String> = variants
            .iter()
            .map(|v| format!("{}: {}", v.variant.slug(), short(v.response)))
            .collect();
        rows.push(Row {
            figure: f.number.to_string(),
            claim: "response with other impact laws (end of the long run)".to_string(),
            paper: "chaotic".to_string(),
            ours: ours.join("; "),
            verdict: if chaotic.is_empty() {
                "no variant is chaotic".to_string()
            } else {
                format!("chaotic with {}", chaotic.join(", "))
            },
        });
    }
}

/// The table of the quoted exponents against ours in three units.
pub(super) fn units_section(out: &mut String, rep: &Reproduction) {
    let quoted: Vec<(&PaperFigure, &ResponseExample, &LyapunovResult, bool)> = FIGURES
        .iter()
        .filter_map(|f| {
            f.lyapunov?;
            let r = rep.response(f.number)?;
            let (l, w) = best_exponent(r)?;
            Some((f, r, l, w.is_some()))
        })
        .collect();
    let Some(first) = quoted.first() else {
        return;
    };
    out.push_str("## Lyapunov exponents: which unit did the paper use?\n\n");
    let p = first.1.config.geometry().p;
    let _ = writeln!(
        out,
        "The paper quotes its exponents without a unit or a method. Ours are natural-log rates per unit τ = p t, per excitation cycle (× 2π/Ω_h) and per second (× p, with p = √(3g/4R) = {p:.3} 1/s). \"transient\" marks the exponent of the chaotic rocking before a tumble.\n"
    );
    out.push_str(
        "| Fig. | paper | ours per τ | per cycle | per second | two trajectories per τ |\n|---|---|---|---|---|---|\n",
    );
    let (mut near_tau, mut near_cycle, mut near_second) = (0, 0, 0);
    for (f, _, l, transient) in &quoted {
        let pl = f.lyapunov.unwrap_or(0.0);
        let per_s = l.largest_per_tau * p;
        let close = |x: f64| near_quoted(x, pl);
        near_tau += usize::from(close(l.largest_per_tau));
        near_cycle += usize::from(close(l.per_cycle));
        near_second += usize::from(close(per_s));
        let b = l.check.map_or("—".to_string(), |c| {
            format!("{:.3} ± {:.3}", c.benettin_per_tau, c.benettin_stderr)
        });
        let _ = writeln!(
            out,
            "| {}{} | {pl} | {:.3} ± {:.3} | {:.3} ± {:.3} | {per_s:.3} | {b} |",
            f.number,
            if *transient { " (transient)" } else { "" },
            l.largest_per_tau,
            l.stderr,
            l.per_cycle,
            l.stderr_per_cycle
        );
    }
    let _ = writeln!(
        out,
        "\nWithin 15 % of the paper's value: {near_tau} of {n} per τ, {near_cycle} of {n} per cycle, {near_second} of {n} per second.\n",
        n = quoted.len()
    );
    out.push_str("A unit explains the paper's exponents only if one column matches them all. The paper does not say how it computed its exponents (nor how it treated the impacts, across which a naive two-trajectory estimate is wrong), and its runs were shorter and fixed-step, so a quoted exponent may also differ for those reasons.\n\n");
}
