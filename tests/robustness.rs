//! Numerical robustness on the GPU: no NaN or infinity reaches an image, large
//! coordinates do not cause self-intersection acne, and rays that graze
//! surfaces or pass exactly through edges and vertices behave.

mod support;

use glam::Vec3;
use glint_encoding::gpu_types::View;
use glint_gpu::{Acceleration, RenderOptions};
use glint_scene::{Attenuation, LightKind, Projection, Scene};
use support::{parse, render};

#[test]
fn no_nan_or_infinite_pixel_in_random_scenes() {
    for seed in 0..40 {
        let scene = glint_reference::random_scene(1000 + seed);
        let (image, _) = render(&scene);
        for (i, p) in image.linear.iter().chain(&image.display).enumerate() {
            assert!(p.iter().all(|c| c.is_finite()), "seed {seed}: pixel {i} is {p:?}");
        }
        assert!(image.display.iter().all(|p| p[..3].iter().all(|c| (0.0..=1.0).contains(c))));
    }
}

/// Everything positional multiplied by `s`: the same picture at another scale.
fn scaled(scene: &Scene, s: f32) -> Scene {
    let mut out = scene.clone();
    out.camera.eye *= s;
    out.camera.look_at *= s;
    if let Projection::Orthographic { height } = &mut out.camera.projection {
        *height *= s;
    }
    for light in &mut out.lights {
        if let LightKind::Point { position } = &mut light.kind {
            *position *= s;
        }
    }
    for shape in out.objects.iter_mut().flat_map(|o| o.shapes.iter_mut()) {
        *shape = shape.scaled(s);
    }
    for checker in out.materials.iter_mut().filter_map(|m| m.checker.as_mut()) {
        checker.size *= s;
    }
    out
}

#[test]
fn a_scene_scaled_by_ten_thousand_renders_like_the_original() {
    for seed in 0..6 {
        let mut scene = glint_reference::random_scene(2000 + seed);
        // Distance-dependent terms would rightly change with scale.
        scene.depth_cue = None;
        scene.lights.iter_mut().for_each(|l| l.attenuation = Attenuation::None);
        let (small, _) = render(&scene);
        let (large, _) = render(&scaled(&scene, 1e4));
        let differing = small
            .display
            .iter()
            .zip(&large.display)
            .filter(|(a, b)| (0..3).any(|c| (a[c] - b[c]).abs() > 4.0 / 255.0))
            .count();
        // Silhouettes may move by a rounding; acne would spot whole surfaces.
        assert!(differing * 100 <= small.display.len(), "seed {seed}: {differing} pixels differ at 1e4 scale");
    }
}

#[test]
fn rays_through_shared_edges_and_vertices_find_no_holes() {
    // A quad of two triangles and a fan of eight triangles around a vertex, seen
    // orthographically so that pixel centres fall exactly on the shared edges
    // and on the centre vertex.
    let scene = parse(
        r#"
[image]
width = 16
height = 16
background = [1, 0, 0]
[camera]
type = "orthographic"
eye = [0, 0, 5]
look_at = [0, 0, 0]
height = 4
[ambient]
intensity = 1
[material.grey]
color = 0.5
ka = 1
kd = 0
ks = 0
[[object]]
type = "triangle"
vertices = [[-2, -2, 0], [2, -2, 0], [2, 2, 0]]
material = "grey"
[[object]]
type = "triangle"
vertices = [[-2, -2, 0], [2, 2, 0], [-2, 2, 0]]
material = "grey"
"#,
    );
    // Pixel centres are at −2 + (i + 0.5)/4: none is at 0, so also shift the
    // camera by half a pixel to put centres on the diagonal and the origin.
    let mut on_grid = scene.clone();
    on_grid.camera.eye += Vec3::new(0.125, 0.125, 0.0);
    on_grid.camera.look_at += Vec3::new(0.125, 0.125, 0.0);
    for s in [scene, on_grid] {
        let (image, _) = render(&s);
        for y in 1..15 {
            for x in 1..15 {
                let c = image.linear_at(x, y);
                assert!((c[0] - 0.5).abs() < 1e-6 && c[1] > 0.49, "hole at ({x}, {y}): {c:?}");
            }
        }
    }
}

#[test]
fn grazing_rays_give_finite_results() {
    // The camera looks exactly along a polygon's plane and along a cylinder's
    // surface line: rays parallel to surfaces must neither produce NaN nor hit
    // spuriously far away.
    let scene = parse(
        r#"
[image]
width = 33
height = 33
background = [0, 0, 1]
[camera]
type = "orthographic"
eye = [0, 0, 10]
look_at = [0, 0, 0]
height = 4
[ambient]
intensity = 1
[[light]]
type = "point"
position = [0, 0, 10]
[[object]]
type = "polygon"
vertices = [[-1, 0, -5], [1, 0, -5], [1, 0, 5], [-1, 0, 5]]
[[object]]
type = "cylinder"
base = [1.5, -1, -5]
apex = [1.5, -1, 5]
base_radius = 0.25
[[object]]
type = "sphere"
center = [-1.5, -1, 0]
radius = 0.25
"#,
    );
    let (image, stats) = render(&scene);
    assert!(image.linear.iter().all(|p| p.iter().all(|c| c.is_finite())));
    let (depth, _) = support::render_options(&scene, Acceleration::Bvh, RenderOptions { view: View::Depth, ..Default::default() });
    // The polygon is seen edge-on: its row of pixels sees no surface.
    for x in 0..11 {
        let d = depth.linear_at(x, 16)[0];
        assert!(d > 1e30, "edge-on polygon hit at column {x}: {d}");
    }
    assert!(stats.eye_hit > 0);
}
