//! The ray tree as the lecture reads it (shaders/lib/ray_tree.wgsl: an
//! explicit stack of pending rays, a trace step, shading that casts its own
//! shadow rays) and as lavapipe's profile walks it (shaders/fast/ray_tree.wgsl:
//! one loop, one call of the BVH walk; fast/push_rays.wgsl and
//! flush_counts.wgsl: loops over bit masks) trace the same rays in the same order:
//! the same pixels and ray counts in every view, bit for bit, and the same
//! probed trees, for every kind of primitive, plain and tinted shadows,
//! reflection, refraction, total internal reflection, depth cueing and the
//! unturned normals of grading's diagnosis.

mod support;

use std::path::Path;

use glint_encoding::gpu_types::View;
use glint_gpu::probe::Prober;
use glint_gpu::shaders::ShaderSource;
use glint_gpu::{Acceleration, DeviceProfile, RenderOptions, Renderer, Tuning};
use glint_scene::Scene;

/// Width and height odd, so that workgroups overhang the image's edges.
const SIZE: (u32, u32) = (41, 29);

/// A renderer on the test device with lavapipe's choices but the plain ray
/// tree and loops.
fn plain_tree_renderer() -> Renderer {
    let gpu = support::gpu();
    let profile = DeviceProfile { one_walk_tree: false, mask_loops: false, ..*support::renderer().profile() };
    Renderer::with_profile(gpu.device.clone(), gpu.queue.clone(), &ShaderSource::Embedded, profile).unwrap_or_else(|e| panic!("{e}"))
}

/// Returns the reflected and refracted rays traced.
fn assert_one_walk_traces_as_the_plain_tree(plain: &Renderer, scene: &Scene, what: &str) -> [u64; 2] {
    let mut scene = scene.clone();
    (scene.width, scene.height) = SIZE;
    let walked = support::renderer();
    let prepare = |r: &Renderer| r.prepare(&scene, SIZE.0, SIZE.1, Acceleration::Bvh).unwrap_or_else(|e| panic!("{what}: {e}"));
    let (mut prepared, plain_prepared) = (prepare(walked), prepare(plain));
    let lavapipe_shapes = |t: Tuning| t.one_walk_tree() && t.mask_loops();
    let plain_shapes = |t: Tuning| !t.one_walk_tree() && !t.mask_loops();
    assert!(lavapipe_shapes(prepared.buffers.tuning()) && plain_shapes(plain_prepared.buffers.tuning()), "{what}: the profiles' trees");
    let mut secondary = [0; 2];
    for view in View::ALL {
        let options = RenderOptions { view, spp: 2, seed: 7, view_scale: prepared.view_scale(view), ..Default::default() };
        let mut render = |lavapipe: bool| {
            prepared.buffers.retune(prepared.buffers.tuning().with_one_walk_tree(lavapipe).with_mask_loops(lavapipe));
            walked.render(&prepared.buffers, &options, &mut |_, _| {}).unwrap_or_else(|e| panic!("{what}: {e}"))
        };
        let ((one_walk, one_walk_stats), (recursive, recursive_stats)) = (render(true), render(false));
        let case = format!("{what}, {view:?} view");
        support::assert_images_equal(&recursive.linear, &one_walk.linear, 0, &case);
        assert_eq!(recursive_stats, one_walk_stats, "{case}");
        secondary = [secondary[0] + recursive_stats.reflect, secondary[1] + recursive_stats.refract];
    }
    prepared.buffers.retune(prepared.buffers.tuning().with_one_walk_tree(true).with_mask_loops(true));
    let (walked_prober, plain_prober) = (Prober::new(walked, &ShaderSource::Embedded).unwrap(), Prober::new(plain, &ShaderSource::Embedded).unwrap());
    for (x, y) in [(SIZE.0 / 2, SIZE.1 / 2), (SIZE.0 / 3, SIZE.1 * 2 / 3), (SIZE.0 * 3 / 4, SIZE.1 / 4), (0, SIZE.1 - 1)] {
        let options = RenderOptions::default();
        let one_walk = walked_prober.probe(walked, &prepared.buffers, x, y, &options).unwrap_or_else(|e| panic!("{what}: {e}"));
        let recursive = plain_prober.probe(plain, &plain_prepared.buffers, x, y, &options).unwrap_or_else(|e| panic!("{what}: {e}"));
        assert_eq!((recursive.color, recursive.truncated), (one_walk.color, one_walk.truncated), "{what}, probe of ({x}, {y})");
        assert_eq!(recursive.rays, one_walk.rays, "{what}, probe of ({x}, {y})");
    }
    secondary
}

#[test]
fn the_plain_ray_tree_traces_what_the_one_walk_traces() {
    let plain = plain_tree_renderer();
    let mut secondary = [0; 2];
    let mut check = |scene: &Scene, what: &str| {
        let [reflect, refract] = assert_one_walk_traces_as_the_plain_tree(&plain, scene, what);
        secondary = [secondary[0] + reflect, secondary[1] + refract];
    };
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("scenes");
    // primitives: every kind, smooth triangles; showcase: mirrors, glass,
    // tinted shadows, a checkered plane, depth cueing, highlights of every
    // kind; total_internal_reflection and glass: refraction and Fresnel.
    for file in ["gallery/primitives.toml", "showcase.toml", "gallery/total_internal_reflection.toml", "gallery/glass.toml", "gallery/shadows.toml"] {
        let scene = glint_scene::load(&dir.join(file)).unwrap_or_else(|e| panic!("{file}: {e}"));
        check(&scene, file);
    }
    for name in ["balls:1", "tree:2", "gears:1"] {
        let scene = glint_scene::load(Path::new(&format!("spd:{name}"))).unwrap_or_else(|e| panic!("{e}"));
        check(&scene, name);
    }
    for seed in 0..2 {
        let mut scene = glint_reference::random_scene(seed);
        check(&scene, &format!("random scene {seed}"));
        scene.render.turn_normals = false;
        check(&scene, &format!("random scene {seed}, normals unturned"));
    }
    let lambert = glint_scene::load(&dir.join("gallery/lambert.toml")).unwrap();
    check(&lambert, "lambert.toml, eye rays alone");
    assert!(secondary[0] > 0 && secondary[1] > 0, "reflected and refracted rays traced: {secondary:?}");
}
