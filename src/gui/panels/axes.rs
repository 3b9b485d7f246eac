//! Readable plot axes at any zoom: numbered ticks on both axes, spaced
//! 1–2–5 × 10ᵏ apart, and tick numbers with as many decimals as the
//! spacing needs and no more.
//!
//! Why not egui_plot's default: its log-10 grid jumps tenfold between
//! levels, so an axis spanning, say, −0.4 … 0.9 on 230 points gets lines
//! every 0.1 (too close to number) and every 1 (only "0" visible): a
//! plot with a single numbered tick, which a projector audience cannot
//! read. A 1–2–5 ladder always leaves a level whose numbered ticks are
//! between [`MIN_LABEL_GAP`] and 2.5× that apart.

use std::ops::RangeInclusive;

use egui_plot::{AxisHints, GridInput, GridMark, Plot};

/// Smallest distance between numbered ticks, points, per axis: x numbers
/// are wide ("−0.125"), so they need more room than y numbers (one line
/// high). Both are above egui_plot's own label thresholds (60 and 20
/// points), below which it fades numbers out.
pub(crate) const MIN_LABEL_GAP: [f64; 2] = [72.0, 34.0];

/// Smallest distance between numbered ticks that an axis too short for
/// two ticks [`MIN_LABEL_GAP`] apart may fall back to, points per axis: an
/// x number ("−0.05") is about 32 points wide, a y number 16 high (egui_plot
/// still leaves out a number wider than its gap). A short
/// axis (a plot squeezed by a large presentation scale) then still shows
/// two numbers rather than one.
pub(crate) const FLOOR_LABEL_GAP: [f64; 2] = [36.0, 17.0];

/// egui_plot's smallest grid spacing (points), which it turns into
/// [`GridInput::base_step_size`]; set explicitly so the conversion from
/// plot units to points is known.
const GRID_MIN: f32 = 8.0;

/// The smallest 1, 2 or 5 × 10ᵏ that is ≥ `raw` (> 0).
pub(crate) fn nice_step(raw: f64) -> f64 {
    if !(raw.is_finite() && raw > 0.0) {
        return 1.0;
    }
    let k = raw.log10().floor();
    let base = 10f64.powf(k);
    for m in [1.0, 2.0, 5.0, 10.0] {
        // A hair of slack so 0.2 (not exactly representable) is 2 × 0.1.
        if m * base >= raw * (1.0 - 1e-9) {
            return m * base;
        }
    }
    10.0 * base
}

/// Grid marks for one axis: numbered ticks `major` apart and thin lines a
/// fifth (or half, for a 2 step) of that. `points_per_unit` is the axis's
/// scale, `min_gap` the smallest gap between numbered ticks in points, and
/// `floor_gap` the smaller gap allowed where `min_gap` leaves fewer than two
/// numbered ticks on the axis.
pub fn marks(bounds: (f64, f64), points_per_unit: f64, min_gap: f64, floor_gap: f64) -> Vec<GridMark> {
    let (lo, hi) = (bounds.0.min(bounds.1), bounds.0.max(bounds.1));
    if !(lo.is_finite() && hi.is_finite() && points_per_unit.is_finite() && points_per_unit > 0.0) {
        return Vec::new();
    }
    let mut major = nice_step(min_gap / points_per_unit);
    // Step down the ladder while fewer than two numbered ticks fall inside
    // the axis, as long as neighbours stay `floor_gap` apart.
    let majors_inside = |step: f64| (hi / step).floor() - (lo / step).ceil() + 1.0;
    while majors_inside(major) < 2.0 {
        let smaller = step_below(major);
        if smaller * points_per_unit < floor_gap.min(min_gap) {
            break;
        }
        major = smaller;
    }
    let mantissa = major / 10f64.powf(major.log10().floor());
    let mut minor = if (mantissa - 2.0).abs() < 1e-6 {
        major / 2.0
    } else {
        major / 5.0
    };
    // Thin lines stay closer than any numbered pair, so egui_plot (told
    // by [`readable`] to number marks from `floor_gap` apart) numbers the
    // major marks only.
    while minor * points_per_unit >= 0.95 * floor_gap.min(min_gap) {
        minor = step_below(minor);
    }
    let mut out = Vec::new();
    // Index from the step, not by accumulating, so 0 is exactly 0.
    // Only marks inside the axis: a number just outside it is drawn
    // half-clipped at the plot's edge.
    let first = (lo / minor).ceil() as i64;
    let last = (hi / minor).floor() as i64;
    if last - first > 2000 {
        return out;
    }
    let per_major = (major / minor).round() as i64;
    for i in first..=last {
        let value = i as f64 * minor;
        let step_size = if i.rem_euclid(per_major) == 0 { major } else { minor };
        out.push(GridMark { value, step_size });
    }
    out
}

