//! The parameter sliders as an explorer uses them: a grab never jumps the
//! value (it moves by how far the pointer moved, one step per point), a
//! Shift-drag moves a twentieth as far and goes on past the end of the
//! rail, the arrow keys step the focused slider, the tooltip says the
//! steps, and the period-doubling lesson is one continuous drag through
//! the windows the core computes. Driven headless through egui_kittest on
//! the app fed a fixed (empty) stream, so every value comes from the panel.
#![cfg(feature = "gui")]

mod gui_common;

use egui_kittest::Harness;
use egui_kittest::kittest::{By, NodeT as _, Queryable as _};
use gui_common::{pointer, scene};
use rocking::analysis::classify::{ClassifyOptions, Response};
use rocking::analysis::orbit_diagram::{BlockSweep, Continuation, Grid, Plan, block_sweep};
use rocking::analysis::steady::Window;
use rocking::gui::RockingApp;
use rocking::gui::lessons::Note;
use rocking::sim::Param;

/// What the A_v slider's tooltip promises: a point of plain drag (or an
/// arrow press) moves A_v by 0.1 ψg, a fine one by 0.005 ψg.
const STEP: f64 = 0.1;
const FINE: f64 = 0.005;

/// The windows of the period-doubling cascade on the period-doubling
/// preset, as the core finds them sweeping A_v upwards from 1.6 with each
/// value started from the last one's final state (as a drag goes on from
/// the state shown), on the 0.005 grid a fine drag visits:
/// `rocking sweep --preset period-doubling --param excitation.a_v
/// --from 1.6 --to 2.33 --step 0.005 --continuation up`. The note's
/// numbers; checked against the core by
/// [`the_period_doubling_note_gives_the_windows_the_core_finds`].
const PERIOD_2: (f64, f64) = (1.71, 2.265);
const PERIOD_4: (f64, f64) = (2.27, 2.315);
const PERIOD_8: (f64, f64) = (2.32, 2.32);

fn app(preset: &str, size: egui::Vec2) -> Harness<'static, RockingApp> {
    let (s, c) = scene(preset, &[]);
    let mut h = Harness::builder()
        .with_size(size)
        .build_eframe(move |cc| RockingApp::with_stream(cc, s, c, Vec::new()));
    h.step();
    h
}

fn a_v(h: &Harness<'static, RockingApp>) -> f64 {
    h.state().config().excitation.a_v
}

/// The slider's rect and where its handle is drawn for `value` on a
/// 0–5 rail (egui's default handle, half as wide as 0.75 × height / 2.5,
/// kept inside the rail).
fn handle(h: &Harness<'static, RockingApp>, value: f64) -> (egui::Rect, egui::Pos2) {
    let rect = h.get_by_label("A_v slider").rect();
    let inset = 0.75 * rect.height() / 2.5;
    let x = rect.left() + inset + (value / 5.0) as f32 * (rect.width() - 2.0 * inset);
    (rect, egui::pos2(x, rect.center().y))
}

fn shift(h: &Harness<'static, RockingApp>, held: bool) {
    let m = if held {
        egui::Modifiers::SHIFT
    } else {
        egui::Modifiers::NONE
    };
    h.event(egui::Event::ModifiersChanged(m));
}

#[test]
fn a_press_anywhere_on_the_slider_without_moving_keeps_the_value() {
    let mut h = app("period-doubling", egui::vec2(1280.0, 800.0));
    assert_eq!(a_v(&h), 1.6);
    let (rect, on_handle) = handle(&h, 1.6);
    // Near the right end (about A_v = 4.8 under the pointer), on the
    // left end, then on the handle: press, hold a few frames, release.
    for at in [
        egui::pos2(rect.right() - 4.0, rect.center().y),
        egui::pos2(rect.left() + 2.0, rect.center().y),
        on_handle,
    ] {
        pointer(&mut h, at, None);
        pointer(&mut h, at, Some(true));
        h.step();
        pointer(&mut h, at, Some(false));
        h.step();
        assert_eq!(a_v(&h), 1.6, "pressed at x = {} (rail {:?})", at.x, rect.x_range());
    }
}

