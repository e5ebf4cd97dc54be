//! Anti-aliasing, determinism, tiling, AOVs and float output, on the GPU.

mod support;

use glam::DVec3;
use glint_encoding::gpu_types::{Filter, View};
use glint_gpu::{Acceleration, Bits, RenderOptions};
use support::{parse, render_options};

/// A white sphere on black, ambient only: a hard silhouette to anti-alias.
fn edge_scene() -> glint_scene::Scene {
    parse(
        r#"
[image]
width = 48
height = 48
[camera]
eye = [0, 0, 5]
look_at = [0, 0, 0]
fov = 30
[ambient]
intensity = 1
[material.white]
color = 1
ka = 1
kd = 0
ks = 0
[[object]]
type = "sphere"
center = [0.1, 0.05, 0]
radius = 1
material = "white"
"#,
    )
}

fn options(spp: u32, seed: u32, filter: Filter) -> RenderOptions {
    RenderOptions { spp, seed, filter, ..RenderOptions::default() }
}

fn mean_abs_diff(a: &[[f32; 4]], b: &[[f32; 4]]) -> f64 {
    a.iter().zip(b).map(|(p, q)| f64::from((p[0] - q[0]).abs())).sum::<f64>() / a.len() as f64
}

#[test]
fn anti_aliasing_lowers_edge_error_against_a_64_spp_reference() {
    let scene = edge_scene();
    let (reference, _) = render_options(&scene, Acceleration::Bvh, options(64, 1000, Filter::Box));
    let (one, _) = render_options(&scene, Acceleration::Bvh, options(1, 0, Filter::Box));
    let (sixteen, _) = render_options(&scene, Acceleration::Bvh, options(16, 0, Filter::Box));
    let (e1, e16) = (mean_abs_diff(&one.linear, &reference.linear), mean_abs_diff(&sixteen.linear, &reference.linear));
    assert!(e16 < e1 / 3.0, "1 spp error {e1:.5}, 16 spp error {e16:.5}");
    // Edge pixels take intermediate values; at 1 spp every pixel is 0 or 1.
    let partial = sixteen.linear.iter().filter(|p| p[0] > 0.05 && p[0] < 0.95).count();
    assert!(partial > 40, "only {partial} partially covered pixels");
    assert!(one.linear.iter().all(|p| p[0] < 1e-6 || p[0] > 1.0 - 1e-6));
    // The tent filter blurs wider: more intermediate pixels than the box.
    let (tent, _) = render_options(&scene, Acceleration::Bvh, options(16, 0, Filter::Tent));
    let tent_partial = tent.linear.iter().filter(|p| p[0] > 0.05 && p[0] < 0.95).count();
    assert!(tent_partial > partial, "tent {tent_partial} vs box {partial}");
}

#[test]
fn the_same_seed_gives_identical_bytes() {
    let scene = parse(&std::fs::read_to_string(concat!(env!("CARGO_MANIFEST_DIR"), "/scenes/showcase.toml")).unwrap());
    let scene = glint_scene::Scene { width: 64, height: 40, ..scene };
    let dir = tempfile::tempdir().unwrap();
    let mut files = Vec::new();
    for (i, seed) in [7, 7, 8].into_iter().enumerate() {
        let (image, _) = render_options(&scene, Acceleration::Bvh, options(4, seed, Filter::Tent));
        let path = dir.path().join(format!("{i}.png"));
        glint_gpu::write_image(&image, &path, Bits::Eight).unwrap();
        files.push(std::fs::read(&path).unwrap());
    }
    assert_eq!(files[0], files[1], "same seed, different bytes");
    assert_ne!(files[0], files[2], "a different seed should jitter differently");
}

#[test]
fn tiled_and_single_dispatch_renders_are_identical() {
    let scene = parse(&std::fs::read_to_string(concat!(env!("CARGO_MANIFEST_DIR"), "/scenes/showcase.toml")).unwrap());
    let scene = glint_scene::Scene { width: 90, height: 50, ..scene };
    let base = options(2, 3, Filter::Box);
    let (single, s1) = render_options(&scene, Acceleration::Bvh, RenderOptions { band_rows: Some(50), ..base });
    let (tiled, s2) = render_options(&scene, Acceleration::Bvh, RenderOptions { band_rows: Some(8), ..base });
    let (adaptive, s3) = render_options(&scene, Acceleration::Bvh, base);
    assert_eq!(single.linear, tiled.linear);
    assert_eq!(single.linear, adaptive.linear);
    assert_eq!((s1, s1), (s2, s3));
    // Bands that are no multiple of the 8-row workgroup must not trace the rows
    // their last workgroups reach into: every pixel gets each sample once.
    for rows in [5, 13] {
        let (odd, stats) = render_options(&scene, Acceleration::Bvh, RenderOptions { band_rows: Some(rows), ..base });
        assert_eq!(stats.eye_hit + stats.eye_miss, 90 * 50 * 2, "bands of {rows} rows");
        assert_eq!(single.linear, odd.linear, "bands of {rows} rows");
    }
}

