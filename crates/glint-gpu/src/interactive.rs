//! What an interactive viewer needs beyond a one-shot render: tracing a band of
//! rows without waiting for the device, resolving straight into a texture the
//! UI draws, reading ray counts without stalling, editing lights, materials and
//! per-frame settings in place, and picking the object under a pixel.

use std::ops::Range;
use std::sync::{Arc, Mutex};

use bytemuck::Zeroable;
use glint_encoding::gpu_types::{DispatchParams, GpuLight, GpuMaterial, PackedLayout, ResolveParams, SceneUniforms, View};
use glint_encoding::specialization::Specialization;

use crate::error_scope::ErrorScope;
use crate::pipelines::create_pipeline;
use crate::renderer::STAT_BYTES;
use crate::shaders::{Kernel, ShaderSource};
use crate::tuning::Tuning;
use crate::{GpuError, RayStats, Region, RenderOptions, Renderer, SceneBuffers};

/// Bytes of one accumulation pixel (rgb sum and sample count).
const PIXEL_BYTES: u64 = 16;


/// The present kernel: resolve.wgsl's display mapping, written into a texture.
pub struct PresentPipeline {
    pipeline: wgpu::ComputePipeline,
}

/// An rgba8 texture of a scene's image size that the present kernel fills.
pub struct PresentTarget {
    pub texture: wgpu::Texture,
    /// A view of `texture` for sampling it (egui draws it).
    pub view: wgpu::TextureView,
    params: wgpu::Buffer,
    bind: wgpu::BindGroup,
}

/// Ray counts read back a few frames late instead of stalling for them: the
/// device's counters are copied out and cleared on `request`, and `poll` hands
/// the copy over once the device has written it.
pub struct RayCounter {
    buffer: wgpu::Buffer,
    mapped: Arc<Mutex<Option<Result<(), wgpu::BufferAsyncError>>>>,
    in_flight: bool,
}

impl SceneBuffers {
    /// How its kernels are tuned for the current view: glint-gpu's choice,
    /// which front ends read.
    pub fn tuning(&self) -> Tuning {
        self.view_tuning()
    }

    /// Tunes its kernels by hand (tests of each variant; the `variants` feature).
    #[cfg(feature = "variants")]
    pub fn retune(&mut self, tuning: Tuning) {
        self.tuning = tuning;
    }

    pub fn width(&self) -> u32 {
        self.width
    }

    pub fn height(&self) -> u32 {
        self.height
    }

    /// The BVH record traversal starts from, for `gpu_types::scene_uniforms`.
    pub fn bvh_root(&self) -> u32 {
        self.layout.bvh_root
    }

    /// Where its BVH's walk starts and where its planes are, for
    /// `scene_uniforms` when the view changes.
    pub fn layout(&self) -> PackedLayout {
        self.layout
    }

    /// How many lights the lights buffer holds.
    pub fn light_capacity(&self) -> usize {
        (self.lights.size() / std::mem::size_of::<GpuLight>() as u64) as usize
    }

    /// Whether the accumulation holds every pixel of the image, as progressive
    /// rendering, presenting and picking need. An image too large for the
    /// device is held a tile at a time and renders only through `render`.
    pub fn holds_whole_image(&self) -> bool {
        self.accum_pixels == u64::from(self.width) * u64::from(self.height)
    }

    /// [`Self::holds_whole_image`], as an error naming the sizes when not.
    pub fn check_whole_image(&self) -> Result<(), GpuError> {
        if self.holds_whole_image() {
            return Ok(());
        }
        Err(GpuError::Region(format!(
            "the {}x{} image is too large for the device to hold at once ({} pixels fit): it renders only tile by tile",
            self.width, self.height, self.accum_pixels
        )))
    }

    /// How many materials the materials buffer holds.
    pub fn material_capacity(&self) -> usize {
        (self.materials.size() / std::mem::size_of::<GpuMaterial>() as u64) as usize
    }
}

