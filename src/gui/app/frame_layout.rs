//! Where the last frame put each panel, the banner and the caption after a
//! tumble: read back by the layout tests (no panel covers another, the
//! banner's text inside its plate, the caption off the block), and by
//! nothing else.

use super::RockingApp;

/// The banner's plate and the text drawn on it, points.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct BannerRects {
    /// The dark plate.
    pub plate: egui::Rect,
    /// The union of its lines of text.
    pub text: egui::Rect,
}

/// The rectangles of one frame, points.
#[derive(Clone, Debug, PartialEq)]
pub struct FrameLayout {
    /// The window's content, points.
    pub screen: egui::Rect,
    /// Each panel shown, by name: `controls`, `status`, `params`,
    /// `history`, `side` or `plots` and `analyses`, and `central`.
    pub panels: Vec<(&'static str, egui::Rect)>,
    /// The verdict banner, if one was drawn.
    pub banner: Option<BannerRects>,
    /// The "drawn, not simulated" caption after a tumble, if drawn.
    pub caption: Option<egui::Rect>,
    /// The highest point of the block as drawn (smallest y), points.
    pub block_top: Option<f32>,
    /// The top of the shake table as drawn, points.
    pub table_top: Option<f32>,
    /// The width the parameter panel needs to show its rows without
    /// scrolling them sideways, points (0 before they are drawn): the next
    /// frame makes the panel this wide where the window has room.
    pub params_need: f32,
}

impl Default for FrameLayout {
    fn default() -> Self {
        Self {
            screen: egui::Rect::NOTHING,
            panels: Vec::new(),
            banner: None,
            caption: None,
            block_top: None,
            table_top: None,
            params_need: 0.0,
        }
    }
}

impl RockingApp {
    /// Where the last frame put the panels, the banner and the caption.
    pub fn frame_layout(&self) -> &FrameLayout {
        &self.frame_layout
    }
}
