//! Pictures of the app for slides: an animated GIF of a few seconds of the
//! window, and one PNG of it. The app asks egui for screenshots
//! ([`egui::Context::request_screenshot`]); this module turns them into
//! files, off the UI thread.
//!
//! Contract: nothing half-written (the finished bytes go through
//! [`crate::gui::export::write_atomic`]), errors are one line naming the
//! file, and the work runs on a background thread that wakes the app when
//! it is done.
//!
//! GIF encoding: each frame is downscaled (area average) to the first
//! frame's output size, mapped to one fixed 256-colour palette
//! ([`palette`]) and LZW-compressed; frames are processed in parallel
//! (rayon) in small batches as they arrive, so the file is ready soon after
//! the recording ends and only the compressed frames stay in memory.
//!
//! Why a fixed palette and not an adaptive one (the gif crate's NeuQuant,
//! `Frame::from_rgba_speed`): NeuQuant spends its 256 colours where the
//! pixels are, so the small swatches that matter (the mode legend, a
//! Poincaré dot) came out grey or in the wrong hue; a fixed palette keeps
//! every hue within a step of the colour cube, the greys of the panels
//! within 4 levels, and is several times faster (no search).

use std::path::{Path, PathBuf};
use std::sync::Arc;

use crossbeam_channel::{Receiver, Sender};
use egui::ColorImage;
use rayon::prelude::*;

use crate::gui::export::write_atomic;

/// Levels per channel of the palette's colour cube (6³ = 216 colours,
/// steps of 51: hues stay recognisable, the web-safe cube).
const CUBE: usize = 6;

/// Greys in the palette besides the cube's six: the app's panels, text
/// and grid lines are greys, which the cube alone would band badly.
const GREYS: usize = 39;

/// The palette index that stands for "as in the frame before": the
/// unchanged pixels of every frame after the first (most of the window)
/// become one long run, which LZW packs to almost nothing.
const UNCHANGED: u8 = 255;

/// The `i`-th extra grey (0-based), spread evenly between black and white.
fn grey(i: usize) -> u8 {
    ((i + 1) * 255 / (GREYS + 1)) as u8
}

/// The GIF palette, RGB bytes: the 6 × 6 × 6 colour cube, then 39 greys,
/// then black at [`UNCHANGED`] (the transparent index; never drawn).
pub(crate) fn palette() -> Vec<u8> {
    let mut p = Vec::with_capacity(3 * 256);
    for r in 0..CUBE {
        for g in 0..CUBE {
            for b in 0..CUBE {
                p.extend([r, g, b].map(|c| (c * 51) as u8));
            }
        }
    }
    for i in 0..GREYS {
        p.extend([grey(i); 3]);
    }
    p.extend([0; 3]);
    p
}

/// The index in [`palette`] of the colour nearest (r, g, b): the nearer
/// of the nearest cube colour and the nearest grey.
pub(crate) fn nearest(r: u8, g: u8, b: u8) -> u8 {
    let level = |c: u8| (usize::from(c) + 25) / 51;
    let (ri, gi, bi) = (level(r), level(g), level(b));
    let d2 = |c: u8, q: u8| {
        let d = i32::from(c) - i32::from(q);
        d * d
    };
    let cube_d = d2(r, (ri * 51) as u8) + d2(g, (gi * 51) as u8) + d2(b, (bi * 51) as u8);
    // The nearest grey is the one nearest the mean; grey(i) ≈ (i + 1)·255/40,
    // so the guess is off by one at most after the rounding: try around it.
    let mean = (usize::from(r) + usize::from(g) + usize::from(b)) / 3;
    let guess = (mean * (GREYS + 1) / 255).clamp(1, GREYS) - 1;
    let (gi_extra, grey_d) = (guess.saturating_sub(1)..=(guess + 1).min(GREYS - 1))
        .map(|i| {
            let q = grey(i);
            (i, d2(r, q) + d2(g, q) + d2(b, q))
        })
        .min_by_key(|&(_, d)| d)
        .expect("at least one grey");
    if grey_d < cube_d {
        (CUBE * CUBE * CUBE + gi_extra) as u8
    } else {
        (ri * CUBE * CUBE + gi * CUBE + bi) as u8
    }
}

