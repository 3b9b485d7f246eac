//! The app drawn once more, off screen, with more pixels a point: the
//! PNG of the view at presentation resolution whatever the window's size.
//!
//! Why off screen: the other way, enlarging the window for the picture
//! with the zoom raised to keep the layout, is up to the window manager,
//! and a window manager keeps a maximised window, or one as large as the
//! screen, at its size; the picture then had the window's 1280 × 800
//! pixels, not the 1920 promised.
//!
//! How: a second egui context gets the window's state (memory: panel
//! sizes, plot bounds, tabs; options: theme and zoom; fonts), the same
//! screen in points with `scale` times the pixels per point, and runs the
//! app's `ui` once: the same layout, drawn with more pixels. Its shapes
//! are drawn by the app's own egui-wgpu renderer, which holds the app's
//! textures (the Poincaré density, the outcome map) and the block
//! scene's pipeline, into a texture that is then read back. The second
//! context's own textures (its font atlas, rasterised at the higher
//! scale) are lent to the renderer under user ids, [`LENT_IDS`] up, for
//! that one drawing and freed after.
//!
//! Contract: the window, its zoom, its memory and its textures are left
//! as they were. The app runs its `ui` a second time in the frame;
//! [`RockingApp::exporting_view`] is true meanwhile, and the sharing tick
//! does nothing in that pass. The target has one sample a pixel, as the
//! app's renderer (eframe's default `multisampling: 0`).

use std::time::Duration;

use egui::epaint::{ClippedPrimitive, Primitive};
use egui::{ColorImage, TextureId};
use egui_wgpu::wgpu;

use super::RockingApp;

/// The first user texture id lent to the second context's textures: far
/// above the ids egui-wgpu hands out for native textures (from 0 up).
const LENT_IDS: u64 = 1 << 48;

/// How long to wait for the GPU to draw and copy the picture.
const GPU_WAIT: Duration = Duration::from_secs(20);

/// The id a texture of the second context is lent under.
fn lent(id: TextureId) -> TextureId {
    match id {
        TextureId::Managed(n) => TextureId::User(LENT_IDS + n),
        TextureId::User(_) => id,
    }
}

impl RockingApp {
    /// The app drawn with `scale` times the window's pixels per point, in
    /// the window's layout: a picture of `scale` × the window's pixels.
    /// Called from [`eframe::App::logic`] (it needs the frame, to run the
    /// app's `ui`, and the renderer).
    pub(super) fn draw_offscreen(
        &mut self,
        ctx: &egui::Context,
        frame: &mut eframe::Frame,
        scale: f32,
    ) -> Result<ColorImage, String> {
        let rs = frame
            .wgpu_render_state()
            .cloned()
            .ok_or("no GPU renderer to draw the view with")?;
        let rect = ctx.content_rect();
        let ppp = ctx.pixels_per_point() * scale;
        let zoom = ctx.zoom_factor();

        let second = egui::Context::default();
        second.options_mut(|o| *o = ctx.options(|o| o.clone()));
        second.set_fonts(ctx.fonts(|f| f.definitions().clone()));
        second.memory_mut(|m| *m = ctx.memory(|m| m.clone()));
        let mut input = egui::RawInput {
            screen_rect: Some(rect),
            time: Some(ctx.input(|i| i.time)),
            max_texture_side: Some(ctx.input(|i| i.max_texture_side)),
            focused: true,
            ..Default::default()
        };
        if let Some(root) = input.viewports.get_mut(&egui::ViewportId::ROOT) {
            root.native_pixels_per_point = Some(ppp / zoom);
            root.inner_rect = Some(rect);
            root.focused = Some(true);
        }
        self.share.offscreen = true;
        let output = second.run_ui(input, |ui| eframe::App::ui(self, ui, frame));
        self.share.offscreen = false;

        let ppp = second.pixels_per_point();
        let mut primitives = second.tessellate(output.shapes, ppp);
        for p in &mut primitives {
            if let ClippedPrimitive {
                primitive: Primitive::Mesh(mesh),
                ..
            } = p
                && let TextureId::Managed(_) = mesh.texture_id
                && owned(&second, mesh.texture_id)
            {
                mesh.texture_id = lent(mesh.texture_id);
            }
        }
        let size = [
            (rect.width() * ppp).round().max(1.0) as u32,
            (rect.height() * ppp).round().max(1.0) as u32,
        ];
        let clear = ctx.style_of(ctx.theme()).visuals.panel_fill;
        let mut delta = output.textures_delta;
        let picture = render(&rs, &second, &delta, &primitives, size, ppp, clear);
        // Applied (lent and freed) or, after a refusal, not needed: the
        // second context goes with this call.
        delta.clear();
        picture
    }
}

/// Whether `id` is a texture of `ctx` (and not one of the window's
/// context that the app's `ui` referred to by its id).
fn owned(ctx: &egui::Context, id: TextureId) -> bool {
    ctx.tex_manager().read().meta(id).is_some()
}

