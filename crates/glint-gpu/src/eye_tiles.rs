//! Eye tiles on the device (glint-encoding's eye_tiles.rs bins them on the host): the lists
//! and the primitives the primary kernel's packets read them with, bound as
//! group 1 (shaders/fast/eye_tiles.wgsl). They belong to one view, so they are
//! bound apart from the scene and rebuilt when the camera moves.

use glint_encoding::eye_tiles::Footprints;
use glint_encoding::gpu_types::{DispatchParams, GpuCamera, EYE_TILE_HEIGHT, EYE_TILE_WIDTH};

use crate::{Renderer, SceneBuffers, Tuning};

/// A scene's eye tiles as bound: the lists, for the camera they were built
/// for (none: lists no kernel reads), and the primitives' buffer to bind
/// beside them.
pub(crate) struct EyeTileBinding {
    pub(crate) bind: wgpu::BindGroup,
    camera: Option<GpuCamera>,
    prims: wgpu::Buffer,
    /// Where the lists are: a new view's lists are written over the last
    /// ones while they fit, so a camera move allocates nothing on the device
    /// (docs/decisions/048-cheaper-eye-tile-binning.md).
    lists: wgpu::Buffer,
    /// The view's primitives were too many to bin: packets walking the BVH
    /// for it would part at almost every leaf, so its eye rays are traced
    /// one at a time (docs/decisions/058-single-eye-rays-where-tiles-are-refused.md).
    crowded: bool,
}

pub(crate) fn bind_group_layout(device: &wgpu::Device) -> wgpu::BindGroupLayout {
    let entry = |binding| wgpu::BindGroupLayoutEntry {
        binding,
        visibility: wgpu::ShaderStages::COMPUTE,
        ty: wgpu::BindingType::Buffer {
            ty: wgpu::BufferBindingType::Storage { read_only: true },
            has_dynamic_offset: false,
            min_binding_size: None,
        },
        count: None,
    };
    device.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor { label: Some("eye tiles"), entries: &[entry(0), entry(1)] })
}

impl Renderer {
    /// What a scene uploaded with `prims` (its primitives' storage buffer, or
    /// `None` when the kernels read textures) binds before any lists.
    pub(crate) fn no_eye_tiles(&self, prims: Option<&wgpu::Buffer>) -> EyeTileBinding {
        let prims = prims.cloned().unwrap_or_else(|| self.device.create_buffer(&storage("no primitives", 16)));
        self.eye_tile_binding(8, prims)
    }

    /// Bins `footprints` for `camera` and binds the lists, when the device can
    /// trace them and they are short enough to repay it; else the kernels walk
    /// the BVH, one eye ray at a time where the lists were refused as too
    /// long (`crowded`). True when the scene now has eye tiles.
    pub(crate) fn bin_eye_tiles(&self, scene: &mut SceneBuffers, footprints: &Footprints, camera: &GpuCamera) -> bool {
        if !self.profile.eye_tiles {
            scene.forget_view();
            return false;
        }
        let limit = self.device.limits().max_storage_buffer_binding_size;
        let Some(tiles) = footprints.bin(camera, scene.width, scene.height).filter(|t| (t.words.len() as u64) * 4 <= limit) else {
            scene.forget_view();
            scene.eye_tiles.crowded = true;
            return false;
        };
        let bytes: &[u8] = bytemuck::cast_slice(&tiles.words);
        if bytes.len() as u64 > scene.eye_tiles.lists.size() {
            // Room to spare, for the next views' lists to fit.
            let room = (bytes.len() as u64 + bytes.len() as u64 / 4).next_multiple_of(4).min(limit);
            scene.eye_tiles = self.eye_tile_binding(room, scene.eye_tiles.prims.clone());
        }
        self.queue.write_buffer(&scene.eye_tiles.lists, 0, bytes);
        scene.eye_tiles.camera = Some(*camera);
        scene.eye_tiles.crowded = false;
        scene.tuning.eye_tiles = true;
        true
    }

    fn eye_tile_binding(&self, size: u64, prims: wgpu::Buffer) -> EyeTileBinding {
        let lists = self.device.create_buffer(&storage("eye tiles", size));
        let bind = self.device.create_bind_group(&wgpu::BindGroupDescriptor {
            label: Some("eye tiles"),
            layout: &self.eye_tiles_layout,
            entries: &[
                wgpu::BindGroupEntry { binding: 0, resource: lists.as_entire_binding() },
                wgpu::BindGroupEntry { binding: 1, resource: prims.as_entire_binding() },
            ],
        });
        EyeTileBinding { bind, camera: None, prims, lists, crowded: false }
    }
}

fn storage(label: &str, size: u64) -> wgpu::BufferDescriptor<'_> {
    wgpu::BufferDescriptor { label: Some(label), size, usage: wgpu::BufferUsages::STORAGE | wgpu::BufferUsages::COPY_DST, mapped_at_creation: false }
}

impl SceneBuffers {
    /// After the camera in the uniforms became `camera`: the lists serve it
    /// only if they were built for it.
    pub(crate) fn aim_eye_tiles(&mut self, camera: &GpuCamera) {
        self.tuning.eye_tiles = self.eye_tiles.camera.as_ref() == Some(camera);
        self.eye_tiles.crowded &= !self.tuning.eye_tiles;
    }

    /// Leaves the lists built for no view, as a camera move does, so that the
    /// next `Renderer::pose` bins them again (and `glint bench` times a move).
    pub fn forget_view(&mut self) {
        self.eye_tiles.camera = None;
        self.tuning.eye_tiles = false;
    }

    /// The tuning the current view's dispatches run: single eye rays where
    /// the view was too crowded to bin.
    pub(crate) fn view_tuning(&self) -> Tuning {
        if self.eye_tiles.crowded { self.tuning.with_single_eye_rays() } else { self.tuning }
    }

    /// The tuning a dispatch over `region` runs: without eye tiles where its
    /// workgroups start off the tiles' corners (a pick's pixel).
    pub(crate) fn dispatch_tuning(&self, region: &DispatchParams) -> Tuning {
        let tuning = self.view_tuning();
        if tiles_align(region) { tuning } else { tuning.without_eye_tiles() }
    }
}

/// Whether a dispatch over `region` hands each SIMD group blocks of one tile:
/// its workgroups start on tile corners.
fn tiles_align(region: &DispatchParams) -> bool {
    region.origin[0].is_multiple_of(EYE_TILE_WIDTH) && region.origin[1].is_multiple_of(EYE_TILE_HEIGHT)
}
