//! BVH traversal on the GPU against brute force (every ray tests every
//! primitive): identical images, depths and ray counts, on generated SPD scenes and
//! on random scenes of every primitive kind.

mod support;

use glint_encoding::gpu_types::View;
use glint_gpu::{Acceleration, Image, RayStats, RenderOptions};
use glint_scene::Scene;
use support::{render_options, render_with};

/// Renders `scene` shaded and as depth with the BVH and by brute force, and
/// asserts both agree to the bit. Returns the BVH's shaded image and counts.
fn assert_bvh_matches_brute_force(scene: &Scene, what: &str) -> (Image, RayStats) {
    let (bvh, bvh_stats) = render_with(scene, Acceleration::Bvh);
    let (brute, brute_stats) = render_with(scene, Acceleration::BruteForce);
    let depth = |a| render_options(scene, a, RenderOptions { view: View::Depth, ..Default::default() }).0.linear;
    support::assert_images_equal(&depth(Acceleration::Bvh), &depth(Acceleration::BruteForce), 0, &format!("{what} depth"));
    // Coincident surfaces (teapot_s1 has some) tie at equal t: the kernel gives
    // them to the lower object id, so visiting order cannot change a pixel.
    support::assert_images_equal(&bvh.linear, &brute.linear, 0, &format!("{what} colour"));
    assert_eq!(bvh_stats, brute_stats, "{what}");
    (bvh, bvh_stats)
}

/// Small SPD scenes, and every primitive kind shows up.
#[test]
fn spd_scenes_render_identically_with_and_without_the_bvh() {
    for name in ["balls:1", "gears:1", "mount:1", "rings:1", "teapot:1", "teapot:2", "tetra:2", "tree:2", "jacks:1", "shells:1", "lattice:1", "sombrero:1", "nurbtst:1"] {
        let path = std::path::PathBuf::from(format!("spd:{name}"));
        let mut scene = glint_scene::load(&path).unwrap_or_else(|e| panic!("{e}"));
        (scene.width, scene.height) = (48, 48);
        let (bvh, bvh_stats) = assert_bvh_matches_brute_force(&scene, name);
        let distinct: std::collections::HashSet<[u32; 3]> =
            bvh.linear.iter().map(|p| [p[0].to_bits(), p[1].to_bits(), p[2].to_bits()]).collect();
        assert!(distinct.len() > 20, "{name}: only {} colours", distinct.len());
        assert!(bvh_stats.eye_hit > 0, "{name}: nothing hit");
    }
}

/// The CPU reference's random scenes (spheres, triangles, convex and concave
/// polygons, cones and cylinders, mirrors and glass, at random scales), with
/// their reflected, refracted and shadow rays.
#[test]
fn random_scenes_render_identically_with_and_without_the_bvh() {
    let mut secondary = 0;
    for seed in 0..20 {
        let scene = glint_reference::random_scene(seed);
        let (_, stats) = assert_bvh_matches_brute_force(&scene, &format!("seed {seed}"));
        assert!(stats.eye_hit > 0, "seed {seed}: nothing hit");
        secondary += stats.shadow + stats.reflect + stats.refract;
    }
    assert!(secondary > 0, "no secondary rays: the test would not exercise them");
}