/// How many frames are quantised together (in parallel) before they are
/// written: enough to keep every core busy, few enough that uncompressed
/// frames never pile up (each is 4 bytes a pixel).
const BATCH: usize = 8;

/// What to record.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct GifOptions {
    /// Length of the recording, s of wall-clock time.
    pub seconds: f32,
    /// Frames per second. 15 is smooth enough for a rocking block on a
    /// slide and keeps a 5 s clip near a few MB.
    pub fps: f32,
    /// Width of the GIF at most, pixels: a wider window is scaled down.
    /// 960 px fills half a 1920 slide, or all of a 1024 one, sharply.
    pub max_width: usize,
}

impl Default for GifOptions {
    fn default() -> Self {
        Self {
            seconds: 5.0,
            fps: 15.0,
            max_width: 960,
        }
    }
}

/// What was written.
#[derive(Clone, Debug, PartialEq)]
pub struct Written {
    /// The file.
    pub path: PathBuf,
    /// Frames in it (1 for a PNG).
    pub frames: usize,
    /// Its size, bytes.
    pub bytes: usize,
    /// Its picture's size, pixels (width, height).
    pub size: [usize; 2],
}

impl Written {
    /// The status-bar line: `wrote FILE (N frames, X MB)`.
    pub fn line(&self) -> String {
        let name = self
            .path
            .file_name()
            .map_or_else(|| self.path.display().to_string(), |n| n.to_string_lossy().into_owned());
        let mb = self.bytes as f64 / 1e6;
        if self.frames == 1 {
            format!("wrote {name} ({} × {} px, {mb:.1} MB)", self.size[0], self.size[1])
        } else {
            format!(
                "wrote {name} ({} frames, {} × {} px, {mb:.1} MB)",
                self.frames, self.size[0], self.size[1]
            )
        }
    }
}

/// The size of a `size` picture scaled down (never up) to at most
/// `max_width` wide, keeping its aspect ratio; at least 1 × 1.
pub fn fit_width(size: [usize; 2], max_width: usize) -> [usize; 2] {
    let [w, h] = size;
    if w <= max_width || w == 0 {
        return [w.max(1), h.max(1)];
    }
    let height = (h as f64 * max_width as f64 / w as f64).round() as usize;
    [max_width.max(1), height.max(1)]
}

/// [`nearest`] for every colour with 6 bits a channel (the centre of each
/// 4 × 4 × 4 cell): one table read a pixel instead of a search, built once
/// (256 KiB). The cell adds at most 2 levels a channel to the palette's
/// own error.
fn lookup() -> &'static [u8] {
    static LUT: std::sync::OnceLock<Vec<u8>> = std::sync::OnceLock::new();
    LUT.get_or_init(|| {
        let mut t = vec![0u8; 1 << 18];
        for (i, e) in t.iter_mut().enumerate() {
            let c = |shift: usize| (((i >> shift) & 63) * 4 + 2) as u8;
            *e = nearest(c(12), c(6), c(0));
        }
        t
    })
}

/// `img` resampled to `size` as RGB bytes, each output pixel the average
/// of the source pixels it covers (a box filter: sharp text stays legible
/// when shrinking by less than 2, where nearest-neighbour would drop whole
/// rows of a line). A window is opaque: alpha is dropped.
pub fn resample(img: &ColorImage, size: [usize; 2]) -> Vec<u8> {
    let [sw, sh] = img.size;
    let [w, h] = size;
    let mut out = vec![0u8; w * h * 3];
    if sw == 0 || sh == 0 {
        return out;
    }
    // Source span of output column/row i: [i·s/n, (i+1)·s/n), at least one pixel.
    let span = |i: usize, n: usize, s: usize| {
        let a = i * s / n;
        let b = ((i + 1) * s).div_ceil(n).clamp(a + 1, s);
        (a.min(s - 1), b)
    };
    let cols: Vec<(usize, usize)> = (0..w).map(|x| span(x, w, sw)).collect();
    for y in 0..h {
        let (y0, y1) = span(y, h, sh);
        for (x, &(x0, x1)) in cols.iter().enumerate() {
            let mut sum = [0u32; 3];
            for row in img.pixels[y0 * sw..y1 * sw].chunks_exact(sw) {
                for c in &row[x0..x1] {
                    sum[0] += u32::from(c.r());
                    sum[1] += u32::from(c.g());
                    sum[2] += u32::from(c.b());
                }
            }
            let n = ((y1 - y0) * (x1 - x0)) as u32;
            let o = (y * w + x) * 3;
            for k in 0..3 {
                out[o + k] = ((sum[k] + n / 2) / n) as u8;
            }
        }
    }
    out
}

