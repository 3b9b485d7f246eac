//! Reading a figure's SVG back for tests: its texts with their positions,
//! the numbers on its axes, and whether any shows a raw underscore.

/// One `<text>` element: its position, anchor and content.
#[derive(Clone, Debug, PartialEq)]
pub(crate) struct SvgText {
    /// x, pixels.
    pub x: f64,
    /// y, pixels.
    pub y: f64,
    /// `text-anchor`: `start`, `middle` or `end`.
    pub anchor: String,
    /// Whether it is turned (an axis title).
    pub rotated: bool,
    /// The text, entities decoded.
    pub content: String,
}

fn attr(tag: &str, name: &str) -> Option<String> {
    let key = format!(" {name}=\"");
    let start = tag.find(&key)? + key.len();
    let end = tag[start..].find('"')? + start;
    Some(tag[start..end].to_string())
}

/// Every `<text>` element of `svg`.
pub fn texts(svg: &str) -> Vec<SvgText> {
    let mut out = Vec::new();
    let mut rest = svg;
    while let Some(open) = rest.find("<text") {
        let after = &rest[open..];
        let (Some(tag_end), Some(close)) = (after.find('>'), after.find("</text>")) else {
            break;
        };
        let tag = &after[..tag_end];
        let content = after[tag_end + 1..close]
            .replace("&lt;", "<")
            .replace("&gt;", ">")
            .replace("&quot;", "\"")
            .replace("&#39;", "'")
            .replace("&amp;", "&");
        out.push(SvgText {
            x: attr(tag, "x").and_then(|v| v.parse().ok()).unwrap_or(f64::NAN),
            y: attr(tag, "y").and_then(|v| v.parse().ok()).unwrap_or(f64::NAN),
            anchor: attr(tag, "text-anchor").unwrap_or_default(),
            rotated: tag.contains("rotate("),
            content,
        });
        rest = &after[close + 7..];
    }
    out
}

/// Whether `text` reads as a number (`2`, `0.5`, `-1`, `1e-5`).
fn is_number(text: &str) -> bool {
    text.trim().replace('−', "-").parse::<f64>().is_ok()
}

/// The numbers under the lowest x axis of `svg`: the numeric, centred texts
/// on the lowest row that holds any.
pub(crate) fn x_axis_numbers(svg: &str) -> Vec<String> {
    let numbers: Vec<SvgText> = texts(svg)
        .into_iter()
        .filter(|t| !t.rotated && t.anchor == "middle" && is_number(&t.content))
        .collect();
    let lowest = numbers.iter().map(|t| t.y).fold(f64::NEG_INFINITY, f64::max);
    numbers
        .into_iter()
        .filter(|t| (t.y - lowest).abs() < 1.0)
        .map(|t| t.content)
        .collect()
}

/// The numbers beside the leftmost y axis of `svg`: the numeric,
/// right-aligned texts in the leftmost column that holds any.
pub(crate) fn y_axis_numbers(svg: &str) -> Vec<String> {
    let numbers: Vec<SvgText> = texts(svg)
        .into_iter()
        .filter(|t| !t.rotated && t.anchor == "end" && is_number(&t.content))
        .collect();
    let leftmost = numbers.iter().map(|t| t.x).fold(f64::INFINITY, f64::min);
    numbers
        .into_iter()
        .filter(|t| (t.x - leftmost).abs() < 1.0)
        .map(|t| t.content)
        .collect()
}

/// Asserts that the x and y axes of `svg` each carry at least two numbers.
pub(crate) fn assert_numbered(svg: &str, what: &str) {
    let (x, y) = (x_axis_numbers(svg), y_axis_numbers(svg));
    assert!(x.len() >= 2, "{what}: x axis numbers {x:?}");
    assert!(y.len() >= 2, "{what}: y axis numbers {y:?}");
}

/// The texts of `svg` that show an underscore.
pub(crate) fn underscores(svg: &str) -> Vec<String> {
    texts(svg)
        .into_iter()
        .map(|t| t.content)
        .filter(|c| c.contains('_'))
        .collect()
}
