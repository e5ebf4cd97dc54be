// The probe kernel: one pixel's ray tree, traced by the same code as the
// trace kernel (lib/ray_tree.wgsl, lib/shade.wgsl) and recorded ray by ray
// with every term it adds, for `glint probe` and the viewer's inspector.
// The tree is recorded by kernels/probe_notes.wgsl, which stands in for the
// lib/notes.wgsl that every other kernel composes.
// import: bindings kernels/probe_notes ray_tree

@compute @workgroup_size(1)
fn probe_main() {
    let pixel = dispatch.origin;
    probe.count = 0u;
    probe.truncated = 0u;
    probe.color = trace_pixel(pixel);
}