#[test]
fn a_drag_of_n_points_moves_the_value_n_steps() {
    let mut h = app("period-doubling", egui::vec2(1280.0, 800.0));
    let (rect, _) = handle(&h, 1.6);
    // Grabbed away from the handle (near the left end), moved right 7
    // points in 1-point frames, then left 11 in one frame.
    let start = egui::pos2(rect.left() + 5.0, rect.center().y);
    pointer(&mut h, start, None);
    pointer(&mut h, start, Some(true));
    let mut seen = Vec::new();
    for k in 1..=7 {
        pointer(&mut h, start + egui::vec2(k as f32, 0.0), None);
        seen.push(a_v(&h));
    }
    assert_eq!(seen, [1.7, 1.8, 1.9, 2.0, 2.1, 2.2, 2.3], "one step per point");
    assert!((a_v(&h) - (1.6 + 7.0 * STEP)).abs() < 1e-12);
    pointer(&mut h, start + egui::vec2(-4.0, 0.0), None);
    pointer(&mut h, start + egui::vec2(-4.0, 0.0), Some(false));
    h.step();
    assert_eq!(a_v(&h), 1.2, "then 11 points left: 2.3 − 11 × {STEP}");
}

#[test]
fn a_shift_drag_goes_on_past_the_end_of_the_rail() {
    let mut h = app("period-doubling", egui::vec2(1280.0, 800.0));
    let (rect, at) = handle(&h, 1.6);
    pointer(&mut h, at, None);
    pointer(&mut h, at, Some(true));
    shift(&h, true);
    // To the rail's right end in 10-point frames, then 100 points beyond.
    let mut x = at.x;
    let mut at_end = None;
    let mut frames = 0;
    while x < rect.right() + 100.0 {
        x += 10.0;
        frames += 1;
        if frames == 3 {
            // Letting go of Shift mid-drag keeps the drag fine.
            shift(&h, false);
        }
        pointer(&mut h, egui::pos2(x, at.y), None);
        if at_end.is_none() && x >= rect.right() {
            at_end = Some((x, a_v(&h)));
        }
    }
    pointer(&mut h, egui::pos2(x, at.y), Some(false));
    h.step();
    let (end_x, at_end) = at_end.expect("crossed the rail's end");
    let moved = f64::from(x - at.x);
    let want = 1.6 + moved * FINE;
    let got = a_v(&h);
    assert!(
        got > at_end + 90.0 * FINE,
        "past the rail's end (x = {end_x}, A_v = {at_end}) the value went on to {got}"
    );
    assert!(
        (got - want).abs() < 5e-4,
        "{moved} points of fine drag: A_v = {got}, want 1.6 + {moved} × {FINE} = {want}"
    );
}

#[test]
fn a_fine_drag_stops_only_at_the_sliders_range() {
    let mut h = app("period-doubling", egui::vec2(1280.0, 800.0));
    let (_, at) = handle(&h, 1.6);
    pointer(&mut h, at, None);
    pointer(&mut h, at, Some(true));
    shift(&h, true);
    // 1.6 + 800 × 0.005 = 5.6: held at the rail's 5.
    for k in 1..=8 {
        pointer(&mut h, at + egui::vec2(100.0 * k as f32, 0.0), None);
    }
    assert_eq!(a_v(&h), 5.0);
    // And back: the drag turns at once, from 5.
    pointer(&mut h, at + egui::vec2(790.0, 0.0), None);
    assert_eq!(a_v(&h), 4.95);
    pointer(&mut h, at + egui::vec2(790.0, 0.0), Some(false));
}