#[test]
fn depth_aov_at_the_centre_is_eye_distance_minus_radius() {
    let scene = parse(
        r#"
[image]
width = 31
height = 21
[camera]
eye = [1, 2, 9]
look_at = [0.5, -0.3, 1]
fov = 35
[[object]]
type = "sphere"
center = [0.5, -0.3, 1]
radius = 1.25
"#,
    );
    let (image, _) = render_options(&scene, Acceleration::Bvh, RenderOptions { view: View::Depth, ..RenderOptions::default() });
    let image = image.with_misses_at_infinity();
    let expected = (DVec3::new(1.0, 2.0, 9.0) - DVec3::new(0.5, -0.3, 1.0)).length() - 1.25;
    let got = f64::from(image.linear_at(15, 10)[0]);
    assert!(((got - expected) / expected).abs() < 1e-5, "depth {got}, expected {expected}");
    assert_eq!(image.linear_at(0, 0)[0], f32::INFINITY, "a miss has infinite depth");
}

#[test]
fn normal_and_id_aovs_at_chosen_pixels() {
    let scene = parse(
        r#"
[image]
width = 40
height = 40
[camera]
eye = [0, 0, 6]
look_at = [0, 0, 0]
fov = 40
[[object]]
type = "polygon"
vertices = [[-9, -9, -3], [9, -9, -3], [9, 9, -3], [-9, 9, -3]]
[[object]]
type = "sphere"
center = [0, 0, 0]
radius = 1.5
"#,
    );
    let (normals, _) = render_options(&scene, Acceleration::Bvh, RenderOptions { view: View::Normal, ..RenderOptions::default() });
    let (ids, _) = render_options(&scene, Acceleration::Bvh, RenderOptions { view: View::Id, ..RenderOptions::default() });
    for (x, y) in [(20, 20), (15, 22), (24, 14), (18, 25)] {
        let ray = scene.camera.ray(40, 40, f64::from(x) + 0.5, f64::from(y) + 0.5).unwrap();
        let b = ray.origin.dot(ray.direction);
        let t = -b - (b * b - (ray.origin.length_squared() - 2.25)).sqrt();
        let n = (ray.origin + t * ray.direction).normalize();
        support::assert_close(normals.linear_at(x, y), n.to_array(), 1e-4, &format!("normal at ({x}, {y})"));
        assert_eq!(ids.linear_at(x, y)[0], 1.0, "sphere id at ({x}, {y})");
    }
    support::assert_close(normals.linear_at(1, 1), [0.0, 0.0, 1.0], 1e-5, "the back wall faces the camera");
    assert_eq!(ids.linear_at(1, 1)[0], 0.0);
}

#[test]
fn pfm_and_exr_round_trip_the_linear_values() {
    let scene = edge_scene();
    let (image, _) = render_options(&scene, Acceleration::Bvh, options(4, 0, Filter::Box));
    let image = glint_gpu::Image {
        // Values above 1 must survive a float format.
        linear: image.linear.iter().map(|p| [p[0] * 3.5, p[1] * 0.25, p[2] + 0.125, 1.0]).collect(),
        ..image
    };
    let dir = tempfile::tempdir().unwrap();
    let pfm = dir.path().join("x.pfm");
    glint_gpu::write_image(&image, &pfm, Bits::Eight).unwrap();
    let (w, h, rgb) = glint_gpu::read_pfm(&std::fs::read(&pfm).unwrap()).unwrap();
    assert_eq!((w, h), (48, 48));
    for (a, b) in rgb.iter().zip(&image.linear) {
        assert_eq!(*a, [b[0], b[1], b[2]]);
    }
    let exr = dir.path().join("x.exr");
    glint_gpu::write_image(&image, &exr, Bits::Eight).unwrap();
    let back = image::open(&exr).unwrap().to_rgb32f();
    assert_eq!(back.dimensions(), (48, 48));
    for (a, b) in back.pixels().zip(&image.linear) {
        assert_eq!(a.0, [b[0], b[1], b[2]]);
    }
    let png16 = dir.path().join("x.png");
    glint_gpu::write_image(&image, &png16, Bits::Sixteen).unwrap();
    assert_eq!(image::open(&png16).unwrap().color(), image::ColorType::Rgb16);
}