impl Renderer {
    /// Compiles the present kernel from `source`.
    pub fn present_pipeline(&self, source: &ShaderSource) -> Result<PresentPipeline, GpuError> {
        let pipeline = create_pipeline(&self.device, source, Kernel::Present, (Specialization::ALL, Tuning::PLAIN), None)?;
        Ok(PresentPipeline { pipeline })
    }

    /// A texture of `scene`'s image size for `present` to fill.
    pub fn present_target(&self, pipeline: &PresentPipeline, scene: &SceneBuffers) -> PresentTarget {
        let texture = self.device.create_texture(&wgpu::TextureDescriptor {
            label: Some("present"),
            size: wgpu::Extent3d { width: scene.width, height: scene.height, depth_or_array_layers: 1 },
            mip_level_count: 1,
            sample_count: 1,
            dimension: wgpu::TextureDimension::D2,
            format: wgpu::TextureFormat::Rgba8Unorm,
            // COPY_SRC lets the image be read back (tests compare it with `resolve`).
            usage: wgpu::TextureUsages::STORAGE_BINDING | wgpu::TextureUsages::TEXTURE_BINDING | wgpu::TextureUsages::COPY_SRC,
            view_formats: &[],
        });
        let view = texture.create_view(&Default::default());
        let params = self.device.create_buffer(&wgpu::BufferDescriptor {
            label: Some("present params"),
            size: std::mem::size_of::<ResolveParams>() as u64,
            usage: wgpu::BufferUsages::UNIFORM | wgpu::BufferUsages::COPY_DST,
            mapped_at_creation: false,
        });
        let bind = self.device.create_bind_group(&wgpu::BindGroupDescriptor {
            label: Some("present"),
            layout: &pipeline.pipeline.get_bind_group_layout(0),
            entries: &[
                wgpu::BindGroupEntry { binding: 0, resource: params.as_entire_binding() },
                wgpu::BindGroupEntry { binding: 1, resource: scene.accum.as_entire_binding() },
                wgpu::BindGroupEntry { binding: 3, resource: wgpu::BindingResource::TextureView(&view) },
            ],
        });
        PresentTarget { texture, view, params, bind }
    }

    /// Resolves the samples accumulated so far into `target`, as `resolve` would
    /// (tone map, exposure, view, view scale of `options`), without reading back.
    pub fn present(&self, pipeline: &PresentPipeline, target: &PresentTarget, options: &RenderOptions) {
        let (width, height) = (target.texture.width(), target.texture.height());
        let params = ResolveParams {
            pixel_count: width * height,
            tone_map: options.tone_map as u32,
            exposure: options.exposure,
            view: options.view as u32,
            scale: options.view_scale,
            ..Zeroable::zeroed()
        };
        self.queue.write_buffer(&target.params, 0, bytemuck::bytes_of(&params));
        let mut encoder = self.device.create_command_encoder(&Default::default());
        {
            let mut pass = encoder.begin_compute_pass(&Default::default());
            pass.set_pipeline(&pipeline.pipeline);
            pass.set_bind_group(0, &target.bind, &[]);
            pass.dispatch_workgroups(width.div_ceil(8), height.div_ceil(8), 1);
        }
        self.queue.submit([encoder.finish()]);
    }

    /// Adds sample `sample_index` to the pixels of `rows` and returns without
    /// waiting for the device. Ray counts add up on the device until a
    /// `RayCounter` collects them. Does nothing unless the scene's
    /// accumulation holds the whole image.
    pub fn trace_rows(&self, scene: &SceneBuffers, sample_index: u32, options: &RenderOptions, rows: Range<u32>) -> Result<(), GpuError> {
        let rows = rows.start.min(scene.height)..rows.end.min(scene.height);
        if rows.is_empty() || !scene.holds_whole_image() {
            return Ok(());
        }
        let mut encoder = self.device.create_command_encoder(&Default::default());
        self.encode_band(scene, Region::whole(scene.width, scene.height), sample_index, options, rows, &mut encoder)?;
        self.queue.submit([encoder.finish()]);
        Ok(())
    }