#[test]
fn arrow_keys_step_the_focused_slider_and_shift_steps_finely() {
    let mut h = app("period-doubling", egui::vec2(1280.0, 800.0));
    let (rect, _) = handle(&h, 1.6);
    // A click gives the slider the keyboard (and leaves the value).
    let at = egui::pos2(rect.right() - 4.0, rect.center().y);
    pointer(&mut h, at, None);
    pointer(&mut h, at, Some(true));
    pointer(&mut h, at, Some(false));
    h.step();
    assert_eq!(a_v(&h), 1.6);
    let mut seen = Vec::new();
    for (modifiers, key) in [
        (egui::Modifiers::NONE, egui::Key::ArrowRight),
        (egui::Modifiers::SHIFT, egui::Key::ArrowRight),
        (egui::Modifiers::NONE, egui::Key::ArrowLeft),
        (egui::Modifiers::NONE, egui::Key::ArrowUp),
        (egui::Modifiers::SHIFT, egui::Key::ArrowDown),
        (egui::Modifiers::SHIFT, egui::Key::ArrowLeft),
        (egui::Modifiers::NONE, egui::Key::ArrowDown),
    ] {
        h.key_press_modifiers(modifiers, key);
        h.step();
        h.step();
        seen.push(a_v(&h));
    }
    assert_eq!(seen, [1.7, 1.705, 1.605, 1.705, 1.7, 1.695, 1.595]);
    // A key step is applied as a drag is: the same validation and restart.
    assert_eq!(h.state().message().map(|m| m.error), None);
}

#[test]
fn the_slider_tooltip_says_both_steps_with_their_units() {
    let mut h = app("period-doubling", egui::vec2(1280.0, 800.0));
    let (_, at) = handle(&h, 1.6);
    h.hover_at(at);
    for _ in 0..40 {
        h.step();
    }
    let tip = h
        .get(By::new().predicate(|n| n.value().is_some_and(|v| v.contains("step"))))
        .accesskit_node()
        .value()
        .expect("tooltip text");
    for part in [
        "A_v from 0 to 5 ψg",
        "each point of drag moves it 0.1 ψg",
        "hold Shift during the drag for 0.005 ψg a point (20× finer)",
        "past the ends of the rail",
        "Left and Right (or Down and Up) arrow keys step 0.1 ψg, Shift+arrow 0.005 ψg",
    ] {
        assert!(tip.contains(part), "tooltip {tip:?} lacks {part:?}");
    }
}

/// The note teaches the cascade as one fine drag, and says the numbers.
#[test]
fn the_period_doubling_note_says_how_to_drag_and_the_windows() {
    let note = Note::of_preset("period-doubling").expect("a note").text;
    for part in [
        "hold Shift and drag slowly right in one go, 0.005 a point",
        "2 at A_v ≈ 1.71",
        "4 at ≈ 2.27",
        "8 at 2.32",
        "Shift+arrow keys step 0.005",
        "from 2.33, chaos or a tumble",
    ] {
        assert!(note.contains(part), "note {note:?} lacks {part:?}");
    }
}

/// The numbers of the note are the core's: a sweep over the values a fine
/// drag visits, each run from the previous value's end state, finds one
/// dot below 1.71, 2 on [`PERIOD_2`], 4 on [`PERIOD_4`], 8 at
/// [`PERIOD_8`], a longer period at 2.325 and chaos or a tumble at 2.33.
#[test]
fn the_period_doubling_note_gives_the_windows_the_core_finds() {
    let (s, _) = scene("period-doubling", &[]);
    let base = s.resolve().expect("valid scene");
    let spec = BlockSweep {
        base: &base,
        param: Param::Av,
        window: Window::default(),
        classify: ClassifyOptions::default(),
        lyapunov: None,
    };
    let plan = Plan::new(Grid::new(1.6, 2.33, FINE).unwrap(), Continuation::Up, None).unwrap();
    let values = block_sweep(&spec, &plan, &rocking::analysis::silent).expect("sweep");
    assert_eq!(values.len(), 147);
    for v in &values {
        let a = v.value;
        let ok = match v.response {
            Response::Periodic { period: 1 } => a < PERIOD_2.0,
            Response::Periodic { period: 2 } => (PERIOD_2.0..=PERIOD_2.1).contains(&a),
            Response::Periodic { period: 4 } => (PERIOD_4.0..=PERIOD_4.1).contains(&a),
            Response::Periodic { period: 8 } => (PERIOD_8.0..=PERIOD_8.1).contains(&a),
            Response::Periodic { period } => period > 8 && a > PERIOD_8.1 && a < 2.33,
            Response::Chaotic | Response::Tumbled => a >= 2.33,
            _ => false,
        };
        assert!(ok, "A_v = {a}: {:?}", v.response);
    }
    // Each window is reached (not only nothing out of place).
    for period in [1, 2, 4, 8] {
        assert!(
            values.iter().any(|v| v.response == Response::Periodic { period }),
            "period {period}"
        );
    }
}

