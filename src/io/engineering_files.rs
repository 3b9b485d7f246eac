//! The CSV files of the engineering analyses (docs/engineering.md):
//! `spectrum.csv` and `safe_windows.csv` of `rocking spectrum`,
//! `pulse_map.csv` (and its `safe_windows.csv`) of `rocking pulse-map`,
//! `runs.csv` and `fractions.csv` of `rocking fragility`. Every column
//! with a physical unit names it (`_m`, `_s`, `_g`, `_per_s`, `_rad`);
//! `θ/α` and scale factors are dimensionless. Empty cells mean "does not
//! exist" (no overturning, no fit), never a NaN.

use serde::{Deserialize, Serialize};

use super::csv::{Num, csv_row};

csv_row! {
    /// A row of `spectrum.csv`: one block of a rocking spectrum.
    #[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
    pub(crate) struct SpectrumRow {
        /// Slenderness ratio B/H.
        pub b_over_h: Num,
        /// Slenderness angle α = atan(B/H), rad.
        pub alpha_rad: Num,
        /// Width B, m.
        pub width_m: Num,
        /// Height H, m.
        pub height_m: Num,
        /// Half-diagonal R, m.
        pub r_m: Num,
        /// Frequency parameter p = √(3g/(4R)), 1/s.
        pub p_per_s: Num,
        /// Scale factor of the motion in this run.
        pub scale: Num,
        /// Peak ground acceleration of the scaled motion, g.
        pub pga_g: Num,
        /// How the run ended: rest, moving, overturned, flight.
        pub end: String,
        /// Peak |θ|/α (≥ the overturning angle, 1 by default, when overturned).
        pub peak_theta_over_alpha: Num,
        /// Time of overturning, s; empty unless overturned.
        pub t_overturn_s: Option<Num>,
        /// Time the block left the ground, s; empty unless flight.
        pub t_flight_s: Option<Num>,
        /// Smallest scale factor found to overturn the block (or make it fly,
        /// see `overturn_end`); empty if none up to the largest scale tried or
        /// if no search was asked for.
        pub overturn_scale: Option<Num>,
        /// PGA at that scale, g.
        pub overturn_pga_g: Option<Num>,
        /// What happened at that scale: overturned or flight.
        pub overturn_end: Option<String>,
        /// Safe windows found above it (listed in `safe_windows.csv`).
        pub safe_windows: Option<u32>,
    }
}

csv_row! {
    /// A row of a spectrum's `safe_windows.csv`: amplitudes above a block's
    /// first overturning scale at which it survives again.
    #[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
    pub(crate) struct SpectrumWindowRow {
        /// B/H of the block.
        pub b_over_h: Num,
        /// R of the block, m.
        pub r_m: Num,
        /// Lowest safe scale of the window.
        pub from_scale: Num,
        /// First failing scale above it; empty: safe up to the largest scale
        /// tried.
        pub to_scale: Option<Num>,
        /// `from_scale` as a PGA, g.
        pub from_pga_g: Num,
        /// `to_scale` as a PGA, g.
        pub to_pga_g: Option<Num>,
    }
}

csv_row! {
    /// A row of `pulse_map.csv`: one (pulse, B/H, ω_p/p).
    #[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
    pub(crate) struct PulseMapRow {
        /// Pulse: one-sine, one-cosine, type-c1, ….
        pub pulse: String,
        /// B/H.
        pub b_over_h: Num,
        /// α, rad.
        pub alpha_rad: Num,
        /// ω_p/p.
        pub omega_ratio: Num,
        /// Smallest overturning amplitude a_p/(g tan α); empty if none up to
        /// the largest tried.
        pub min_overturn_amplitude: Option<Num>,
        /// The same as a_p/g.
        pub min_overturn_ap_g: Option<Num>,
        /// What happened there: overturned or flight.
        pub overturn_end: Option<String>,
        /// Safe windows above it (in `safe_windows.csv`).
        pub safe_windows: u32,
    }
}

csv_row! {
    /// A row of a pulse map's `safe_windows.csv`.
    #[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
    pub(crate) struct PulseWindowRow {
        /// Pulse.
        pub pulse: String,
        /// B/H.
        pub b_over_h: Num,
        /// ω_p/p.
        pub omega_ratio: Num,
        /// Lowest safe a_p/(g tan α) of the window.
        pub from_amplitude: Num,
        /// First failing a_p/(g tan α) above it; empty: safe up to the largest
        /// tried.
        pub to_amplitude: Option<Num>,
    }
}

csv_row! {
    /// A row of `runs.csv`: one run of a fragility study.
    #[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
    pub(crate) struct FragilityRunRow {
        /// Run number (block outer, level, record inner), from 0.
        pub run: u64,
        /// Block number, from 0.
        pub block: u64,
        /// Width B, m.
        pub width_m: Num,
        /// Height H, m.
        pub height_m: Num,
        /// Record name (file stem).
        pub record: String,
        /// Intensity measure: pga_g or pgv_m_s.
        pub im: String,
        /// Intensity level, in the unit `im` names.
        pub level: Num,
        /// Scale factor of the record.
        pub scale: Num,
        /// rest, moving, overturned or flight.
        pub end: String,
        /// Peak |θ|/α.
        pub peak_theta_over_alpha: Num,
        /// Time of overturning, s.
        pub t_overturn_s: Option<Num>,
        /// Time of flight, s.
        pub t_flight_s: Option<Num>,
        /// Peak horizontal acceleration of the motion as run (scaled), g.
        pub pga_h_g: Num,
        /// Peak vertical acceleration as run (scaled by the same factor), g;
        /// empty when the run had no vertical component.
        pub pga_v_g: Option<Num>,
    }
}