    /// Empties the accumulated samples of `rows`, so the next sample traced
    /// there starts them over while the other rows keep theirs. Does nothing
    /// unless the scene's accumulation holds the whole image.
    pub fn clear_rows(&self, scene: &SceneBuffers, rows: Range<u32>) {
        let (start, end) = (rows.start.min(scene.height), rows.end.min(scene.height));
        if start >= end || !scene.holds_whole_image() {
            return;
        }
        let row_bytes = u64::from(scene.width) * PIXEL_BYTES;
        let mut encoder = self.device.create_command_encoder(&Default::default());
        encoder.clear_buffer(&scene.accum, u64::from(start) * row_bytes, Some(u64::from(end - start) * row_bytes));
        self.queue.submit([encoder.finish()]);
    }

    /// Replaces the scene uniforms (camera, background, ambient, flags, depth
    /// cue, maximum depth, light count) for the dispatches that follow; they
    /// must be for the buffers' image size and BVH root, and a scene uploaded
    /// for its own settings (opaque shadows, no depth cue) takes no others.
    pub fn write_uniforms(&self, scene: &mut SceneBuffers, uniforms: &SceneUniforms) -> Result<(), GpuError> {
        debug_assert_eq!(
            (uniforms.width, uniforms.height, uniforms.bvh_root, uniforms.plane_first, uniforms.plane_count),
            (scene.width, scene.height, scene.layout.bvh_root, scene.layout.plane_first, scene.layout.plane_count)
        );
        if !scene.specialization.covers_uniforms(uniforms) {
            return Err(GpuError::Runtime(format!(
                "the scene was uploaded for its own settings ({}): tinted shadows, depth cueing or a deeper ray tree need it uploaded editable",
                scene.specialization
            )));
        }
        self.queue.write_buffer(&scene.uniforms, 0, bytemuck::bytes_of(uniforms));
        scene.aim_eye_tiles(&uniforms.camera);
        Ok(())
    }

    /// Writes `materials` (packed in scene order) over the scene's materials;
    /// a scene uploaded for fewer terms than they make (no secondary rays, say)
    /// takes none of them (see `Specialization::editable`).
    pub fn write_materials(&self, scene: &SceneBuffers, materials: &[GpuMaterial]) -> Result<(), GpuError> {
        if materials.len() > scene.material_capacity() {
            return Err(GpuError::Runtime(format!(
                "{} materials do not fit the {} uploaded",
                materials.len(),
                scene.material_capacity()
            )));
        }
        if !scene.specialization.covers(materials) {
            return Err(GpuError::Runtime(format!(
                "the scene was uploaded for its own materials' terms ({}): edited materials need it uploaded editable",
                scene.specialization
            )));
        }
        self.queue.write_buffer(&scene.materials, 0, bytemuck::cast_slice(materials));
        Ok(())
    }

    /// Replaces the scene's lights by `lights` (the enabled ones, packed), which
    /// must fit the buffer uploaded with the scene and its kernels' terms.
    pub fn write_lights(&self, scene: &SceneBuffers, lights: &[GpuLight]) -> Result<(), GpuError> {
        if lights.len() > scene.light_capacity() {
            return Err(GpuError::Runtime(format!(
                "{} lights do not fit the room for {} uploaded",
                lights.len(),
                scene.light_capacity()
            )));
        }
        if !scene.specialization.covers_lights(lights) {
            return Err(GpuError::Runtime(format!(
                "the scene was uploaded for lights that do not fade ({}): edited lights need it uploaded editable",
                scene.specialization
            )));
        }
        self.queue.write_buffer(&scene.lights, 0, bytemuck::cast_slice(lights));
        Ok(())
    }

