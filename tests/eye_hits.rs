//! Eye hits (docs/decisions/059-eye-hits-from-the-eye-tiles.md): where a view
//! is binned into eye tiles, the trace kernel shades each pixel centre's eye
//! ray from the hit the primary kernel's eye tiles found, instead of walking
//! the BVH for it again. Every view of the ray tree, and the ray counts, are
//! held to the plain profile's, bit for bit: whole frames, bands that start
//! off the tiles' corners, and samples off the pixel centres.

mod support;

use glint_encoding::gpu_types::View;
use glint_gpu::shaders::Kernel;
use glint_gpu::{Acceleration, RenderOptions};
use glint_scene::Scene;

/// Width and height odd, so the last column and row of blocks hang over the edge.
const SIZE: (u32, u32) = (37, 27);

fn sized(mut scene: Scene) -> Scene {
    (scene.width, scene.height) = SIZE;
    scene
}

/// Mirrors and glass (gears), mirrors and shadows from three lights (balls),
/// glass over a fractal landscape (mount), a room of facing mirrors, and an
/// orthographic camera.
fn scenes() -> Vec<(&'static str, Scene)> {
    let load = |name: &str| sized(glint_scene::load(std::path::Path::new(name)).unwrap_or_else(|e| panic!("{name}: {e}")));
    let gallery = |file: &str| std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("scenes/gallery").join(file).display().to_string();
    vec![
        ("gears", load("spd:gears:1")),
        ("balls", load("spd:balls:1")),
        ("mount", load("spd:mount:1")),
        ("mirror", load(&gallery("mirror.toml"))),
        ("orthographic", load(&gallery("orthographic.toml"))),
    ]
}

#[test]
fn the_ray_tree_shaded_from_the_eye_tiles_hits_is_the_plain_profiles() {
    let renderer = support::renderer();
    for (what, scene) in scenes() {
        let prepared = renderer.prepare(&scene, SIZE.0, SIZE.1, Acceleration::Bvh).unwrap_or_else(|e| panic!("{what}: {e}"));
        assert!(prepared.buffers.tuning().eye_tiles(), "{what}: binned into eye tiles on lavapipe");
        let plain = support::plain_renderer();
        let plain_prepared = plain.prepare(&scene, SIZE.0, SIZE.1, Acceleration::Bvh).unwrap_or_else(|e| panic!("{what}: {e}"));
        // Whole frames; bands of rows from tile corners; bands of three rows,
        // most of which start off the corners and walk their own eye rays;
        // and four jittered samples a pixel, none through its centre.
        for (band_rows, spp) in [(None, 1), (Some(4), 1), (Some(3), 1), (None, 4)] {
            for view in [View::Shaded, View::RayDepth, View::RayCount] {
                let options = RenderOptions { view, band_rows, spp, seed: 7, ..Default::default() };
                let what = format!("{what}, {view:?} view, bands of {band_rows:?} rows, {spp} samples");
                let (image, stats) = renderer.render(&prepared.buffers, &options, &mut |_, _| {}).unwrap_or_else(|e| panic!("{what}: {e}"));
                let (want, want_stats) = plain.render(&plain_prepared.buffers, &options, &mut |_, _| {}).unwrap_or_else(|e| panic!("{what}: {e}"));
                support::assert_images_equal(&image.linear, &want.linear, 0, &what);
                assert_eq!(stats, want_stats, "{what}: each eye ray counted once");
                assert!(stats.eye_hit > 0 && stats.shadow > 0, "{what}: the scene is in view and lit");
            }
        }
    }
    let traced_from_eye_hits = renderer.pipelines_created().iter().any(|(kernel, _, tuning)| *kernel == Kernel::Trace && tuning.eye_hits());
    assert!(traced_from_eye_hits, "no trace kernel took the eye tiles' hits: {:?}", renderer.pipelines_created());
}
