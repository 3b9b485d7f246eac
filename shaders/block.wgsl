// The block scene: every shape is an instanced quad (a rectangle or an
// ellipse, filled or outlined) with a centre, half-size and clockwise
// rotation in metres and a premultiplied-alpha colour. Edges are
// anti-aliased in the fragment shader by their distance to the boundary in
// pixels, since egui's render pass has no multisampling.

struct View {
    // World (m) to normalised device coordinates of the callback's viewport.
    scale: vec2<f32>,
    offset: vec2<f32>,
    // Pixels per metre, for the anti-aliasing width.
    px_per_m: vec2<f32>,
    _pad: vec2<f32>,
};

@group(0) @binding(0) var<uniform> view: View;

struct Instance {
    @location(0) center: vec2<f32>,
    @location(1) half_size: vec2<f32>,
    @location(2) color: vec4<f32>,
    // x: rotation, rad, clockwise positive; y: shape (0 rectangle, 1 ellipse).
    @location(3) angle_shape: vec2<f32>,
    // x: outline width, m, centred on the edge (0: filled); y: padding.
    @location(4) stroke: vec2<f32>,
};

struct VsOut {
    @builtin(position) position: vec4<f32>,
    // Position inside the shape, in pixels from its centre.
    @location(0) local_px: vec2<f32>,
    @location(1) half_px: vec2<f32>,
    @location(2) color: vec4<f32>,
    @location(3) shape: f32,
    // Outline width in pixels (0: filled).
    @location(4) stroke_px: f32,
};

@vertex
fn vs_main(@builtin(vertex_index) vi: u32, inst: Instance) -> VsOut {
    // Triangle strip: (-1,-1), (1,-1), (-1,1), (1,1), grown by one pixel
    // and half an outline so neither the anti-aliased edge nor the outer
    // half of an outline is clipped.
    let corner = vec2<f32>(f32(vi & 1u) * 2.0 - 1.0, f32((vi >> 1u) & 1u) * 2.0 - 1.0);
    let grow = vec2<f32>(1.5, 1.5) / view.px_per_m + vec2<f32>(0.5 * inst.stroke.x, 0.5 * inst.stroke.x);
    let local = corner * (inst.half_size + grow);
    let c = cos(inst.angle_shape.x);
    let s = sin(inst.angle_shape.x);
    // Clockwise rotation by θ: (x, y) -> (x cos θ + y sin θ, -x sin θ + y cos θ).
    let rotated = vec2<f32>(local.x * c + local.y * s, -local.x * s + local.y * c);
    let world = inst.center + rotated;
    var out: VsOut;
    out.position = vec4<f32>(world * view.scale + view.offset, 0.0, 1.0);
    out.local_px = local * view.px_per_m;
    out.half_px = inst.half_size * view.px_per_m;
    out.color = inst.color;
    out.shape = inst.angle_shape.y;
    out.stroke_px = inst.stroke.x * view.px_per_m.x;
    return out;
}

@fragment
fn fs_main(in: VsOut) -> @location(0) vec4<f32> {
    var inside: f32;
    if (in.shape < 0.5) {
        // Signed distance to the rectangle's edge, in pixels.
        let d = in.half_px - abs(in.local_px);
        inside = min(d.x, d.y);
    } else {
        // Approximate distance to the ellipse's edge, in pixels.
        let r = max(in.half_px, vec2<f32>(0.5, 0.5));
        let q = in.local_px / r;
        inside = (1.0 - length(q)) * min(r.x, r.y);
    }
    var coverage: f32;
    if (in.stroke_px > 0.0) {
        // An outline: the band within half its width of the edge.
        let h = 0.5 * in.stroke_px;
        coverage = clamp(inside + h + 0.5, 0.0, 1.0) * clamp(h - inside + 0.5, 0.0, 1.0);
    } else {
        coverage = clamp(inside + 0.5, 0.0, 1.0);
    }
    return in.color * coverage;
}
