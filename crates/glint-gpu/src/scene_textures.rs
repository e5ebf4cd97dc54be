//! The scene's arrays as the kernels read them: textures of
//! `SCENE_TEXTURE_WIDTH` texels a row, one record of 16 bytes a texel (a
//! primitive takes `PRIM_TEXELS`), fetched by `prim_at` and its siblings in
//! shaders/fast/scene_textures.wgsl. lavapipe fetches a texel per lane without the
//! branch a storage buffer's bounds check costs per lane and component.

use glint_encoding::gpu_types::{SCENE_TEXEL_BYTES, SCENE_TEXTURE_WIDTH};

const FORMAT: wgpu::TextureFormat = wgpu::TextureFormat::Rgba32Uint;

const ROW_BYTES: usize = SCENE_TEXTURE_WIDTH as usize * SCENE_TEXEL_BYTES;

/// The rows that hold `bytes`, at least one: an empty array still binds.
pub(crate) fn rows(bytes: usize) -> u32 {
    bytes.div_ceil(ROW_BYTES).max(1) as u32
}

/// The most bytes one array may have on a device whose textures are at most
/// `max_side` texels high.
pub(crate) fn capacity(max_side: u32) -> u64 {
    u64::from(max_side) * ROW_BYTES as u64
}

/// Bytes a texture holding `bytes` takes on the device, its last row padded.
pub(crate) fn device_bytes(bytes: usize) -> u64 {
    u64::from(rows(bytes)) * ROW_BYTES as u64
}

/// Uploads `bytes`, whole texels, as a texture: its whole rows, then what
/// is left as the start of the last row, whose rest wgpu zeroes.
pub(crate) fn upload(device: &wgpu::Device, queue: &wgpu::Queue, label: &str, bytes: &[u8]) -> wgpu::TextureView {
    debug_assert_eq!(bytes.len() % SCENE_TEXEL_BYTES, 0, "{label}: whole texels");
    let texture = device.create_texture(&wgpu::TextureDescriptor {
        label: Some(label),
        size: wgpu::Extent3d { width: SCENE_TEXTURE_WIDTH, height: rows(bytes.len()), depth_or_array_layers: 1 },
        mip_level_count: 1,
        sample_count: 1,
        dimension: wgpu::TextureDimension::D2,
        format: FORMAT,
        usage: wgpu::TextureUsages::TEXTURE_BINDING | wgpu::TextureUsages::COPY_DST,
        view_formats: &[],
    });
    let (whole, tail) = bytes.split_at(bytes.len() / ROW_BYTES * ROW_BYTES);
    let write = |data: &[u8], y: u32, texels: usize, rows: usize| {
        let origin = wgpu::Origin3d { x: 0, y, z: 0 };
        let layout = wgpu::TexelCopyBufferLayout { offset: 0, bytes_per_row: Some(ROW_BYTES as u32), rows_per_image: None };
        let size = wgpu::Extent3d { width: texels as u32, height: rows as u32, depth_or_array_layers: 1 };
        queue.write_texture(wgpu::TexelCopyTextureInfo { texture: &texture, mip_level: 0, origin, aspect: wgpu::TextureAspect::All }, data, layout, size);
    };
    let whole_rows = whole.len() / ROW_BYTES;
    if whole_rows > 0 {
        write(whole, 0, SCENE_TEXTURE_WIDTH as usize, whole_rows);
    }
    if !tail.is_empty() {
        write(tail, whole_rows as u32, tail.len() / SCENE_TEXEL_BYTES, 1);
    }
    texture.create_view(&Default::default())
}

/// The layout entry of a scene texture at `binding`.
pub(crate) fn layout_entry(binding: u32) -> wgpu::BindGroupLayoutEntry {
    wgpu::BindGroupLayoutEntry {
        binding,
        visibility: wgpu::ShaderStages::COMPUTE,
        ty: wgpu::BindingType::Texture {
            sample_type: wgpu::TextureSampleType::Uint,
            view_dimension: wgpu::TextureViewDimension::D2,
            multisampled: false,
        },
        count: None,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn an_array_takes_whole_rows_and_an_empty_one_still_one() {
        assert_eq!(rows(0), 1);
        assert_eq!(rows(SCENE_TEXEL_BYTES), 1);
        assert_eq!(rows(ROW_BYTES), 1);
        assert_eq!(rows(ROW_BYTES + SCENE_TEXEL_BYTES), 2);
        assert_eq!(device_bytes(ROW_BYTES + 1), 2 * ROW_BYTES as u64);
        assert_eq!(capacity(16384), 16384 * ROW_BYTES as u64);
    }
}