/// Bounds for data spanning `lo` … `hi` on an axis `length` points long,
/// widened to whole numbered steps and then by `pad` of the span each side:
/// so the axis shows at least two numbered ticks (its outermost steps) at
/// least `floor_gap` apart, however short the axis or narrow the data (a
/// period-one orbit's Poincaré points all but coincide), where the axis is
/// at least 2.2 floor gaps long (else the data, padded). The step is the
/// smallest 1–2–5 step that keeps numbers `floor_gap` apart, at least
/// what `min_gap` asks where the axis is long enough.
pub(crate) fn nice_bounds(lo: f64, hi: f64, length: f64, min_gap: f64, floor_gap: f64, pad: f64) -> (f64, f64) {
    let (lo, hi) = (lo.min(hi), lo.max(hi));
    if !(lo.is_finite() && hi.is_finite() && length.is_finite() && length > 0.0) {
        return (lo, hi);
    }
    let span = (hi - lo).max(1e-12 * lo.abs().max(1.0));
    let mut step = nice_step(span * min_gap.min(floor_gap) / length);
    for _ in 0..64 {
        let a = (lo / step).floor() * step;
        let b = (hi / step).ceil() * step;
        let b = if b - a < step { a + step } else { b };
        let width = (b - a) * (1.0 + 2.0 * pad);
        // Numbers `step` apart are this many points apart:
        let gap = step * length / width;
        if gap >= floor_gap {
            return (a - pad * (b - a), b + pad * (b - a));
        }
        step = nice_step(step * 1.01);
    }
    // An axis shorter than two floor gaps: the data, padded.
    (lo - pad * span, hi + pad * span)
}

/// The next 1–2–5 step below `step` (1 → 0.5, 5 → 2, 2 → 1).
fn step_below(step: f64) -> f64 {
    let base = 10f64.powf(step.log10().floor());
    let mantissa = step / base;
    if mantissa > 4.0 {
        2.0 * base
    } else if mantissa > 1.5 {
        base
    } else {
        0.5 * base
    }
}

/// A tick's number: as many decimals as its step needs (a 0.05 step gives
/// two, a 0.2 step one, a 5 step none), in scientific notation for very
/// large or very small steps so a deep zoom still reads.
pub(crate) fn format_tick(mark: GridMark, _range: &RangeInclusive<f64>) -> String {
    let step = mark.step_size.abs();
    let v = if mark.value.abs() < step * 1e-9 {
        0.0
    } else {
        mark.value
    };
    if !(step.is_finite() && step > 0.0) {
        return format!("{v}");
    }
    if !(1e-4..1e5).contains(&step) {
        if v == 0.0 {
            // "0", not "0e0".
            return "0".to_owned();
        }
        // Significant digits enough to tell neighbouring ticks apart.
        let digits = ((v.abs().max(step)).log10().floor() - step.log10().floor()).clamp(0.0, 12.0) as usize;
        return format!("{v:.digits$e}");
    }
    let decimals = (-step.log10() - 1e-9).ceil().clamp(0.0, 12.0) as usize;
    format!("{v:.decimals$}")
}

