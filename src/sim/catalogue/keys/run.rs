//! The keys of a run: its `[initial]` state, how `[run]` integrates it and what `[analysis]` adds.

use super::{B, RECORD, at, atol, lin, open_unit, rtol, spacing, tail, zeno};
use crate::sim::catalogue::{Dimension, Group, KeySpec, Param, Range, Value};

/// The `[initial]` keys: the state a run starts from.
pub(super) const INITIAL: &[KeySpec] = &[
    // [initial]
    KeySpec {
        key: "initial.theta",
        value: Value::Quantity(Dimension::Rotation),
        symbol: "Θ₀",
        unit: "ψ",
        meaning: "initial rotation",
        written: "\"0.01 rad\", \"0.5 deg\"",
        doc: "Θ at τ = 0, |Θ| < tumble angle. Default 0 (flat). Click the phase portrait to set Θ₀ and Θ'₀.",
        param: Some(Param::Theta0),
        slot: at(Group::Initial, 0),
        slider: lin(-1.0, 1.0, 0.05),
        ..B
    },
    KeySpec {
        key: "initial.theta_dot",
        value: Value::Quantity(Dimension::AngularVelocity),
        symbol: "Θ'₀",
        unit: "ψ p",
        meaning: "initial angular velocity",
        written: "\"0.1 rad/s\", \"5 deg/s\"",
        doc: "Θ' at τ = 0. Default 0.",
        param: Some(Param::ThetaDot0),
        slot: at(Group::Initial, 1),
        slider: lin(-3.0, 3.0, 0.1),
        ..B
    },
    KeySpec {
        key: "initial.x_dot",
        value: Value::Quantity(Dimension::Velocity),
        symbol: "X'₀",
        unit: "R p",
        meaning: "initial velocity of the centre of mass",
        written: "\"0.1 m/s\", \"10 cm/s\"",
        doc: "X' of the centre of mass at τ = 0. Default: no slip of the contact corner.",
        param: Some(Param::XDot0),
        slot: at(Group::Initial, 2),
        slider: lin(-3.0, 3.0, 0.1),
        ..B
    },
];

