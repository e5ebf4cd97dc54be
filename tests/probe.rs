//! The probe: one pixel's ray tree, recorded by the kernels that render the
//! image. Its contributions add up to the rendered pixel, its tree is the one
//! a hand count gives, and each of its rays hits what the CPU reference hits.
//! Also the teaching views that show the tree's depth and size per pixel.

mod support;

use std::path::Path;
use std::sync::OnceLock;

use glam::Vec3;
use glint_gpu::probe::{Prober, RayTree};
use glint_gpu::shaders::ShaderSource;
use glint_gpu::{Acceleration, RenderOptions};
use glint_scene::gpu_types::{View, NO_RAY, RAY_EYE, RAY_REFLECT, RAY_SHADOW};
use glint_scene::Scene;

fn prober() -> &'static Prober {
    static PROBER: OnceLock<Prober> = OnceLock::new();
    PROBER.get_or_init(|| Prober::new(support::renderer(), &ShaderSource::Embedded).unwrap_or_else(|e| panic!("{e}")))
}

fn probe(scene: &Scene, x: u32, y: u32) -> RayTree {
    let renderer = support::renderer();
    let prepared = renderer.prepare(scene, scene.width, scene.height, Acceleration::Bvh).unwrap();
    prober().probe(renderer, &prepared.buffers, x, y, &RenderOptions::default()).unwrap()
}

fn sum_of_contributions(scene: &Scene, tree: &RayTree) -> [f32; 3] {
    let cue = scene.depth_cue.map(|d| d.color.into());
    tree.rays.iter().map(|r| tree.contribution(r, scene.background.into(), cue)).fold([0.0; 3], |a, c| [a[0] + c[0], a[1] + c[1], a[2] + c[2]])
}

#[track_caller]
fn assert_adds_up(scene: &Scene, what: &str) {
    let (image, _) = support::render(scene);
    let (w, h) = (scene.width, scene.height);
    let mut secondary = 0;
    for (x, y) in [(w / 2, h / 2), (w / 3, h / 4), (2 * w / 3, 3 * h / 4), (w / 5, 2 * h / 3), (4 * w / 5, h / 3)] {
        let tree = probe(scene, x, y);
        assert!(!tree.truncated, "{what} ({x}, {y})");
        let pixel = image.linear_at(x, y);
        let sum = sum_of_contributions(scene, &tree);
        for c in 0..3 {
            let tol = 1e-5 * pixel[c].abs().max(1e-2);
            assert!((tree.color[c] - pixel[c]).abs() <= tol, "{what} ({x}, {y}): probe {:?}, render {pixel:?}", tree.color);
            assert!((sum[c] - pixel[c]).abs() <= tol, "{what} ({x}, {y}): contributions sum to {sum:?}, render {pixel:?}");
        }
        secondary += tree.rays.iter().filter(|r| r.kind != RAY_EYE).count();
    }
    assert!(secondary > 0, "{what}: no secondary rays probed");
}

#[test]
fn contributions_add_up_to_the_rendered_pixel() {
    for spec in ["balls:1", "mount:1", "gears:1", "teapot:2", "rings:1"] {
        let mut scene = glint_scene::load(Path::new(&format!("spd:{spec}"))).unwrap();
        (scene.width, scene.height) = (64, 64);
        assert_adds_up(&scene, spec);
    }
    for seed in 0..8 {
        let mut scene = glint_reference::random_scene(seed);
        (scene.width, scene.height) = (48, 36);
        assert_adds_up(&scene, &format!("random scene {seed}"));
    }
}

/// One mirror sphere, one light, a dark background: the tree at the centre is
/// countable by hand.
fn mirror_scene() -> Scene {
    support::parse(
        r#"
[image]
width = 33
height = 33
background = [0.1, 0.2, 0.3]
[camera]
eye = [0, 0, 5]
look_at = [0, 0, 0]
fov = 30
[[light]]
type = "point"
position = [0, 0, 10]
[material.mirror]
color = 0.5
kd = 0.5
ks = 0
reflect = 0.8
[[object]]
type = "sphere"
center = [0, 0, 0]
radius = 1
material = "mirror"
"#,
    )
}