/// `plot` with readable axes: 1–2–5 ticks numbered on both axes at any
/// zoom ([`marks`]) and their numbers ([`format_tick`]), at the gaps
/// [`MIN_LABEL_GAP`] gives for egui's default font. [`titled`] then fits the
/// gaps and the numbers to the font the style gives plot numbers.
pub fn readable<'a>(plot: Plot<'a>) -> Plot<'a> {
    with_gaps(plot, 1.0)
}

/// The font size [`MIN_LABEL_GAP`] and [`FLOOR_LABEL_GAP`] were chosen
/// for, points: egui's default body text.
const GAP_FONT_PT: f32 = 12.5;

/// The text style plot numbers are drawn in ([`crate::gui::app`] sets its
/// size: at least 14 px, 20 px in the lecture presentation).
pub(crate) const PLOT_NUMBERS: &str = "plot numbers";

/// The font of plot numbers in `style`: [`PLOT_NUMBERS`], else the body font.
pub(crate) fn number_font(style: &egui::Style) -> egui::FontId {
    let name = egui::TextStyle::Name(PLOT_NUMBERS.into());
    style
        .text_styles
        .get(&name)
        .cloned()
        .unwrap_or_else(|| egui::TextStyle::Body.resolve(style))
}

/// The smallest gaps between numbered ticks for plot numbers in `style`'s
/// [`number_font`], points per axis: ([`MIN_LABEL_GAP`], [`FLOOR_LABEL_GAP`])
/// grown with the font.
pub(crate) fn gaps(style: &egui::Style) -> ([f64; 2], [f64; 2]) {
    let grow = f64::from((number_font(style).size / GAP_FONT_PT).max(1.0));
    (
        [grow * MIN_LABEL_GAP[0], grow * MIN_LABEL_GAP[1]],
        [grow * FLOOR_LABEL_GAP[0], grow * FLOOR_LABEL_GAP[1]],
    )
}

/// `plot`'s grid and numbers with every gap [`MIN_LABEL_GAP`],
/// [`FLOOR_LABEL_GAP`] multiplied by `grow` (numbers larger than the font the
/// gaps were chosen for need as much more room).
fn with_gaps<'a>(plot: Plot<'a>, grow: f64) -> Plot<'a> {
    let spacer = move |axis: usize| {
        move |input: GridInput| {
            // base_step_size is the plot-unit length of GRID_MIN points.
            let ppu = f64::from(GRID_MIN) / input.base_step_size;
            marks(
                input.bounds,
                ppu,
                grow * MIN_LABEL_GAP[axis],
                grow * FLOOR_LABEL_GAP[axis],
            )
        }
    };
    plot.grid_spacing(egui::Rangef::new(GRID_MIN, 300.0))
        .x_grid_spacer(spacer(0))
        .y_grid_spacer(spacer(1))
        .custom_x_axes(vec![hints(AxisHints::new_x(), 0, grow, None)])
        .custom_y_axes(vec![hints(AxisHints::new_y(), 1, grow, None)])
}

/// Axis `axis`'s hints: [`format_tick`] numbers, in `font` (egui_plot's
/// body font if `None`). egui_plot hides numbers closer than its label
/// spacing (60 points on x, 20 on y by default) and fades them up to a
/// larger one; [`marks`] already keeps numbered marks at least the floor
/// apart and thin ones closer, so number exactly the marks at or beyond the
/// floor, at full strength.
fn hints<'a>(hints: AxisHints<'a>, axis: usize, grow: f64, font: Option<egui::FontId>) -> AxisHints<'a> {
    let floor = (grow * FLOOR_LABEL_GAP[axis]) as f32;
    let hints = hints
        .formatter(format_tick)
        .label_spacing(egui::Rangef::new(floor * 0.96, floor * 0.97));
    match font {
        Some(f) => hints.tick_label_font(f),
        None => hints,
    }
}

