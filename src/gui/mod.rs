//! The desktop app (feature `gui`): the block, its phase portrait and
//! Poincaré points, live, with every parameter at hand.
//!
//! Layering: the app sits on top of [`crate::sim`]. It starts a
//! [`crate::sim::runner::SimHandle`], sends it commands and draws the
//! updates; it does no mechanics and no analysis. The block scene is drawn
//! by our own wgpu pipeline ([`block_view`], `shaders/block.wgsl`) through an
//! egui paint callback.

pub mod app;
pub mod block_view;
pub mod capture;
pub mod export;
pub mod ghost_trails;
pub mod glossary;
pub mod history;
pub mod lessons;
pub mod panels;
pub mod prefs;
pub mod settings;
pub mod units;

pub use app::RockingApp;
pub use settings::Settings;

use crate::sim::Scenario;
use crate::sim::protocol::Speed;

/// Opens the window on `settings` (resolved to `config`) and runs until it
/// is closed. The block starts moving at once, in real time, unless
/// `paused`.
pub fn run(settings: Settings, config: Scenario, paused: bool) -> Result<(), String> {
    let title = app::window_title(&settings.origin, false);
    let options = eframe::NativeOptions {
        viewport: egui::ViewportBuilder::default()
            .with_title(title)
            .with_inner_size([1280.0, 800.0])
            .with_min_inner_size([640.0, 420.0]),
        renderer: eframe::Renderer::Wgpu,
        ..Default::default()
    };
    // The app's name, not its title: eframe makes it the Wayland app id
    // (what the desktop groups windows and finds the icon by), which a
    // scene's name would change from run to run.
    eframe::run_native(
        "rocking",
        options,
        Box::new(move |cc| {
            let mut app = RockingApp::live(cc, settings, config, Speed::default(), paused);
            app.remember_scale(&cc.egui_ctx);
            Ok(Box::new(app))
        }),
    )
    .map_err(|e| format!("cannot open the window: {e}"))
}
