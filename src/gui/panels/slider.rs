//! A parameter slider that moves its value by how far the pointer moved,
//! not to where the pointer is.
//!
//! egui's own slider sets the value under the pointer, so pressing on it
//! jumps the value to that pixel, and its travel ends where the rail
//! ends. Here a drag adds `Δx × rate` to the value it started from (one
//! [`SliderRange::step`] per point, or a [`FINE_DRAG`]-th of it once Shift
//! has been held during the drag), so a press that does not move leaves
//! the value exactly as it was, and the value keeps moving while the
//! pointer goes on past either end of the rail: only the slider's range
//! limits it. The arrow keys step the focused slider by the same amounts.
//!
//! The widget knows nothing of the scene: it takes a value and returns
//! the new one; the parameter panel validates and applies it.

/// The range of a key's slider: from `min` to `max` in the key's unit,
/// on a logarithmic scale if `log`, and how far a point of drag or an
/// arrow press moves it (`step`).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SliderRange {
    /// Left end.
    pub min: f64,
    /// Right end.
    pub max: f64,
    /// Logarithmic (for scales: sizes and frequencies).
    pub log: bool,
    /// What one point of a plain drag, or one arrow press, adds: in the
    /// key's unit, or for a logarithmic slider the fraction of the value
    /// (0.05: 5 %). A round number near the range over the 54 points the
    /// handle travels, so that the handle nearly follows the pointer and
    /// the tooltip can say the step.
    pub step: f64,
}

/// How much finer a Shift-drag (and a Shift-arrow) moves a slider than a
/// plain one: on A_v a point is 0.1 ψg, wider than the period-4 window
/// of the paper's Fig. 4 (2.267–2.315 in this model); a twentieth of it,
/// 0.005, puts about ten points in that window and one value (2.32)
/// in the period-8 window (2.316–2.323), while the whole cascade from
/// A_v = 1.6 still fits in one drag of about 150 points, on the screen
/// at every presentation scale.
pub(crate) const FINE_DRAG: f64 = 20.0;

impl SliderRange {
    /// The step of a plain or a fine move ([`SliderRange::step`], or a
    /// [`FINE_DRAG`]-th of it).
    pub(crate) fn step_of(&self, fine: bool) -> f64 {
        if fine { self.step / FINE_DRAG } else { self.step }
    }

    /// `value` moved by `points` points of drag (or arrow presses; may be
    /// fractional or negative), plain or `fine`, and kept on the range:
    /// the range widened to take `start`, the value the move began from,
    /// so that a value typed beyond the rail stays where it is until the
    /// move heads back.
    pub fn moved(&self, value: f64, points: f64, fine: bool, start: f64) -> f64 {
        let step = self.step_of(fine);
        let v = if self.log && value > 0.0 {
            value * (1.0 + step).powf(points)
        } else {
            value + points * step
        };
        v.clamp(self.min.min(start), self.max.max(start))
    }

    /// Where `value` sits along the rail, from 0 (left end) to 1 (right
    /// end), on the rail's own scale; a value beyond the range sits at the
    /// nearer end.
    pub fn place(&self, value: f64) -> f64 {
        let f = if self.log && self.min > 0.0 && value > 0.0 {
            (value / self.min).ln() / (self.max / self.min).ln()
        } else {
            (value - self.min) / (self.max - self.min)
        };
        if f.is_nan() { 0.0 } else { f.clamp(0.0, 1.0) }
    }

    /// A step as the tooltip says it: `0.1 ψg`, or `5 %` on a
    /// logarithmic slider.
    pub(crate) fn step_text(&self, fine: bool, unit: &str) -> String {
        let step = self.step_of(fine);
        if self.log {
            format!("{} %", slider_text(100.0 * step))
        } else if unit.is_empty() {
            slider_text(step)
        } else {
            format!("{} {unit}", slider_text(step))
        }
    }
}

/// A slider's value as the text to apply: four significant digits, which
/// is finer than a pixel of any slider and keeps the scene's numbers
/// readable.
pub fn slider_text(v: f64) -> String {
    if v == 0.0 || !v.is_finite() {
        return "0".to_string();
    }
    let digits = (3 - v.abs().log10().floor() as i32).clamp(0, 15) as usize;
    let text = format!("{v:.digits$}");
    if text.contains('.') {
        text.trim_end_matches('0').trim_end_matches('.').to_string()
    } else {
        text
    }
}