/// The `[run]` keys: how to integrate and when to stop.
pub(super) const RUN: &[KeySpec] = &[
    // [run]
    KeySpec {
        key: "run.tau_end",
        value: Value::Quantity(Dimension::Tau),
        symbol: "τ end",
        unit: "τ",
        meaning: "end of the run in tau = p*t",
        written: "bare: tau, the name says so; or \"20 s\"",
        doc: "End of a batch run, in (0, 1e9]. The live view runs on until paused. Default 800.",
        param: Some(Param::TauEnd),
        slot: at(Group::Solver, 7),
        ..B
    },
    KeySpec {
        key: "run.t_end",
        value: Value::Quantity(Dimension::Seconds),
        symbol: "t end",
        unit: "s",
        meaning: "end of the run",
        written: "s, or \"500 ms\"",
        doc: "End of a batch run in seconds (instead of τ end). A record run lasts the record plus the tail unless this is set.",
        slot: at(Group::Solver, 8),
        ..B
    },
    KeySpec {
        key: "run.tail_s",
        value: Value::Quantity(Dimension::Seconds),
        symbol: "tail",
        unit: "s",
        meaning: "time after a record's end to wait for rest or overturning",
        written: "s",
        doc: "A record run goes on after the record until the block is at rest, at most this long. Default 30 s.",
        range: Some(Range {
            ok: tail,
            allowed: "in [0, 1e6] (seconds)",
        }),
        applies: RECORD,
        slot: at(Group::Solver, 9),
        ..B
    },
    KeySpec {
        key: "run.method",
        value: Value::Choice(&["dop853", "dopri5", "ralston", "taylor"]),
        symbol: "method",
        meaning: "integration method",
        written: "\"dop853\", \"dopri5\", \"ralston\" or \"taylor\" (default: by rtol)",
        doc: "taylor (default at rtol ≤ 1e-6: high-order series, fastest at tight tolerances), dop853 (default at looser rtol), dopri5, or ralston (the paper's fixed-step RK2).",
        slot: at(Group::Solver, 0),
        ..B
    },
    KeySpec {
        key: "run.rtol",
        symbol: "rtol",
        meaning: "relative tolerance",
        written: "dimensionless",
        doc: "Relative tolerance, in (0, 1). Default 1e-10.",
        param: Some(Param::Rtol),
        range: Some(Range {
            ok: rtol,
            allowed: "in [1e-16, 1) (below 1e-16, less than double precision's rounding)",
        }),
        slot: at(Group::Solver, 1),
        ..B
    },
    KeySpec {
        key: "run.atol",
        symbol: "atol",
        meaning: "absolute tolerance",
        written: "dimensionless",
        doc: "Absolute tolerance, in (0, 1). Default 1e-12.",
        param: Some(Param::Atol),
        range: Some(Range {
            ok: atol,
            allowed: "in [1e-20, 1) (below 1e-20 the step size underflows near rest)",
        }),
        slot: at(Group::Solver, 2),
        ..B
    },
    KeySpec {
        key: "run.step",
        value: Value::Quantity(Dimension::Tau),
        symbol: "step",
        unit: "τ",
        meaning: "fixed step of ralston",
        written: "\"1 ms\"",
        doc: "Fixed step of ralston, in (0, 1). Default 0.004 (the paper's).",
        param: Some(Param::Step),
        range: Some(Range {
            ok: open_unit,
            allowed: "in (0, 1)",
        }),
        slot: at(Group::Solver, 3),
        ..B
    },
    KeySpec {
        key: "run.output_dt",
        value: Value::Quantity(Dimension::Tau),
        symbol: "output dt",
        unit: "τ",
        meaning: "spacing of the time history",
        written: "\"10 ms\" (0 keeps none)",
        doc: "History spacing of a batch run; 0 writes none. Default 0.02.",
        param: Some(Param::OutputDt),
        range: Some(Range {
            ok: spacing,
            allowed: ">= 0 (0 writes no history)",
        }),
        slot: at(Group::Solver, 10),
        ..B
    },
    KeySpec {
        key: "run.tumble_theta",
        value: Value::Quantity(Dimension::Rotation),
        symbol: "Θ tumble",
        unit: "ψ",
        meaning: "rotation at which the block has tumbled",
        written: "\"0.3 rad\", \"20 deg\"",
        doc: "|Θ| at which the block has tumbled, in (0, π/(2ψ)]. Default 1.",
        param: Some(Param::TumbleTheta),
        slot: at(Group::Solver, 4),
        ..B
    },
    KeySpec {
        key: "run.flight",
        value: Value::Choice(&["stop", "ignore"]),
        symbol: "flight",
        meaning: "what a vanishing normal force does",
        written: "\"stop\" or \"ignore\"",
        doc: "stop: a vanishing normal force ends the run (default); ignore: integrate on, as the paper did.",
        slot: at(Group::Solver, 5),
        ..B
    },
    KeySpec {
        key: "run.zeno_eps",
        symbol: "zeno ε",
        unit: "ψ p",
        meaning: "impact accumulation threshold on |Theta'|",
        written: "normalised, in [0, 1)",
        doc: "Impact accumulation threshold on |Θ'|, in [0, 1). Default 1e-5.",
        param: Some(Param::ZenoEps),
        range: Some(Range {
            ok: zeno,
            allowed: "in [0, 1)",
        }),
        slot: at(Group::Solver, 6),
        ..B
    },
    KeySpec {
        key: "run.max_steps",
        value: Value::Count,
        symbol: "max steps",
        meaning: "most integration steps",
        written: "an integer",
        doc: "Most steps in one run. Default 1e9.",
        slot: at(Group::Solver, 11),
        ..B
    },
    KeySpec {
        key: "run.max_events",
        value: Value::Count,
        symbol: "max events",
        meaning: "most events",
        written: "an integer",
        doc: "Most events in one run. Default 1e8.",
        slot: at(Group::Solver, 12),
        ..B
    },
];

/// The `[analysis]` keys: what a batch run adds.
pub(super) const ANALYSIS: &[KeySpec] = &[
    // [analysis]
    KeySpec {
        key: "analysis.lyapunov",
        value: Value::Flag,
        meaning: "add Lyapunov exponents to the summary",
        written: "true or false",
        doc: "Add the Lyapunov exponents to summary.json. Default false.",
        ..B
    },
    KeySpec {
        key: "analysis.lyapunov_method",
        value: Value::Choice(&["tangent", "benettin", "both"]),
        meaning: "how the Lyapunov exponents are computed",
        written: "\"tangent\", \"benettin\" or \"both\"",
        doc: "tangent: tangent dynamics with saltation matrices, the whole spectrum (the default for a [block] and a [frame]: it needs no separation parameter); benettin: two trajectories on the stroboscopic map, the largest exponent (the default, and the only method, for a [[stack]], whose tangent equations are not written); both: both on one trajectory, with their paired difference.",
        ..B
    },
    KeySpec {
        key: "analysis.spectrum",
        value: Value::Flag,
        meaning: "add the spectrum of Theta(tau) to the summary",
        written: "true or false",
        doc: "Add the amplitude spectrum of Θ(τ) to summary.json. Default false.",
        ..B
    },
    KeySpec {
        key: "analysis.spectrum_window",
        value: Value::Choice(&["paper", "all"]),
        meaning: "the part of the run the spectrum is taken over",
        written: "\"paper\" or \"all\"",
        doc: "all: the whole history (default); paper: the paper's samples 3000–7095 at Δτ = 0.004 (τ 12–28.384).",
        ..B
    },
];
