//! Kernels specialised to the one view a command renders (`glint render`
//! without AOVs) and to the shading terms a scene's materials and lights make
//! (glint-encoding's specialization.rs) render the very pixels and ray counts of
//! the kernels that serve every view and every term.

mod support;

use glint_encoding::gpu_types::View;
use glint_gpu::{Acceleration, RenderOptions};
use support::{parse, renderer};

// Small kernels (two kinds) keep the compiles quick; the mirror floor makes
// ray trees of different depths.
const SCENE: &str = r#"
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
"#;

#[test]
fn a_kernel_for_one_view_renders_it_as_the_kernel_for_every_view() {
    let scene = parse(SCENE);
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

#[test]
fn a_kernel_without_the_terms_a_scene_lacks_renders_what_the_kernel_with_them_renders() {
    // No highlight (k_s = 0), no checkerboard, a light that does not fade.
    let scene = parse(&SCENE.replace("ks = 0.3", "ks = 0").replace("reflect = 0.5", "reflect = 0.5\nks = 0"));
    let r = renderer();
    let mut prepared = r.prepare(&scene, scene.width, scene.height, Acceleration::Bvh).unwrap();
    let own = prepared.buffers.specialization;
    assert!(!own.highlights && !own.checker && !own.attenuation && own.secondary_rays && !own.refractions, "{own:?}");
    let options = RenderOptions { spp: 3, seed: 2, ..RenderOptions::default() };
    let mut render = |specialization| {
        prepared.buffers.specialization = specialization;
        r.render(&prepared.buffers, &options, &mut |_, _| {}).unwrap()
    };
    let (want, want_stats) = render(own.editable());
    let (got, got_stats) = render(own);
    assert!(got.linear == want.linear && got.display == want.display, "pixels differ");
    assert_eq!(got_stats, want_stats);
}
