//! The host pipeline from a loaded scene to uploaded buffers:
//! cut large polygons → validate → build BVH → pack → upload. Shared by the CLI, the viewer and the tests.

use std::time::Duration;

use web_time::Instant;
use glint_encoding::gpu_bvh::GpuBvh;
use glint_encoding::gpu_types::{self, View, UNIFORM_TREE_RECORDS};
use glint_scene::bvh::Bvh;
use glint_scene::polygon_split;
use glint_scene::Scene;

use glint_encoding::eye_tiles::Footprints;
use crate::depth_extent::Corners;
use crate::{GpuError, Renderer, SceneBuffers};

/// How the primitives are organised for traversal.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum Acceleration {
    #[default]
    Bvh,
    /// One leaf holding everything: every ray tests every primitive. The
    /// reference the BVH is checked against.
    BruteForce,
}

/// A scene on the device, with what it took to get it there.
pub struct Prepared {
    pub buffers: SceneBuffers,
    pub primitives: usize,
    pub bvh_nodes: usize,
    pub bvh_build: Duration,
    /// The BVH's primitives as the eye tiles bin them, for each new view.
    pub footprints: Footprints,
    /// Binning them into eye tiles for the view, when the scene has them.
    pub eye_tiles_build: Option<Duration>,
    /// Distance from the eye to the farthest corner of the scene's bounds.
    pub depth_extent: f32,
    /// The corners of the scene's primitives' bounds (before large polygons
    /// are cut) that `pose` measures `depth_extent` to: a pose moves none.
    posed_corners: Corners,
    /// The scene's longest ray path and its lights, which bound the ray tree.
    pub max_depth: u32,
    pub lights: u32,
}

impl Prepared {
    /// The `RenderOptions::view_scale` that shows `view` well for this scene.
    pub fn view_scale(&self, view: View) -> f32 {
        match view {
            View::Depth => self.depth_extent,
            // Twice the depth of a balanced tree is a busy pixel.
            View::Heatmap => 2.0 * (self.bvh_nodes.max(2) as f32).log2() + 8.0,
            View::RayDepth => self.max_depth as f32,
            // A path to the deepest level with a shadow ray per light at every hit.
            View::RayCount => ((1 + self.lights) * self.max_depth) as f32,
            _ => 1.0,
        }
    }
}

impl Renderer {
    /// Builds the acceleration structure, packs and uploads `scene` for an image
    /// of `width` × `height`.
    pub fn prepare(&self, scene: &Scene, width: u32, height: u32, acceleration: Acceleration) -> Result<Prepared, GpuError> {
        let posed_corners = Corners::new(&gpu_types::primitive_bounds(scene));
        // Validated as the kernels get it, sectors and all.
        let scene = &*polygon_split::split_large_polygons(scene);
        scene.validate()?;
        let bounds = gpu_types::primitive_bounds(scene);
        // The build includes laying the tree out for the kernel.
        let start = Instant::now();
        let bvh = match acceleration {
            // On a device that reads a tree from uniform buffers, one that fits
            // them is read faster than any SAH tree larger by a little.
            Acceleration::Bvh if self.profile.uniform_tree => Bvh::build_within(&bounds, UNIFORM_TREE_RECORDS as usize),
            Acceleration::Bvh => Bvh::build(&bounds),
            Acceleration::BruteForce => Bvh::single_leaf(&bounds),
        };
        let gpu_bvh = GpuBvh::encode(&bvh)?;
        let bvh_build = start.elapsed();
        let packed = gpu_types::pack(scene, &bvh.order, gpu_bvh);
        let uniforms = gpu_types::scene_uniforms(scene, width, height, packed.light_count, packed.layout());
        let mut buffers = self.upload(&packed, uniforms)?;
        // Brute force is the reference the BVH is checked against: every ray
        // tests every primitive, from no list.
        let (footprints, eye_tiles_build) = match acceleration {
            Acceleration::Bvh => {
                let start = Instant::now();
                let footprints = Footprints::new(&packed, &bvh.order.iter().map(|&i| bounds[i as usize]).collect::<Vec<_>>());
                let binned = self.bin_eye_tiles(&mut buffers, &footprints, &uniforms.camera);
                (footprints, binned.then(|| start.elapsed()))
            }
            Acceleration::BruteForce => (Footprints::default(), None),
        };
        Ok(Prepared {
            buffers,
            primitives: scene.primitive_count(),
            bvh_nodes: bvh.nodes.len(),
            bvh_build,
            footprints,
            eye_tiles_build,
            depth_extent: Corners::new(&bounds).farthest(scene.camera.eye),
            posed_corners,
            max_depth: scene.render.max_depth,
            lights: packed.light_count,
        })
    }

    /// Gives a prepared scene the camera and lights of `scene`, the same scene
    /// posed at another frame (`Scene::set_frame`): only the lights, the
    /// uniforms and the eye tiles (which are the view's) are written, and the
    /// depth view's extent follows the eye.
    pub fn pose(&self, prepared: &mut Prepared, scene: &Scene) -> Result<(), GpuError> {
        let lights: Vec<_> = scene.lights.iter().filter(|l| l.enabled).map(gpu_types::pack_light).collect();
        if lights.len() != prepared.lights as usize {
            return Err(GpuError::Runtime(format!("{} lights are on, but the scene was prepared with {}", lights.len(), prepared.lights)));
        }
        let buffers = &mut prepared.buffers;
        if !lights.is_empty() {
            self.write_lights(buffers, &lights)?;
        }
        let uniforms = gpu_types::scene_uniforms(scene, buffers.width(), buffers.height(), prepared.lights, buffers.layout());
        self.write_uniforms(buffers, &uniforms)?;
        if !buffers.tuning.eye_tiles && prepared.eye_tiles_build.is_some() {
            self.bin_eye_tiles(buffers, &prepared.footprints, &uniforms.camera);
        }
        prepared.depth_extent = prepared.posed_corners.farthest(scene.camera.eye);
        Ok(())
    }
}