/// Draws `primitives` into a `size` picture at `ppp` pixels a point with
/// the app's renderer, after lending it `second`'s textures from `delta`.
fn render(
    rs: &egui_wgpu::RenderState,
    second: &egui::Context,
    delta: &egui::TexturesDelta,
    primitives: &[ClippedPrimitive],
    size: [u32; 2],
    ppp: f32,
    clear: egui::Color32,
) -> Result<ColorImage, String> {
    let max = rs.device.limits().max_texture_dimension_2d;
    if size[0] > max || size[1] > max {
        return Err(format!(
            "{} × {} px is more than the GPU draws ({max} px)",
            size[0], size[1]
        ));
    }
    let format = rs.target_format;
    let swap = match format {
        wgpu::TextureFormat::Rgba8Unorm | wgpu::TextureFormat::Rgba8UnormSrgb => false,
        wgpu::TextureFormat::Bgra8Unorm | wgpu::TextureFormat::Bgra8UnormSrgb => true,
        other => return Err(format!("cannot read pictures in the {other:?} format back")),
    };
    let texture = rs.device.create_texture(&wgpu::TextureDescriptor {
        label: Some("view export"),
        size: wgpu::Extent3d {
            width: size[0],
            height: size[1],
            depth_or_array_layers: 1,
        },
        mip_level_count: 1,
        sample_count: 1,
        dimension: wgpu::TextureDimension::D2,
        format,
        usage: wgpu::TextureUsages::RENDER_ATTACHMENT | wgpu::TextureUsages::COPY_SRC,
        view_formats: &[],
    });
    let view = texture.create_view(&wgpu::TextureViewDescriptor::default());
    let screen = egui_wgpu::ScreenDescriptor {
        size_in_pixels: size,
        pixels_per_point: ppp,
    };
    let lent_ids: Vec<TextureId> = second
        .tex_manager()
        .read()
        .allocated()
        .map(|(id, _)| lent(*id))
        .collect();
    let mut encoder = rs.device.create_command_encoder(&wgpu::CommandEncoderDescriptor {
        label: Some("view export"),
    });
    let submitted = {
        let mut renderer = rs.renderer.write();
        // In order for each texture (a full image, then its patches); the
        // textures' order among themselves does not matter.
        for (id, images) in &delta.set {
            for image in images {
                renderer.update_texture(&rs.device, &rs.queue, lent(*id), image);
            }
        }
        let extra = renderer.update_buffers(&rs.device, &rs.queue, &mut encoder, primitives, &screen);
        {
            let [r, g, b, a] = clear.to_normalized_gamma_f32();
            let mut pass = encoder
                .begin_render_pass(&wgpu::RenderPassDescriptor {
                    label: Some("view export"),
                    color_attachments: &[Some(wgpu::RenderPassColorAttachment {
                        view: &view,
                        resolve_target: None,
                        ops: wgpu::Operations {
                            load: wgpu::LoadOp::Clear(wgpu::Color {
                                r: f64::from(r),
                                g: f64::from(g),
                                b: f64::from(b),
                                a: f64::from(a),
                            }),
                            store: wgpu::StoreOp::Store,
                        },
                        depth_slice: None,
                    })],
                    ..Default::default()
                })
                .forget_lifetime();
            renderer.render(&mut pass, primitives, &screen);
        }
        let submitted = rs
            .queue
            .submit(extra.into_iter().chain(std::iter::once(encoder.finish())));
        // The GPU keeps what it still needs; the renderer forgets them.
        for id in &lent_ids {
            renderer.free_texture(id);
        }
        submitted
    };
    rs.device
        .poll(wgpu::PollType::Wait {
            submission_index: Some(submitted),
            timeout: Some(GPU_WAIT),
        })
        .map_err(|e| format!("the GPU did not draw the view: {e}"))?;
    read_back(rs, &texture, size, swap)
}

/// The pixels of `texture` (`size`, 4 bytes a pixel; `swap`: BGRA).
fn read_back(
    rs: &egui_wgpu::RenderState,
    texture: &wgpu::Texture,
    size: [u32; 2],
    swap: bool,
) -> Result<ColorImage, String> {
    let [w, h] = size.map(|v| v as usize);
    let row = 4 * w;
    let align = wgpu::COPY_BYTES_PER_ROW_ALIGNMENT as usize;
    let padded = row.div_ceil(align) * align;
    let buffer = rs.device.create_buffer(&wgpu::BufferDescriptor {
        label: Some("view export"),
        size: (padded * h) as u64,
        usage: wgpu::BufferUsages::MAP_READ | wgpu::BufferUsages::COPY_DST,
        mapped_at_creation: false,
    });
    let mut encoder = rs.device.create_command_encoder(&wgpu::CommandEncoderDescriptor {
        label: Some("view export"),
    });
    encoder.copy_texture_to_buffer(
        texture.as_image_copy(),
        wgpu::TexelCopyBufferInfo {
            buffer: &buffer,
            layout: wgpu::TexelCopyBufferLayout {
                offset: 0,
                bytes_per_row: Some(padded as u32),
                rows_per_image: None,
            },
        },
        wgpu::Extent3d {
            width: size[0],
            height: size[1],
            depth_or_array_layers: 1,
        },
    );
    let submitted = rs.queue.submit(std::iter::once(encoder.finish()));
    let (tx, rx) = std::sync::mpsc::channel();
    buffer.slice(..).map_async(wgpu::MapMode::Read, move |r| {
        let _ = tx.send(r);
    });
    rs.device
        .poll(wgpu::PollType::Wait {
            submission_index: Some(submitted),
            timeout: Some(GPU_WAIT),
        })
        .map_err(|e| format!("the GPU did not copy the view: {e}"))?;
    rx.recv_timeout(GPU_WAIT)
        .map_err(|_| "the GPU did not copy the view".to_string())?
        .map_err(|e| format!("the view could not be read back: {e}"))?;
    let data = buffer
        .slice(..)
        .get_mapped_range()
        .map_err(|e| format!("the view could not be read back: {e}"))?;
    let mut pixels = Vec::with_capacity(w * h);
    for line in data.chunks_exact(padded) {
        for p in line[..row].chunks_exact(4) {
            let (r, b) = if swap { (p[2], p[0]) } else { (p[0], p[2]) };
            pixels.push(egui::Color32::from_rgba_premultiplied(r, p[1], b, p[3]));
        }
    }
    Ok(ColorImage::new(size.map(|v| v as usize), pixels))
}