#[test]
fn a_mirror_sphere_gives_the_tree_counted_by_hand() {
    let scene = mirror_scene();
    let tree = probe(&scene, 16, 16);
    // The eye ray hits the sphere head on; its shadow ray reaches the light;
    // the reflected ray goes straight back past the eye and misses.
    let kinds: Vec<(u32, u32, u32)> = tree.rays.iter().map(|r| (r.kind, r.parent, r.depth)).collect();
    assert_eq!(kinds, vec![(RAY_EYE, NO_RAY, 1), (RAY_SHADOW, 0, 1), (RAY_REFLECT, 0, 2)], "{tree:#?}");
    let (eye, shadow, reflected) = (&tree.rays[0], &tree.rays[1], &tree.rays[2]);
    assert!((eye.t - 4.0).abs() < 1e-5, "the eye is 4 from the sphere: {}", eye.t);
    assert_eq!(eye.object, 0);
    assert!((shadow.n_dot_l - 1.0).abs() < 1e-5 && (shadow.distance - 9.0).abs() < 1e-4);
    assert!((reflected.weight[0] - 0.8).abs() < 1e-6 && reflected.object == NO_RAY);
    // I = k_d·O_d·I_l·N·L = 0.5·0.5·1·1 at the hit, plus 0.8 × the background.
    let want = [0.25 + 0.8 * 0.1, 0.25 + 0.8 * 0.2, 0.25 + 0.8 * 0.3];
    for c in 0..3 {
        assert!((tree.color[c] - want[c]).abs() < 1e-5, "{:?} vs {want:?}", tree.color);
    }
}

/// The probed rays hit what the f64 reference finds along the same rays.
#[test]
fn each_probed_ray_hits_what_the_cpu_reference_hits() {
    for seed in 0..6 {
        let mut scene = glint_reference::random_scene(seed);
        (scene.width, scene.height) = (40, 30);
        let reference = glint_reference::Tracer::new(&scene);
        for (x, y) in [(20, 15), (10, 20), (30, 8)] {
            let tree = probe(&scene, x, y);
            for ray in tree.rays.iter().filter(|r| r.kind != RAY_SHADOW) {
                let (o, d) = (Vec3::from(ray.origin).as_dvec3(), Vec3::from(ray.dir).as_dvec3());
                let hit = reference.nearest_hit(o, d, 0.0, f64::INFINITY);
                match hit {
                    Some(h) if ray.object != NO_RAY => {
                        // Grazing rays may meet a different surface in f32; the
                        // same object at the same distance is the rule.
                        if (h.t - f64::from(ray.t)).abs() < 1e-3 * h.t.max(1.0) {
                            assert_eq!(h.object, ray.object, "seed {seed} ({x}, {y})");
                        }
                    }
                    None => assert_eq!(ray.object, NO_RAY, "seed {seed} ({x}, {y}): the reference misses"),
                    Some(h) => assert!(h.t > 1e6 || ray.depth > 1, "seed {seed} ({x}, {y}): the reference hits at {}", h.t),
                }
            }
        }
    }
}

#[test]
fn the_teaching_views_show_the_tree_depth_and_ray_count() {
    let scene = mirror_scene();
    let view = |view| support::render_options(&scene, Acceleration::Bvh, RenderOptions { view, ..RenderOptions::default() }).0;
    let (depth, count) = (view(View::RayDepth), view(View::RayCount));
    // The centre: eye ray, its shadow ray and the reflected ray, two levels deep.
    assert_eq!((depth.linear_at(16, 16)[0], count.linear_at(16, 16)[0]), (2.0, 3.0));
    // A corner sees only the background: one eye ray, one level.
    assert_eq!((depth.linear_at(0, 0)[0], count.linear_at(0, 0)[0]), (1.0, 1.0));
}