/// One press, Shift held, the pointer moved right a point a frame: A_v
/// passes through the period-2, -4 and -8 windows in order without a
/// second grab, with the pointer inside the window, at every presentation
/// scale the View menu offers and on both window sizes.
#[test]
fn the_period_doubling_lesson_is_one_continuous_drag_at_every_scale() {
    for size in [egui::vec2(1280.0, 800.0), egui::vec2(1920.0, 1080.0)] {
        for scale in rocking::gui::prefs::offered([size.x, size.y], false) {
            let mut h = app("period-doubling", size);
            h.ctx.set_zoom_factor(scale);
            for _ in 0..3 {
                h.step();
            }
            // Where the panel scrolls, the user scrolls to the slider first.
            h.get_by_label("A_v slider").scroll_to_me();
            for _ in 0..3 {
                h.step();
            }
            let width = size.x / scale;
            let (_, at) = handle(&h, 1.6);
            pointer(&mut h, at, None);
            pointer(&mut h, at, Some(true));
            shift(&h, true);
            let mut reached = vec![a_v(&h)];
            let mut x = at.x;
            while a_v(&h) < PERIOD_8.1 + 2.0 * FINE {
                x += 1.0;
                assert!(
                    x < width,
                    "{size:?} at {scale}: the drag left the window at A_v = {}",
                    a_v(&h)
                );
                pointer(&mut h, egui::pos2(x, at.y), None);
                reached.push(a_v(&h));
            }
            pointer(&mut h, egui::pos2(x, at.y), Some(false));
            let first_in = |w: (f64, f64)| reached.iter().position(|&v| v >= w.0 && v <= w.1 + 1e-9);
            let (two, four, eight) = (first_in(PERIOD_2), first_in(PERIOD_4), first_in(PERIOD_8));
            assert!(
                matches!((two, four, eight), (Some(a), Some(b), Some(c)) if a < b && b < c),
                "{size:?} at {scale}: windows reached at {two:?}, {four:?}, {eight:?} of {reached:?}"
            );
            assert!(
                reached.windows(2).all(|w| w[1] - w[0] <= FINE + 1e-9),
                "{size:?} at {scale}: no value skipped: {reached:?}"
            );
        }
    }
}

/// A slider that took the keyboard by a click (for its arrows) leaves
/// Space to play and pause, as before the click: after a drag the lecturer
/// pauses on what the drag found.
#[test]
fn space_still_plays_and_pauses_while_a_slider_has_the_keyboard() {
    let mut h = app("period-doubling", egui::vec2(1280.0, 800.0));
    let paused = h.state().paused();
    let (_, at) = handle(&h, 1.6);
    pointer(&mut h, at, None);
    pointer(&mut h, at, Some(true));
    pointer(&mut h, at + egui::vec2(3.0, 0.0), None);
    pointer(&mut h, at + egui::vec2(3.0, 0.0), Some(false));
    h.step();
    assert_eq!(a_v(&h), 1.9);
    h.key_press(egui::Key::Space);
    h.step();
    assert_eq!(h.state().paused(), !paused, "Space after the drag");
    // The slider still has the arrows.
    h.key_press(egui::Key::ArrowRight);
    h.step();
    assert_eq!(a_v(&h), 2.0);
}
