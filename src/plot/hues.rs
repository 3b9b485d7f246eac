//! The hues the figures draw series and classes in, by name: matplotlib's
//! "tab10" set (distinct in print and on screen, and familiar to readers
//! of scientific plots) and two light hues of its "tab20". Each palette
//! lists its order of these names, so a hue is written once.

use plotters::style::RGBColor;

/// tab10 blue.
pub(crate) const BLUE: RGBColor = RGBColor(31, 119, 180);
/// tab10 orange.
pub(crate) const ORANGE: RGBColor = RGBColor(255, 127, 14);
/// tab10 green.
pub(crate) const GREEN: RGBColor = RGBColor(44, 160, 44);
/// tab10 red.
pub(crate) const RED: RGBColor = RGBColor(214, 39, 40);
/// tab10 purple.
pub(crate) const PURPLE: RGBColor = RGBColor(148, 103, 189);
/// tab10 brown.
pub(crate) const BROWN: RGBColor = RGBColor(140, 86, 75);
/// tab10 pink.
pub(crate) const PINK: RGBColor = RGBColor(227, 119, 194);
/// tab10 grey.
pub(crate) const GREY: RGBColor = RGBColor(127, 127, 127);
/// tab10 olive.
pub(crate) const OLIVE: RGBColor = RGBColor(188, 189, 34);
/// tab10 cyan.
pub(crate) const CYAN: RGBColor = RGBColor(23, 190, 207);
/// tab20 light blue.
pub(crate) const LIGHT_BLUE: RGBColor = RGBColor(174, 199, 232);
/// tab20 light green.
pub(crate) const LIGHT_GREEN: RGBColor = RGBColor(152, 223, 138);