/// A drag in progress: the unrounded value it has reached, the value it
/// began from, where the pointer was last frame (points), and whether
/// Shift has been held at any time since the press (a fine drag stays
/// fine until released).
#[derive(Clone, Copy, Debug)]
struct Drag {
    value: f64,
    start: f64,
    last_x: f32,
    fine: bool,
}

/// Where the slider that has the keyboard leaves its id, for
/// [`has_keyboard`].
fn keyboard_id() -> egui::Id {
    egui::Id::unique("parameter slider with the keyboard")
}

/// Whether one of these sliders has the keyboard focus. It takes only the
/// arrow keys, so the app's one-key shortcuts (Space, R, S) stay on while
/// it has the focus a click gave it.
pub(crate) fn has_keyboard(ctx: &egui::Context) -> bool {
    let focused = ctx.memory(|m| m.focused());
    focused.is_some() && ctx.data(|d| d.get_temp::<egui::Id>(keyboard_id())) == focused
}

/// How a slider is drawn and named.
pub struct Slider<'a> {
    /// The value shown now (the scene's).
    pub value: f64,
    /// Rail ends, scale and steps.
    pub range: SliderRange,
    /// Accessible name (e.g. `A_v slider`).
    pub name: &'a str,
}

impl Slider<'_> {
    /// Draws the slider and handles its drag and keys. Returns the
    /// response and the value asked for this frame, if it differs from
    /// [`Slider::value`].
    pub fn show(self, ui: &mut egui::Ui) -> (egui::Response, Option<f64>) {
        let height = ui
            .text_style_height(&egui::TextStyle::Body)
            .max(ui.spacing().interact_size.y);
        let size = egui::vec2(ui.spacing().slider_width, height);
        let (rect, r) = ui.allocate_exact_size(size, egui::Sense::drag());
        let range = self.range;
        let mut wanted = None;

        // The drag: relative to where it started, never to the pointer.
        let state_id = r.id.with("relative drag");
        let down = r.is_pointer_button_down_on();
        let drag: Option<Drag> = ui.data(|d| d.get_temp(state_id));
        match (down, drag, r.interact_pointer_pos()) {
            (true, previous, Some(pointer)) => {
                let shift = ui.input(|i| i.modifiers.shift);
                let mut d = previous.unwrap_or_else(|| {
                    // Pressing gives the slider the keyboard, for the arrows.
                    r.request_focus();
                    Drag {
                        value: self.value,
                        start: self.value,
                        last_x: ui.input(|i| i.pointer.press_origin()).map_or(pointer.x, |p| p.x),
                        fine: false,
                    }
                });
                d.fine |= shift;
                let dx = f64::from(pointer.x - d.last_x);
                d.value = range.moved(d.value, dx, d.fine, d.start);
                d.last_x = pointer.x;
                ui.data_mut(|data| data.insert_temp(state_id, d));
                if d.value != self.value {
                    wanted = Some(d.value);
                }
            }
            (true, _, None) | (false, Some(_), _) => ui.data_mut(|data| data.remove::<Drag>(state_id)),
            (false, None, _) => {}
        }

        if ui.memory(|m| m.has_focus(r.id)) {
            ui.data_mut(|data| data.insert_temp(keyboard_id(), r.id));
        }
        // The keys: a step per press, from the value shown (or reached).
        let (plain, fine) = key_steps(ui, &r);
        if plain != 0 || fine != 0 {
            let current = ui.data(|data| data.get_temp::<Drag>(state_id));
            let (from, start) = current.map_or((self.value, self.value), |d| (d.value, d.start));
            let v = range.moved(from, f64::from(plain), false, start);
            let v = range.moved(v, f64::from(fine), true, start);
            if let Some(mut d) = current {
                d.value = v;
                ui.data_mut(|data| data.insert_temp(state_id, d));
            }
            if v != self.value {
                wanted = Some(v);
            }
        }

        let shown = wanted.unwrap_or(self.value);
        r.widget_info(|| egui::WidgetInfo::slider(ui.is_enabled(), shown, self.name));
        let name = self.name.to_owned();
        ui.ctx().accesskit_node_builder(r.id, |node| {
            node.set_label(name);
            node.set_min_numeric_value(range.min);
            node.set_max_numeric_value(range.max);
            node.add_action(egui::accesskit::Action::Increment);
            node.add_action(egui::accesskit::Action::Decrement);
        });
        if ui.is_rect_visible(rect) {
            paint(ui, &r, rect, &range, shown);
        }
        (r, wanted)
    }
}