/// An animated GIF built a frame at a time (looping for ever, as slides
/// want). Frame delays come from the frames' capture times, so the GIF
/// plays at the speed the app ran even when frames came unevenly.
pub struct GifBuilder {
    fps: f32,
    max_width: usize,
    size: Option<[usize; 2]>,
    /// Frames waiting for their successor's time (their delay) or for a
    /// batch to fill.
    pending: Vec<(f64, Arc<ColorImage>)>,
    encoder: Option<gif::Encoder<Vec<u8>>>,
    frames: usize,
    /// The last frame written, whole (palette indices).
    prev: Option<Vec<u8>>,
    /// When the recording ended (s, the frames' clock), if known: the
    /// last frame lasts until then.
    end: Option<f64>,
}

impl GifBuilder {
    /// A GIF at most `max_width` wide whose last frame lasts 1/`fps` s.
    pub fn new(fps: f32, max_width: usize) -> Self {
        Self {
            fps,
            max_width,
            size: None,
            pending: Vec::new(),
            encoder: None,
            frames: 0,
            prev: None,
            end: None,
        }
    }

    /// Says when the recording ended (s, the clock of [`GifBuilder::push`]):
    /// the last frame is shown until then, so the GIF plays for the whole
    /// clip even when frames came slower than asked. Without it (or if it
    /// is not after the last frame) the last frame lasts 1/fps.
    pub(crate) fn end_at(&mut self, t: f64) {
        self.end = Some(t);
    }

    /// Adds `image`, captured at `t` (s, any origin, increasing).
    pub fn push(&mut self, t: f64, image: Arc<ColorImage>) -> Result<(), String> {
        self.pending.push((t, image));
        if self.pending.len() > BATCH {
            // The last one waits for its successor's time.
            let last = self.pending.pop().expect("more than BATCH frames");
            let batch = std::mem::replace(&mut self.pending, vec![last.clone()]);
            self.encode(&batch, Some(last.0))?;
        }
        Ok(())
    }

    /// The finished GIF's bytes, its frame count and size; an error if no
    /// frame was pushed.
    pub fn finish(mut self) -> Result<(Vec<u8>, usize, [usize; 2]), String> {
        let batch = std::mem::take(&mut self.pending);
        self.encode(&batch, None)?;
        let size = self.size.ok_or("no frame was captured")?;
        let encoder = self.encoder.take().ok_or("no frame was captured")?;
        let bytes = encoder.into_inner().map_err(|e| e.to_string())?;
        Ok((bytes, self.frames, size))
    }