/// `plot` titled `x` and `y`, each shortened to fit the length of its axis
/// in `ui`'s remaining room ([`fit_title`]): a title longer than its axis
/// is painted past the plot, over whatever is beside it. Its numbers are in
/// the style's [`number_font`], with gaps grown to match.
pub fn titled<'a>(plot: Plot<'a>, ui: &egui::Ui, x: &str, y: &str) -> Plot<'a> {
    let font = number_font(ui.style());
    let grow = f64::from((font.size / GAP_FONT_PT).max(1.0));
    let room = ui.available_size() - axis_room(ui);
    // The last number on the x axis is centred on the plot's right edge:
    // leave room for its right half, or the panel's edge cuts it.
    let width = (ui.available_size_before_wrap().x - 1.8 * font.size).max(64.0);
    let plot = with_gaps(plot, grow).width(width);
    plot.custom_x_axes(vec![
        hints(AxisHints::new_x(), 0, grow, Some(font.clone())).label(fit_title(ui, x, room.x)),
    ])
    .custom_y_axes(vec![
        hints(AxisHints::new_y(), 1, grow, Some(font)).label(fit_title(ui, y, room.y)),
    ])
}

/// Room the axes themselves take from a plot's rectangle, points: the
/// numbers and the title beside the y axis, and under the x axis (at egui's
/// default font, 56 × 44, grown with the fonts in use).
fn axis_room(ui: &egui::Ui) -> egui::Vec2 {
    let numbers = number_font(ui.style()).size;
    let title = egui::TextStyle::Body.resolve(ui.style()).size;
    egui::vec2(3.0 * numbers + 1.5 * title, 1.6 * numbers + 1.9 * title)
}

/// Where a plot's data area (inside its axes) was drawn, and in which
/// pass: what the layout tests read back.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct PlotRecord {
    /// The plot's name.
    pub name: &'static str,
    /// Its data area, points.
    pub frame: egui::Rect,
    /// egui's pass it was drawn in.
    pub pass: u64,
}

fn records_id() -> egui::Id {
    egui::Id::unique("rocking plot records")
}

/// Notes where plot `name` put its data area this pass (`transform` is
/// what egui_plot returned).
pub fn record(ui: &egui::Ui, name: &'static str, transform: &egui_plot::PlotTransform) {
    let pass = ui.ctx().cumulative_pass_nr();
    let rec = PlotRecord {
        name,
        frame: *transform.frame(),
        pass,
    };
    ui.ctx().data_mut(|d| {
        let v: &mut Vec<PlotRecord> = d.get_temp_mut_or_default(records_id());
        v.retain(|r| r.name != name && r.pass + 1 >= pass);
        v.push(rec);
    });
}

/// The plots drawn in the latest pass that drew any, with their data areas.
pub fn recorded(ctx: &egui::Context) -> Vec<PlotRecord> {
    let v: Vec<PlotRecord> = ctx.data(|d| d.get_temp(records_id()).unwrap_or_default());
    let last = v.iter().map(|r| r.pass).max().unwrap_or(0);
    v.into_iter().filter(|r| r.pass == last).collect()
}

/// The longest form of `title` that fits `length` points in the body font
/// (egui_plot's for axis titles): the whole title, then without its
/// " at …" qualifier ("Θ' = dΘ/dτ at τ_k = 2πk/Ω_h" → "Θ' = dΘ/dτ"), then
/// without the definition after " = " ("Θ'"), then cut with "…".
fn fit_title(ui: &egui::Ui, title: &str, length: f32) -> String {
    let font = egui::TextStyle::Body.resolve(ui.style());
    let fits = |text: &str| {
        ui.painter()
            .layout_no_wrap(text.to_owned(), font.clone(), egui::Color32::WHITE)
            .size()
            .x
            <= length
    };
    let mut forms = title_forms(title);
    if let Some(i) = forms.iter().position(|f| fits(f)) {
        return forms.swap_remove(i);
    }
    // The shortest form, cut a character at a time.
    let shortest = forms.pop().unwrap_or_default();
    let chars: Vec<char> = shortest.chars().collect();
    for n in (1..chars.len()).rev() {
        let cut: String = chars[..n].iter().collect::<String>() + "…";
        if fits(&cut) {
            return cut;
        }
    }
    String::new()
}