    /// The object whose surface the primary ray through the centre of pixel
    /// (`x`, `y`) hits first (from the top-left corner), or `None` on a miss.
    ///
    /// The primary kernel runs in the object-id view over that one pixel. Its
    /// accumulation slot is saved before and restored after, so a progressive
    /// render carries on undisturbed.
    pub fn pick(&self, scene: &SceneBuffers, x: u32, y: u32) -> Result<Option<u32>, GpuError> {
        if x >= scene.width || y >= scene.height {
            return Ok(None);
        }
        scene.check_whole_image()?;
        let slot = (u64::from(y) * u64::from(scene.width) + u64::from(x)) * PIXEL_BYTES;
        let region =
            DispatchParams { origin: [x, y], end: [x + 1, y + 1], sample_count: 1, tile_width: scene.width, ..Zeroable::zeroed() };
        let scope = ErrorScope::push(&self.device);
        let saved = self.device.create_buffer(&wgpu::BufferDescriptor {
            label: Some("pick saved pixel"),
            size: PIXEL_BYTES,
            usage: wgpu::BufferUsages::COPY_SRC | wgpu::BufferUsages::COPY_DST,
            mapped_at_creation: false,
        });
        let readback = self.readback_buffer(PIXEL_BYTES);
        let mut encoder = self.device.create_command_encoder(&Default::default());
        encoder.copy_buffer_to_buffer(&scene.accum, slot, &saved, 0, PIXEL_BYTES);
        self.encode_dispatch(scene, View::Id, region, &mut encoder)?;
        encoder.copy_buffer_to_buffer(&scene.accum, slot, &readback, 0, PIXEL_BYTES);
        encoder.copy_buffer_to_buffer(&saved, 0, &scene.accum, slot, PIXEL_BYTES);
        self.queue.submit([encoder.finish()]);
        let bytes = self.read(&readback);
        if let Some(e) = scope.pop() {
            return Err(GpuError::Runtime(e.to_string()));
        }
        let pixel: [f32; 4] = bytemuck::pod_read_unaligned(&bytes?);
        // The id view writes −1 on a miss, else the object index's bits in y.
        Ok((pixel[0] >= 0.0).then_some(pixel[1].to_bits()))
    }

    pub fn ray_counter(&self) -> RayCounter {
        RayCounter { buffer: self.readback_buffer(STAT_BYTES), mapped: Arc::new(Mutex::new(None)), in_flight: false }
    }
}

impl RayCounter {
    /// Starts collecting the rays counted since the last request; does nothing
    /// while the previous collection is still on its way.
    pub fn request(&mut self, renderer: &Renderer, scene: &SceneBuffers) {
        if self.in_flight {
            return;
        }
        let mut encoder = renderer.device.create_command_encoder(&Default::default());
        encoder.copy_buffer_to_buffer(&scene.stats, 0, &self.buffer, 0, STAT_BYTES);
        encoder.clear_buffer(&scene.stats, 0, None);
        renderer.queue.submit([encoder.finish()]);
        let mapped = Arc::clone(&self.mapped);
        self.buffer.map_async(wgpu::MapMode::Read, .., move |r| {
            *mapped.lock().expect("the map callback never panics") = Some(r);
        });
        self.in_flight = true;
    }

    /// The counts of the last request once the device has delivered them. The
    /// device must be polled (`wgpu::Device::poll`) for that to happen.
    pub fn poll(&mut self) -> Option<Result<RayStats, GpuError>> {
        let result = self.mapped.lock().expect("the map callback never panics").take()?;
        self.in_flight = false;
        if let Err(e) = result {
            return Some(Err(GpuError::Runtime(e.to_string())));
        }
        let stats = match self.buffer.get_mapped_range(..) {
            Ok(bytes) => RayStats::from_slots(&bytemuck::pod_collect_to_vec(&bytes)),
            Err(e) => return Some(Err(GpuError::Runtime(e.to_string()))),
        };
        self.buffer.unmap();
        Some(Ok(stats))
    }
}
