//! The kernels read the scene's arrays from storage buffers or from textures
//! (`SceneArrays`: textures for kernels lavapipe compiles without its
//! optimisation passes), and a BVH that fits from uniform buffers
//! (`Tuning::uniform_tree`). All must trace the same bits: every view,
//! ray packets and single rays, every kind of primitive, shadows, reflection
//! and refraction, and a scene whose arrays fill more than one row of texels.

mod support;

use glint_encoding::gpu_types::{View, UNIFORM_TREE_RECORDS};
use glint_gpu::shaders::{SceneArrays, ShaderSource};
use glint_gpu::{Acceleration, RenderOptions, Renderer};
use glint_scene::Scene;

/// Scenes of every kind of primitive (smooth triangles among them), tinted
/// shadows, mirrors, glass and a checkered plane.
fn gallery() -> Vec<(&'static str, Scene)> {
    let dir = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("scenes");
    ["gallery/primitives.toml", "showcase.toml"]
        .map(|file| (file, glint_scene::load(&dir.join(file)).unwrap_or_else(|e| panic!("{file}: {e}"))))
        .into()
}

fn renderer(arrays: SceneArrays) -> Renderer {
    let gpu = support::gpu();
    Renderer::reading(gpu.device.clone(), gpu.queue.clone(), &ShaderSource::Embedded, arrays).unwrap_or_else(|e| panic!("{e}"))
}

fn assert_textures_trace_as_buffers(buffers: &Renderer, textures: &Renderer, scene: &Scene, what: &str) {
    let mut scene = scene.clone();
    (scene.width, scene.height) = (33, 25);
    let prepare = |r: &Renderer| r.prepare(&scene, scene.width, scene.height, Acceleration::Bvh).unwrap_or_else(|e| panic!("{e}"));
    let (mut from_buffers, mut from_textures) = (prepare(buffers), prepare(textures));
    for view in View::ALL {
        for packets in [false, true] {
            let options = RenderOptions { view, ..Default::default() };
            let render = |renderer: &Renderer, prepared: &mut glint_gpu::Prepared| {
                prepared.buffers.retune(prepared.buffers.tuning().with_packets(packets));
                renderer.render(&prepared.buffers, &options, &mut |_, _| {}).unwrap_or_else(|e| panic!("{e}"))
            };
            let (a, a_stats) = render(buffers, &mut from_buffers);
            let (b, b_stats) = render(textures, &mut from_textures);
            let case = format!("{what}, {view:?} view, packets {packets}");
            support::assert_images_equal(&b.linear, &a.linear, 0, &case);
            assert_eq!(b_stats, a_stats, "{case}");
        }
    }
}

#[test]
fn textures_and_buffers_trace_the_same_bits() {
    let (buffers, textures) = (renderer(SceneArrays::Buffers), renderer(SceneArrays::Textures));
    // tetra:4 has 256 triangles, a row of texels exactly; mount:5 triangles
    // and spheres, three rows of BVH records and nine of primitives; gears:
    // polygons (points); tree: cones and spheres; rings: cylinders.
    for name in ["tetra:4", "mount:5", "gears:1", "balls:1", "tree:2", "rings:1"] {
        let scene = glint_scene::load(std::path::Path::new(&format!("spd:{name}"))).unwrap_or_else(|e| panic!("{e}"));
        assert_textures_trace_as_buffers(&buffers, &textures, &scene, name);
    }
    assert_textures_trace_as_buffers(&buffers, &textures, &glint_reference::random_scene(1), "random scene 1");
    for (name, scene) in gallery() {
        assert_textures_trace_as_buffers(&buffers, &textures, &scene, name);
    }
}

/// Each kernel that walks the tree, from either kind of arrays, renders the
/// same bits and counts the same rays and nodes with the tree read from
/// uniform buffers as from the others; a tree of more records than a uniform
/// buffer holds is read from the others.
#[test]
fn a_tree_in_uniform_buffers_traces_as_in_the_other_arrays() {
    let spd = ["tetra:4", "mount:5", "gears:1", "tree:2", "rings:1"].map(|name| {
        (name, glint_scene::load(std::path::Path::new(&format!("spd:{name}"))).unwrap_or_else(|e| panic!("{e}")))
    });
    let scenes: Vec<(&str, Scene)> = spd.into_iter().chain(gallery()).collect();
    for arrays in SceneArrays::ALL {
        let renderer = renderer(arrays);
        for (name, scene) in &scenes {
            let mut scene = scene.clone();
            (scene.width, scene.height) = (33, 25);
            let mut prepared = renderer.prepare(&scene, scene.width, scene.height, Acceleration::Bvh).unwrap_or_else(|e| panic!("{e}"));
            assert!(prepared.buffers.tuning().uniform_tree(), "{name}: {} records fit", prepared.bvh_nodes);
            for view in View::ALL {
                for packets in [false, true] {
                    let mut render = |uniform_tree| {
                        prepared.buffers.retune(prepared.buffers.tuning().with_packets(packets).with_uniform_tree(uniform_tree));
                        let options = RenderOptions { view, ..Default::default() };
                        renderer.render(&prepared.buffers, &options, &mut |_, _| {}).unwrap_or_else(|e| panic!("{e}"))
                    };
                    let ((uniform, uniform_stats), (other, other_stats)) = (render(true), render(false));
                    let case = format!("{arrays:?}, {name}, {view:?} view, packets {packets}");
                    support::assert_images_equal(&uniform.linear, &other.linear, 0, &case);
                    assert_eq!(uniform_stats, other_stats, "{case}");
                }
            }
        }
    }
    let large = glint_scene::load(std::path::Path::new("spd:tetra:7")).unwrap_or_else(|e| panic!("{e}"));
    let prepared = renderer(SceneArrays::Buffers).prepare(&large, 16, 16, Acceleration::Bvh).unwrap_or_else(|e| panic!("{e}"));
    assert!(prepared.bvh_nodes > UNIFORM_TREE_RECORDS as usize, "{} records", prepared.bvh_nodes);
    assert!(!prepared.buffers.tuning().uniform_tree());
}