/// The forms of an axis title from longest to shortest (see [`fit_title`]).
fn title_forms(title: &str) -> Vec<String> {
    let mut forms = vec![title.to_owned()];
    let mut current = title.to_owned();
    if let Some(i) = current.find(" at ") {
        current.truncate(i);
        forms.push(current.clone());
    }
    if let Some(i) = current.find(" = ") {
        // The definition is the word after " = "; what follows it stays.
        let rest = &current[i + 3..];
        let after = rest.find(' ').map_or("", |j| &rest[j..]);
        current = format!("{}{after}", &current[..i]);
        forms.push(current);
    }
    forms
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn nice_steps_climb_the_one_two_five_ladder() {
        assert_eq!(nice_step(0.7), 1.0);
        assert_eq!(nice_step(1.0), 1.0);
        assert_eq!(nice_step(1.3), 2.0);
        assert_eq!(nice_step(3.0), 5.0);
        assert_eq!(nice_step(6.0), 10.0);
        assert!((nice_step(0.013) - 0.02).abs() < 1e-15);
        assert!((nice_step(0.2) - 0.2).abs() < 1e-15);
        assert_eq!(nice_step(f64::NAN), 1.0);
    }

    /// The case the issue saw: Θ' over −0.4 … 0.9 on 230 points showed
    /// only "0". Now at least three numbered ticks, each at least the
    /// minimum gap apart.
    #[test]
    fn a_short_axis_gets_several_numbered_ticks() {
        let ppu = 230.0 / 1.3;
        let m = marks((-0.4, 0.9), ppu, MIN_LABEL_GAP[1], FLOOR_LABEL_GAP[1]);
        let major: Vec<_> = m.iter().filter(|g| g.step_size > 0.15).collect();
        assert!(major.len() >= 3, "{major:?}");
        assert!(major[0].step_size * ppu >= MIN_LABEL_GAP[1]);
        assert!(major.iter().any(|g| g.value == 0.0));
    }

    /// At any zoom, from 1e-9 to 1e9 wide, an axis of 300 points has
    /// between 2 and 10 numbered ticks, and their numbers differ.
    #[test]
    fn any_zoom_keeps_two_to_ten_distinct_numbers() {
        for e in -9..=9 {
            for centre in [0.0, 0.3, -123.456] {
                let width = 10f64.powi(e);
                let bounds = (centre - width / 2.0, centre + width / 2.0);
                let ppu = 300.0 / width;
                let m = marks(bounds, ppu, MIN_LABEL_GAP[0], FLOOR_LABEL_GAP[0]);
                let top = m.iter().map(|g| g.step_size).fold(0.0, f64::max);
                let labelled: Vec<_> = m
                    .iter()
                    .filter(|g| g.step_size == top && g.value >= bounds.0 && g.value <= bounds.1)
                    .map(|g| format_tick(*g, &(bounds.0..=bounds.1)))
                    .collect();
                assert!((2..=10).contains(&labelled.len()), "{width} at {centre}: {labelled:?}");
                let mut unique = labelled.clone();
                unique.dedup();
                assert_eq!(unique.len(), labelled.len(), "{width} at {centre}: {labelled:?}");
            }
        }
    }

    #[test]
    fn a_title_sheds_its_qualifier_then_its_definition() {
        assert_eq!(
            title_forms("Θ' = dΘ/dτ at τ_k = 2πk/Ω_h"),
            ["Θ' = dΘ/dτ at τ_k = 2πk/Ω_h", "Θ' = dΘ/dτ", "Θ'"]
        );
        assert_eq!(
            title_forms("Θ' = dΘ/dτ before impact"),
            ["Θ' = dΘ/dτ before impact", "Θ' before impact"]
        );
        assert_eq!(title_forms("log10 S/S_max"), ["log10 S/S_max"]);
    }

    /// A short axis (a plot squeezed at a large presentation scale: 45 to
    /// 130 points for −0.06 … 0.06) gets two numbers where the normal gap would
    /// leave one, and its thin lines are closer than the numbered ones.
    #[test]
    fn an_axis_too_short_for_the_normal_gap_still_gets_two_numbers() {
        for (axis, length) in [(1, 45.0), (1, 60.0), (0, 100.0), (0, 130.0)] {
            let bounds = (-0.06, 0.06);
            let ppu = length / 0.12;
            let m = marks(bounds, ppu, MIN_LABEL_GAP[axis], FLOOR_LABEL_GAP[axis]);
            let top = m.iter().map(|g| g.step_size).fold(0.0, f64::max);
            let numbered: Vec<_> = m.iter().filter(|g| g.step_size == top).collect();
            assert!(numbered.len() >= 2, "axis {axis}, {length} pt: {m:?}");
            assert!(top * ppu >= FLOOR_LABEL_GAP[axis]);
            let thin = m.iter().map(|g| g.step_size).fold(f64::INFINITY, f64::min);
            assert!(
                thin == top || thin * ppu < 0.96 * FLOOR_LABEL_GAP[axis],
                "axis {axis}: {m:?}"
            );
        }
    }

    /// Data that all but coincide (a period-one orbit's section points),
    /// on a short axis, at both fonts: the bounds leave two numbered ticks
    /// at least the floor gap apart, with the data inside.
    #[test]
    fn nice_bounds_keep_two_numbers_on_a_short_axis() {
        for (lo, hi) in [
            (-0.0041, 0.0093),
            (0.2, 0.2),
            (-0.4, 0.9),
            (1.001, 1.0012),
            (-123.4, 560.0),
        ] {
            for length in [60.0, 120.0, 160.0, 300.0] {
                for grow in [1.2, 1.6] {
                    let (min_gap, floor) = (grow * MIN_LABEL_GAP[0], grow * FLOOR_LABEL_GAP[0]);
                    if length < 2.2 * floor {
                        // Too short for two numbers a floor apart with the
                        // padding: the layout never makes a plot this small.
                        continue;
                    }
                    let (a, b) = nice_bounds(lo, hi, length, min_gap, floor, 0.04);
                    assert!(a <= lo && b >= hi, "{lo} {hi}: {a} {b}");
                    let m = marks((a, b), length / (b - a), min_gap, floor);
                    let top = m.iter().map(|g| g.step_size).fold(0.0, f64::max);
                    let numbered = m.iter().filter(|g| g.step_size == top).count();
                    assert!(numbered >= 2, "{lo} {hi} on {length}: {a} {b} {m:?}");
                    assert!(top * length / (b - a) >= floor * 0.999, "{lo} {hi} on {length}");
                }
            }
        }
    }

    #[test]
    fn tick_numbers_have_the_decimals_their_step_needs() {
        let t = |value, step_size| format_tick(GridMark { value, step_size }, &(0.0..=1.0));
        assert_eq!(t(0.05, 0.05), "0.05");
        assert_eq!(t(0.4, 0.2), "0.4");
        assert_eq!(t(10.0, 5.0), "10");
        assert_eq!(t(-1e-17, 0.1), "0.0");
        assert_eq!(t(2e-6, 1e-6), "2e-6");
        assert_eq!(t(3e6, 1e6), "3e6");
        assert_eq!(t(0.0, 2e-5), "0");
    }
}