/// The arrow presses on the focused slider `r` this frame, as (plain,
/// fine) steps towards larger values: Right and Up raise, Left and Down
/// lower; with Shift a press is a fine step. A screen reader's increment
/// or decrement is a plain step.
fn key_steps(ui: &egui::Ui, r: &egui::Response) -> (i32, i32) {
    let (mut plain, mut fine) = (0, 0);
    if r.has_focus() {
        // Arrows step the value instead of moving the keyboard focus.
        ui.memory_mut(|m| {
            m.set_focus_lock_filter(
                r.id,
                egui::EventFilter {
                    horizontal_arrows: true,
                    vertical_arrows: true,
                    ..Default::default()
                },
            );
        });
        ui.input(|i| {
            for e in &i.events {
                if let egui::Event::Key {
                    key,
                    pressed: true,
                    modifiers,
                    ..
                } = e
                {
                    let sign = match key {
                        egui::Key::ArrowRight | egui::Key::ArrowUp => 1,
                        egui::Key::ArrowLeft | egui::Key::ArrowDown => -1,
                        _ => continue,
                    };
                    if modifiers.shift {
                        fine += sign;
                    } else {
                        plain += sign;
                    }
                }
            }
        });
    }
    ui.input(|i| {
        use egui::accesskit::Action;
        plain += i.num_accesskit_action_requests(r.id, Action::Increment) as i32;
        plain -= i.num_accesskit_action_requests(r.id, Action::Decrement) as i32;
    });
    (plain, fine)
}

/// The rail, the fill up to the handle and the handle, as egui draws its
/// slider (a handle of half-height `height / 2.5`, in the style's shape,
/// kept inside the rect), plus a ring while the slider has the keyboard,
/// so that the user sees which slider the arrows step.
fn paint(ui: &egui::Ui, r: &egui::Response, rect: egui::Rect, range: &SliderRange, value: f64) {
    let visuals = ui.style().interact(r);
    let painter = ui.painter();
    let radius = rect.height() / 2.5;
    let shape = ui.visuals().handle_shape;
    let half_width = match shape {
        egui::style::HandleShape::Circle => radius,
        egui::style::HandleShape::Rect { aspect_ratio } => radius * aspect_ratio,
    };
    let rail_half = (ui.spacing().slider_rail_height / 2.0).max(0.0);
    let rail = egui::Rect::from_min_max(
        egui::pos2(rect.left(), rect.center().y - rail_half),
        egui::pos2(rect.right(), rect.center().y + rail_half),
    );
    let widgets = &ui.visuals().widgets;
    painter.rect_filled(rail, widgets.inactive.corner_radius, widgets.inactive.bg_fill);
    let travel = rect.x_range().shrink(half_width);
    let x = egui::lerp(travel, range.place(value) as f32);
    let center = egui::pos2(x, rect.center().y);
    if ui.visuals().slider_trailing_fill {
        let fill = egui::Rect::from_min_max(rail.min, egui::pos2(x, rail.max.y));
        painter.rect_filled(fill, widgets.inactive.corner_radius, ui.visuals().selection.bg_fill);
    }
    if r.has_focus() {
        painter.rect_stroke(
            rect.expand(1.0),
            widgets.inactive.corner_radius,
            ui.visuals().selection.stroke,
            egui::StrokeKind::Outside,
        );
    }
    match shape {
        egui::style::HandleShape::Circle => {
            painter.circle(center, radius + visuals.expansion, visuals.bg_fill, visuals.fg_stroke);
        }
        egui::style::HandleShape::Rect { .. } => {
            let handle = egui::Rect::from_center_size(center, egui::vec2(2.0 * half_width, 2.0 * radius));
            painter.rect(
                handle.expand(visuals.expansion),
                visuals.corner_radius,
                visuals.bg_fill,
                visuals.fg_stroke,
                egui::StrokeKind::Inside,
            );
        }
    }
}
