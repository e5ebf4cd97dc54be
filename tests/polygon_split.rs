//! Large polygons reach the kernels cut into sectors
//! (`glint_scene::polygon_split`): the same rays as the polygons whole, and
//! the same pixels but for the last bits of each sector's plane.

mod support;

use glint_encoding::gpu_bvh::GpuBvh;
use glint_encoding::gpu_types::{self, View};
use glint_gpu::{RenderOptions, SceneBuffers};
use glint_scene::bvh::Bvh;
use glint_scene::Scene;

/// `scene` on the device as `Renderer::prepare` puts it, but with its polygons whole.
fn upload_whole(scene: &Scene) -> SceneBuffers {
    let bvh = Bvh::build(&gpu_types::primitive_bounds(scene));
    let packed = gpu_types::pack(scene, &bvh.order, GpuBvh::encode(&bvh).unwrap());
    let uniforms = gpu_types::scene_uniforms(scene, scene.width, scene.height, packed.light_count, packed.layout());
    support::renderer().upload(&packed, uniforms).unwrap()
}

#[test]
fn gear_faces_cut_into_sectors_render_as_whole() {
    let mut scene = glint_scene::load(std::path::Path::new("spd:gears:1")).unwrap();
    (scene.width, scene.height) = (96, 96);
    let r = support::renderer();
    let cut = r.prepare(&scene, scene.width, scene.height, glint_gpu::Acceleration::Bvh).unwrap();
    assert!(cut.primitives > scene.primitive_count(), "the gear faces reach the kernels whole");
    let whole = upload_whole(&scene);
    for view in [View::Shaded, View::Depth] {
        let options = RenderOptions { view, ..Default::default() };
        let (cut_image, cut_rays) = r.render(&cut.buffers, &options, &mut |_, _| {}).unwrap();
        let (whole_image, whole_rays) = r.render(&whole, &options, &mut |_, _| {}).unwrap();
        assert_eq!(cut_rays, whole_rays, "{view:?}: the sectors let a ray through or stop one twice");
        for (i, (a, b)) in cut_image.linear.iter().zip(&whole_image.linear).enumerate() {
            for c in 0..3 {
                let close = a[c] == b[c] || (a[c] - b[c]).abs() <= 1e-5 * b[c].abs().max(1.0);
                assert!(close, "{view:?}: pixel {i}: cut {a:?}, whole {b:?}");
            }
        }
    }
}
