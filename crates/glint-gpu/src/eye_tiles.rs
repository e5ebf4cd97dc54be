//! Eye tiles on the device (binning.rs builds them on the host): the lists
//! and the primitives the primary kernel's packets read them with, bound as
//! group 1 (shaders/fast/eye_tiles.wgsl). They belong to one view, so they are
//! bound apart from the scene and rebuilt when the camera moves.

pub mod binning;

use glint_encoding::gpu_types::{DispatchParams, GpuCamera, EYE_TILE_HEIGHT, EYE_TILE_WIDTH};
use wgpu::util::DeviceExt;

use binning::Footprints;
use crate::{Renderer, SceneBuffers};

/// A scene's eye tiles as bound: the lists, for the camera they were built
/// for (none: empty lists, which no kernel reads), and the primitives' buffer
/// to bind beside them.
pub(crate) struct EyeTileBinding {
    pub(crate) bind: wgpu::BindGroup,
    camera: Option<GpuCamera>,
    prims: wgpu::Buffer,
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
        let prims = prims.cloned().unwrap_or_else(|| self.storage("no primitives", &[0; 16]));
        self.eye_tile_binding(&[0; 2], prims, None)
    }

    /// Bins `footprints` for `camera` and binds the lists, when the device can
    /// trace them and they are short enough to repay it; else the kernels walk
    /// the BVH. True when the scene now has eye tiles.
    pub(crate) fn bin_eye_tiles(&self, scene: &mut SceneBuffers, footprints: &Footprints, camera: &GpuCamera) -> bool {
        let tiles = self.profile.eye_tiles.then(|| footprints.bin(camera, scene.width, scene.height)).flatten();
        let limit = self.device.limits().max_storage_buffer_binding_size;
        let tiles = tiles.filter(|t| (t.words.len() as u64) * 4 <= limit);
        let prims = scene.eye_tiles.prims.clone();
        scene.eye_tiles = match &tiles {
            Some(t) => self.eye_tile_binding(&t.words, prims, Some(*camera)),
            None => self.eye_tile_binding(&[0; 2], prims, None),
        };
        scene.tuning.eye_tiles = tiles.is_some();
        tiles.is_some()
    }

    fn eye_tile_binding(&self, words: &[u32], prims: wgpu::Buffer, camera: Option<GpuCamera>) -> EyeTileBinding {
        let lists = self.storage("eye tiles", bytemuck::cast_slice(words));
        let bind = self.device.create_bind_group(&wgpu::BindGroupDescriptor {
            label: Some("eye tiles"),
            layout: &self.eye_tiles_layout,
            entries: &[
                wgpu::BindGroupEntry { binding: 0, resource: lists.as_entire_binding() },
                wgpu::BindGroupEntry { binding: 1, resource: prims.as_entire_binding() },
            ],
        });
        EyeTileBinding { bind, camera, prims }
    }

    fn storage(&self, label: &str, contents: &[u8]) -> wgpu::Buffer {
        self.device.create_buffer_init(&wgpu::util::BufferInitDescriptor { label: Some(label), contents, usage: wgpu::BufferUsages::STORAGE })
    }
}

impl SceneBuffers {
    /// After the camera in the uniforms became `camera`: the lists serve it
    /// only if they were built for it.
    pub(crate) fn aim_eye_tiles(&mut self, camera: &GpuCamera) {
        self.tuning.eye_tiles = self.eye_tiles.camera.as_ref() == Some(camera);
    }
}

/// Whether a dispatch over `region` hands each SIMD group blocks of one tile:
/// its workgroups start on tile corners.
pub(crate) fn tiles_align(region: &DispatchParams) -> bool {
    region.origin[0].is_multiple_of(EYE_TILE_WIDTH) && region.origin[1].is_multiple_of(EYE_TILE_HEIGHT)
}