    /// Quantises and writes `batch`; `next` is the capture time of the
    /// frame after it, if known.
    fn encode(&mut self, batch: &[(f64, Arc<ColorImage>)], next: Option<f64>) -> Result<(), String> {
        let Some(first) = batch.first() else {
            return Ok(());
        };
        let size = *self.size.get_or_insert_with(|| fit_width(first.1.size, self.max_width));
        let (w, h) = match (u16::try_from(size[0]), u16::try_from(size[1])) {
            (Ok(w), Ok(h)) => (w, h),
            _ => return Err(format!("{} × {} px is too large for a GIF", size[0], size[1])),
        };
        let last_cs = 100.0 / f64::from(self.fps.max(0.1));
        let delays: Vec<u16> = (0..batch.len())
            .map(|i| {
                let cs = match batch.get(i + 1).map(|f| f.0).or(next) {
                    Some(t1) => (t1 - batch[i].0) * 100.0,
                    None => match self.end {
                        Some(end) if end > batch[i].0 => (end - batch[i].0) * 100.0,
                        Some(_) | None => last_cs,
                    },
                };
                // GIF delays are centiseconds; viewers treat under 2 as 10.
                cs.round().clamp(2.0, 6000.0) as u16
            })
            .collect();
        let mut indexed: Vec<Vec<u8>> = batch
            .par_iter()
            .map(|(_, img)| {
                let rgb = resample(img, size);
                let lut = lookup();
                rgb.chunks_exact(3)
                    .map(|c| {
                        lut[(usize::from(c[0] >> 2) << 12) | (usize::from(c[1] >> 2) << 6) | usize::from(c[2] >> 2)]
                    })
                    .collect()
            })
            .collect();
        // Each frame after the first keeps only what changed; the others
        // show the frame before through (Keep disposal).
        for full in &mut indexed {
            let next = full.clone();
            if let Some(prev) = &self.prev {
                for (p, q) in full.iter_mut().zip(prev) {
                    if p == q {
                        *p = UNCHANGED;
                    }
                }
            }
            self.prev = Some(next);
        }
        let frames: Vec<gif::Frame<'static>> = indexed
            .into_par_iter()
            .zip(delays.par_iter())
            .map(|(indices, delay)| {
                let mut f = gif::Frame::from_indexed_pixels(w, h, indices, Some(UNCHANGED));
                f.delay = *delay;
                f.dispose = gif::DisposalMethod::Keep;
                f.make_lzw_pre_encoded();
                f
            })
            .collect();
        if self.encoder.is_none() {
            let mut e = gif::Encoder::new(Vec::new(), w, h, &palette()).map_err(|e| e.to_string())?;
            e.set_repeat(gif::Repeat::Infinite).map_err(|e| e.to_string())?;
            self.encoder = Some(e);
        }
        let encoder = self.encoder.as_mut().expect("made above");
        for f in &frames {
            encoder.write_lzw_pre_encoded_frame(f).map_err(|e| e.to_string())?;
        }
        self.frames += frames.len();
        Ok(())
    }
}

/// What the app sends the GIF writer.
pub(crate) enum Shot {
    /// A frame captured at `t`, s.
    Frame(f64, Arc<ColorImage>),
    /// The recording ended at `t`, s (the frames' clock): write the file.
    /// (A writer whose senders are all dropped before this, as when the
    /// app closes, writes nothing.)
    End(f64),
}

/// The GIF writer's thread: it encodes the frames sent on the returned
/// sender as they come and, after [`Shot::End`], writes `path` and sends
/// what it wrote (or why not) on the returned receiver, then calls `wake`.
pub(crate) fn spawn_gif_writer(
    path: PathBuf,
    options: GifOptions,
    wake: impl Fn() + Send + 'static,
) -> (Sender<Shot>, Receiver<Result<Written, String>>) {
    let (tx, rx) = crossbeam_channel::unbounded::<Shot>();
    let (done_tx, done_rx) = crossbeam_channel::bounded(1);
    let refused = done_tx.clone();
    let name = path.display().to_string();
    let spawned = std::thread::Builder::new().name("gif writer".into()).spawn(move || {
        let mut gif = GifBuilder::new(options.fps, options.max_width);
        let mut failed = None;
        let r = loop {
            match rx.recv() {
                Ok(Shot::Frame(t, img)) => {
                    // After a failure, frames are drained and dropped until
                    // the end, which reports it.
                    if failed.is_none()
                        && let Err(e) = gif.push(t, img)
                    {
                        failed = Some(e);
                    }
                }
                Ok(Shot::End(t)) => {
                    gif.end_at(t);
                    break match failed {
                        Some(e) => Err(format!("{}: {e}", path.display())),
                        None => write_gif(&path, gif),
                    };
                }
                Err(_) => return,
            }
        };
        let _ = done_tx.send(r);
        wake();
    });
    if let Err(e) = spawned {
        let _ = refused.send(Err(format!("{name}: cannot start the GIF writer: {e}")));
    }
    (tx, done_rx)
}

/// Finishes `gif` and writes it to `path` atomically.
pub fn write_gif(path: &Path, gif: GifBuilder) -> Result<Written, String> {
    let (bytes, frames, size) = gif.finish().map_err(|e| format!("{}: {e}", path.display()))?;
    write_atomic(path, &bytes)?;
    Ok(Written {
        path: path.to_path_buf(),
        frames,
        bytes: bytes.len(),
        size,
    })
}

