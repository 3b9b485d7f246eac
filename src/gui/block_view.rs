//! The block scene's wgpu pipeline, drawn through an egui paint callback
//! (the pattern of egui's `custom3d_wgpu` example).
//!
//! Contract: the pipeline, uniform buffer, instance buffer and bind group
//! are built once, by [`install`], and stored in egui-wgpu's
//! `callback_resources`; each frame only a [`SceneCallback`] with the view
//! and the shapes is added, `prepare` writes them into the buffers and
//! `paint` draws. Every shape is a [`Shape`]: an anti-aliased rectangle or
//! ellipse in metres, filled or outlined (`shaders/block.wgsl`). Where no wgpu render state
//! exists (a headless test harness) [`install`] is never called and the
//! scene falls back to egui's painter with the same shapes.

use bytemuck::{Pod, Zeroable};
use egui_wgpu::wgpu;
use wgpu::util::DeviceExt as _;

/// Most shapes one frame draws: a block, 100 ghosts, an impact flash,
/// the base and its ticks, forces and markers, with room to spare.
pub(crate) const MAX_SHAPES: usize = 512;

/// One shape, laid out as the shader's per-instance vertex attributes
/// (48 bytes: a multiple of 16).
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, PartialEq, Pod, Zeroable)]
pub struct Shape {
    /// Centre, m.
    pub center: [f32; 2],
    /// Half width and half height, m.
    pub half_size: [f32; 2],
    /// Premultiplied RGBA in gamma space (egui's blending convention).
    pub color: [f32; 4],
    /// Rotation, rad, clockwise positive; and the shape kind
    /// (0 rectangle, 1 ellipse).
    pub angle_shape: [f32; 2],
    /// Outline width, m, centred on the edge (0: filled); and padding to
    /// 16 bytes.
    pub stroke: [f32; 2],
}

impl Shape {
    /// A rectangle.
    pub fn rect(center: [f64; 2], half_size: [f64; 2], angle: f64, color: egui::Color32) -> Self {
        Self {
            center: [center[0] as f32, center[1] as f32],
            half_size: [half_size[0] as f32, half_size[1] as f32],
            color: color.to_normalized_gamma_f32(),
            angle_shape: [angle as f32, 0.0],
            stroke: [0.0; 2],
        }
    }

    /// The outline of a rectangle: a band `width` wide (m) centred on its
    /// edge, so half of it shows even where the rectangle lies on a filled
    /// shape of the same size.
    pub fn outline(center: [f64; 2], half_size: [f64; 2], angle: f64, width: f64, color: egui::Color32) -> Self {
        Self {
            stroke: [width as f32, 0.0],
            ..Self::rect(center, half_size, angle, color)
        }
    }

    /// A circle of radius `r`.
    pub fn circle(center: [f64; 2], r: f64, color: egui::Color32) -> Self {
        Self {
            angle_shape: [0.0, 1.0],
            ..Self::rect(center, [r, r], 0.0, color)
        }
    }

    /// A segment from `a` to `b` of width `w`, all in metres.
    pub(crate) fn segment(a: [f64; 2], b: [f64; 2], w: f64, color: egui::Color32) -> Self {
        let (dx, dy) = (b[0] - a[0], b[1] - a[1]);
        let len = dx.hypot(dy);
        // The shader rotates clockwise; a segment's direction angle is
        // counter-clockwise from +x, hence the minus.
        let angle = -dy.atan2(dx);
        Self::rect(
            [0.5 * (a[0] + b[0]), 0.5 * (a[1] + b[1])],
            [0.5 * len, 0.5 * w],
            angle,
            color,
        )
    }
}

/// World-to-screen mapping of the scene, as the shader's uniform (32 bytes).
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, PartialEq, Pod, Zeroable)]
pub struct ViewUniform {
    /// NDC per metre.
    pub scale: [f32; 2],
    /// NDC of the world origin.
    pub offset: [f32; 2],
    /// Physical pixels per metre.
    pub px_per_m: [f32; 2],
    /// Padding to 16 bytes.
    pub _pad: [f32; 2],
}

/// The GPU objects, built once.
struct SceneResources {
    pipeline: wgpu::RenderPipeline,
    bind_group: wgpu::BindGroup,
    uniform: wgpu::Buffer,
    instances: wgpu::Buffer,
}

