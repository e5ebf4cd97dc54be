//! A kernel specialised to the one view a command renders (glint-scene's
//! specialization.rs; `glint render` without AOVs) renders the very pixels and
//! ray counts of the kernel that serves every view.

mod support;

use glint_gpu::{Acceleration, RenderOptions};
use glint_scene::gpu_types::View;
use support::{parse, renderer};

#[test]
fn a_kernel_for_one_view_renders_it_as_the_kernel_for_every_view() {
    // Small kernels (two kinds) keep the compiles quick; the mirror floor
    // makes ray trees of different depths.
    let scene = parse(
        r#"
[image]
width = 24
height = 16
[camera]
eye = [0, 1, 5]
look_at = [0, 0, 0]
fov = 40
[[light]]
type = "point"
position = [3, 4, 5]
[material.white]
color = 0.8
kd = 0.9
ks = 0.3
[material.mirror]
color = 0.5
reflect = 0.5
[[object]]
type = "sphere"
center = [0, 0, 0]
radius = 1
material = "white"
[[object]]
type = "triangle"
vertices = [[-3, -1, -3], [3, -1, -3], [0, -1, 3]]
material = "mirror"
"#,
    );
    let r = renderer();
    let mut prepared = r.prepare(&scene, scene.width, scene.height, Acceleration::Bvh).unwrap();
    let every_view = prepared.buffers.specialization;
    assert_eq!(every_view.view, None);
    for view in View::ALL {
        let spp = if view.is_primary_only() { 1 } else { 3 };
        let options = RenderOptions { view, spp, seed: 5, view_scale: prepared.view_scale(view), ..RenderOptions::default() };
        let mut render = |specialization| {
            prepared.buffers.specialization = specialization;
            r.render(&prepared.buffers, &options, &mut |_, _| {}).unwrap()
        };
        let (want, want_stats) = render(every_view);
        let (got, got_stats) = render(every_view.for_views(&[view]));
        assert!(got.linear == want.linear && got.display == want.display, "{view:?}: pixels differ");
        assert_eq!(got_stats, want_stats, "{view:?}: ray counts differ");
        assert!(want.linear.iter().any(|p| p[..3] != want.linear[0][..3]), "{view:?}: the image should not be flat");
    }
}