/// `img` as PNG bytes (8-bit RGB: a window is opaque).
pub fn encode_png(img: &ColorImage) -> Result<Vec<u8>, String> {
    let [w, h] = img.size;
    let (Ok(w32), Ok(h32)) = (u32::try_from(w), u32::try_from(h)) else {
        return Err(format!("{w} × {h} px is too large"));
    };
    let mut rgb = Vec::with_capacity(w * h * 3);
    for c in &img.pixels {
        rgb.extend_from_slice(&[c.r(), c.g(), c.b()]);
    }
    let mut out = Vec::new();
    let mut enc = png::Encoder::new(&mut out, w32, h32);
    enc.set_color(png::ColorType::Rgb);
    enc.set_depth(png::BitDepth::Eight);
    // Fast compression: a screenshot is mostly flat colour, which deflate
    // packs well at any level; the default level takes several times longer.
    enc.set_compression(png::Compression::Fast);
    let mut writer = enc.write_header().map_err(|e| e.to_string())?;
    writer.write_image_data(&rgb).map_err(|e| e.to_string())?;
    writer.finish().map_err(|e| e.to_string())?;
    Ok(out)
}

/// Writes `img` to `path` as PNG, atomically.
pub fn write_png(path: &Path, img: &ColorImage) -> Result<Written, String> {
    let bytes = encode_png(img).map_err(|e| format!("{}: {e}", path.display()))?;
    write_atomic(path, &bytes)?;
    Ok(Written {
        path: path.to_path_buf(),
        frames: 1,
        bytes: bytes.len(),
        size: img.size,
    })
}

/// Writes `img` to `path` as PNG on a background thread; the result comes
/// on the returned receiver, then `wake` is called.
pub(crate) fn spawn_png_writer(
    path: PathBuf,
    img: Arc<ColorImage>,
    wake: impl Fn() + Send + 'static,
) -> Receiver<Result<Written, String>> {
    let (tx, rx) = crossbeam_channel::bounded(1);
    let refused = tx.clone();
    let name = path.display().to_string();
    let spawned = std::thread::Builder::new().name("png writer".into()).spawn(move || {
        let _ = tx.send(write_png(&path, &img));
        wake();
    });
    if let Err(e) = spawned {
        let _ = refused.send(Err(format!("{name}: cannot start the PNG writer: {e}")));
    }
    rx
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn fit_width_scales_down_only_and_keeps_the_aspect() {
        assert_eq!(fit_width([1280, 800], 960), [960, 600]);
        assert_eq!(fit_width([640, 400], 960), [640, 400]);
        assert_eq!(fit_width([3000, 1], 960), [960, 1]);
    }

    #[test]
    fn resample_averages_the_pixels_each_output_pixel_covers() {
        // 2 × 1 black and white → 1 × 1 mid grey.
        let img = ColorImage::new([2, 1], vec![egui::Color32::BLACK, egui::Color32::WHITE]);
        assert_eq!(resample(&img, [1, 1]), vec![128, 128, 128]);
        // Same size: unchanged.
        let img = ColorImage::new([1, 2], vec![egui::Color32::RED, egui::Color32::BLUE]);
        assert_eq!(resample(&img, [1, 2]), vec![255, 0, 0, 0, 0, 255]);
    }

    #[test]
    fn every_colour_maps_to_the_nearest_palette_entry() {
        let p = palette();
        assert_eq!(p.len(), 3 * 256);
        let dist =
            |i: usize, c: [u8; 3]| -> i32 { (0..3).map(|k| (i32::from(p[3 * i + k]) - i32::from(c[k])).pow(2)).sum() };
        // A sparse grid of colours and every grey: the index found is as
        // near as the best of all 256 entries.
        let mut colours: Vec<[u8; 3]> = (0..=255u8).map(|v| [v; 3]).collect();
        for r in (0..=255u8).step_by(17) {
            for g in (0..=255u8).step_by(15) {
                for b in (0..=255u8).step_by(13) {
                    colours.push([r, g, b]);
                }
            }
        }
        for c in colours {
            let found = usize::from(nearest(c[0], c[1], c[2]));
            let best = (0..256).map(|i| dist(i, c)).min().expect("256 entries");
            assert_eq!(dist(found, c), best, "{c:?} -> entry {found}");
        }
        // The app's dark panel grey is kept within 3 levels.
        let i = usize::from(nearest(27, 27, 27));
        assert!((i32::from(p[3 * i]) - 27).abs() <= 3, "{:?}", &p[3 * i..3 * i + 3]);
    }
}