/// Builds the pipeline and stores it in the renderer's callback resources.
pub fn install(render_state: &egui_wgpu::RenderState) {
    let device = &render_state.device;
    let shader = device.create_shader_module(wgpu::ShaderModuleDescriptor {
        label: Some("block scene"),
        source: wgpu::ShaderSource::Wgsl(include_str!("../../shaders/block.wgsl").into()),
    });
    let bgl = device.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
        label: Some("block scene"),
        entries: &[wgpu::BindGroupLayoutEntry {
            binding: 0,
            visibility: wgpu::ShaderStages::VERTEX,
            ty: wgpu::BindingType::Buffer {
                ty: wgpu::BufferBindingType::Uniform,
                has_dynamic_offset: false,
                min_binding_size: wgpu::BufferSize::new(std::mem::size_of::<ViewUniform>() as u64),
            },
            count: None,
        }],
    });
    let layout = device.create_pipeline_layout(&wgpu::PipelineLayoutDescriptor {
        label: Some("block scene"),
        bind_group_layouts: &[Some(&bgl)],
        immediate_size: 0,
    });
    let attributes =
        wgpu::vertex_attr_array![0 => Float32x2, 1 => Float32x2, 2 => Float32x4, 3 => Float32x2, 4 => Float32x2];
    let pipeline = device.create_render_pipeline(&wgpu::RenderPipelineDescriptor {
        label: Some("block scene"),
        layout: Some(&layout),
        vertex: wgpu::VertexState {
            module: &shader,
            entry_point: Some("vs_main"),
            buffers: &[Some(wgpu::VertexBufferLayout {
                array_stride: std::mem::size_of::<Shape>() as u64,
                step_mode: wgpu::VertexStepMode::Instance,
                attributes: &attributes,
            })],
            compilation_options: Default::default(),
        },
        fragment: Some(wgpu::FragmentState {
            module: &shader,
            entry_point: Some("fs_main"),
            targets: &[Some(wgpu::ColorTargetState {
                format: render_state.target_format,
                blend: Some(wgpu::BlendState::PREMULTIPLIED_ALPHA_BLENDING),
                write_mask: wgpu::ColorWrites::ALL,
            })],
            compilation_options: Default::default(),
        }),
        primitive: wgpu::PrimitiveState {
            topology: wgpu::PrimitiveTopology::TriangleStrip,
            ..Default::default()
        },
        depth_stencil: None,
        multisample: wgpu::MultisampleState::default(),
        multiview_mask: None,
        cache: None,
    });
    let uniform = device.create_buffer_init(&wgpu::util::BufferInitDescriptor {
        label: Some("block scene view"),
        contents: bytemuck::bytes_of(&ViewUniform::default()),
        usage: wgpu::BufferUsages::UNIFORM | wgpu::BufferUsages::COPY_DST,
    });
    let instances = device.create_buffer(&wgpu::BufferDescriptor {
        label: Some("block scene shapes"),
        size: (MAX_SHAPES * std::mem::size_of::<Shape>()) as u64,
        usage: wgpu::BufferUsages::VERTEX | wgpu::BufferUsages::COPY_DST,
        mapped_at_creation: false,
    });
    let bind_group = device.create_bind_group(&wgpu::BindGroupDescriptor {
        label: Some("block scene"),
        layout: &bgl,
        entries: &[wgpu::BindGroupEntry {
            binding: 0,
            resource: uniform.as_entire_binding(),
        }],
    });
    render_state.renderer.write().callback_resources.insert(SceneResources {
        pipeline,
        bind_group,
        uniform,
        instances,
    });
}

/// One frame of the scene: the view and the shapes (at most [`MAX_SHAPES`];
/// the rest are not drawn).
pub(crate) struct SceneCallback {
    /// The view.
    pub view: ViewUniform,
    /// The shapes, back to front.
    pub shapes: Vec<Shape>,
}

impl egui_wgpu::CallbackTrait for SceneCallback {
    fn prepare(
        &self,
        _device: &wgpu::Device,
        queue: &wgpu::Queue,
        _screen: &egui_wgpu::ScreenDescriptor,
        _encoder: &mut wgpu::CommandEncoder,
        resources: &mut egui_wgpu::CallbackResources,
    ) -> Vec<wgpu::CommandBuffer> {
        if let Some(r) = resources.get::<SceneResources>() {
            queue.write_buffer(&r.uniform, 0, bytemuck::bytes_of(&self.view));
            let n = self.shapes.len().min(MAX_SHAPES);
            if n > 0 {
                queue.write_buffer(&r.instances, 0, bytemuck::cast_slice(&self.shapes[..n]));
            }
        }
        Vec::new()
    }

    fn paint(
        &self,
        _info: egui::PaintCallbackInfo,
        pass: &mut wgpu::RenderPass<'static>,
        resources: &egui_wgpu::CallbackResources,
    ) {
        let Some(r) = resources.get::<SceneResources>() else {
            return;
        };
        let n = self.shapes.len().min(MAX_SHAPES) as u32;
        if n == 0 {
            return;
        }
        pass.set_pipeline(&r.pipeline);
        pass.set_bind_group(0, &r.bind_group, &[]);
        pass.set_vertex_buffer(0, r.instances.slice(..));
        pass.draw(0..4, 0..n);
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn gpu_structs_are_padded_to_16_bytes() {
        assert_eq!(std::mem::size_of::<Shape>() % 16, 0);
        assert_eq!(std::mem::size_of::<ViewUniform>() % 16, 0);
    }

    #[test]
    fn a_segment_spans_its_end_points() {
        let s = Shape::segment([0.0, 0.0], [0.0, 2.0], 0.1, egui::Color32::WHITE);
        assert_eq!(s.center, [0.0, 1.0]);
        assert!((s.half_size[0] - 1.0).abs() < 1e-6);
        // Pointing up: clockwise rotation by −π/2 turns +x to +y.
        assert!((s.angle_shape[0] + std::f32::consts::FRAC_PI_2).abs() < 1e-6);
    }

    #[test]
    fn an_outline_is_a_rectangle_with_a_stroke() {
        let r = Shape::rect([1.0, 2.0], [0.5, 2.0], 0.1, egui::Color32::RED);
        let o = Shape::outline([1.0, 2.0], [0.5, 2.0], 0.1, 0.02, egui::Color32::RED);
        assert_eq!(r.stroke[0], 0.0);
        assert_eq!(o.stroke[0], 0.02);
        assert_eq!(Shape { stroke: [0.0; 2], ..o }, r);
    }
}
