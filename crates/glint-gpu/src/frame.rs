//! The host pipeline from a loaded scene to uploaded buffers:
//! build BVH → pack → upload. Shared by the CLI, the viewer and the tests.

use std::time::{Duration, Instant};

use glint_scene::bvh::Bvh;
use glint_scene::gpu_types;
use glint_scene::Scene;

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
}

impl Renderer {
    /// Builds the acceleration structure, packs and uploads `scene` for an image
    /// of `width` × `height`.
    pub fn prepare(&self, scene: &Scene, width: u32, height: u32, acceleration: Acceleration) -> Result<Prepared, GpuError> {
        let bounds = gpu_types::primitive_bounds(scene);
        let start = Instant::now();
        let bvh = match acceleration {
            Acceleration::Bvh => Bvh::build(&bounds),
            Acceleration::BruteForce => Bvh::single_leaf(&bounds),
        };
        let bvh_build = start.elapsed();
        let packed = gpu_types::pack(scene, &bvh);
        let globals = gpu_types::globals(scene, width, height, packed.light_count);
        let buffers = self.upload(&packed, globals)?;
        Ok(Prepared { buffers, primitives: bounds.len(), bvh_nodes: bvh.nodes.len(), bvh_build })
    }
}