csv_row! {
    /// A row of `incremental.csv`: one record's run at one level, for one
    /// block (block outer, record, level inner: each record's incremental
    /// curve in order).
    #[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
    pub(crate) struct IncrementalRow {
        /// Block number, from 0.
        pub block: u64,
        /// Width B, m.
        pub width_m: Num,
        /// Height H, m.
        pub height_m: Num,
        /// Record name (file stem).
        pub record: String,
        /// Intensity measure (the column name of `runs.csv`'s `im`).
        pub im: String,
        /// Intensity level.
        pub level: Num,
        /// Peak |θ|/α.
        pub peak_theta_over_alpha: Num,
        /// rest, moving, overturned or flight.
        pub end: String,
    }
}

csv_row! {
    /// A row of `fractions.csv`: one block at one level.
    #[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
    pub(crate) struct FractionRow {
        /// Block number.
        pub block: u64,
        /// Width B, m.
        pub width_m: Num,
        /// Height H, m.
        pub height_m: Num,
        /// Intensity measure: pga_g or pgv_m_s.
        pub im: String,
        /// Intensity level.
        pub level: Num,
        /// Runs (one per record).
        pub runs: u64,
        /// Runs that overturned.
        pub overturned: u64,
        /// Runs that ended in flight (left out of the fractions).
        pub flight: u64,
        /// Runs that overturned or reached the θ/α threshold.
        pub exceeded: u64,
        /// overturned / (runs − flight); empty if every run flew.
        pub fraction_overturned: Option<Num>,
        /// exceeded / (runs − flight).
        pub fraction_exceeded: Option<Num>,
        /// The fitted overturning probability at this level; empty without a fit.
        pub fit_overturned: Option<Num>,
        /// Lower end of its 95 % band.
        pub fit_overturned_lo: Option<Num>,
        /// Upper end.
        pub fit_overturned_hi: Option<Num>,
        /// The fitted exceedance probability.
        pub fit_exceeded: Option<Num>,
        /// Lower end of its 95 % band.
        pub fit_exceeded_lo: Option<Num>,
        /// Upper end.
        pub fit_exceeded_hi: Option<Num>,
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::io::csv::{header, header_of};

    fn n(x: f64) -> Num {
        Num(x)
    }

    #[test]
    fn headers_are_the_row_fields() {
        let s = SpectrumRow {
            b_over_h: n(0.2),
            alpha_rad: n(0.2),
            width_m: n(1.0),
            height_m: n(1.0),
            r_m: n(1.0),
            p_per_s: n(1.0),
            scale: n(1.0),
            pga_g: n(1.0),
            end: "rest".into(),
            peak_theta_over_alpha: n(0.0),
            t_overturn_s: None,
            t_flight_s: None,
            overturn_scale: None,
            overturn_pga_g: None,
            overturn_end: None,
            safe_windows: None,
        };
        assert_eq!(header_of(&s), header::<SpectrumRow>());
        let w = SpectrumWindowRow {
            b_over_h: n(0.2),
            r_m: n(1.0),
            from_scale: n(1.0),
            to_scale: None,
            from_pga_g: n(1.0),
            to_pga_g: None,
        };
        assert_eq!(header_of(&w), header::<SpectrumWindowRow>());
        let p = PulseMapRow {
            pulse: "one-sine".into(),
            b_over_h: n(0.2),
            alpha_rad: n(0.2),
            omega_ratio: n(1.0),
            min_overturn_amplitude: None,
            min_overturn_ap_g: None,
            overturn_end: None,
            safe_windows: 0,
        };
        assert_eq!(header_of(&p), header::<PulseMapRow>());
        let pw = PulseWindowRow {
            pulse: "one-sine".into(),
            b_over_h: n(0.2),
            omega_ratio: n(1.0),
            from_amplitude: n(1.0),
            to_amplitude: None,
        };
        assert_eq!(header_of(&pw), header::<PulseWindowRow>());
        let r = FragilityRunRow {
            run: 0,
            block: 0,
            width_m: n(1.0),
            height_m: n(1.0),
            record: "a".into(),
            im: "pga_g".into(),
            level: n(0.1),
            scale: n(1.0),
            end: "rest".into(),
            peak_theta_over_alpha: n(0.0),
            t_overturn_s: None,
            t_flight_s: None,
            pga_h_g: n(0.1),
            pga_v_g: None,
        };
        assert_eq!(header_of(&r), header::<FragilityRunRow>());
        let f = FractionRow {
            block: 0,
            width_m: n(1.0),
            height_m: n(1.0),
            im: "pga_g".into(),
            level: n(0.1),
            runs: 1,
            overturned: 0,
            flight: 0,
            exceeded: 0,
            fraction_overturned: None,
            fraction_exceeded: None,
            fit_overturned: None,
            fit_overturned_lo: None,
            fit_overturned_hi: None,
            fit_exceeded: None,
            fit_exceeded_lo: None,
            fit_exceeded_hi: None,
        };
        assert_eq!(header_of(&f), header::<FractionRow>());
    }
}
