//! The render pipeline on the device: upload → dispatch tiles → resolve → read back.

use bytemuck::Zeroable;
use std::sync::{Arc, Mutex};
use web_time::Instant;

use glint_encoding::gpu_types::{
    DispatchParams, Filter, GpuScene, PackedLayout, ResolveParams, SceneUniforms, View, STAT_COUNT, STAT_SLOTS, TONE_ACES, TONE_CLAMP, TONE_REINHARD,
    UNIFORM_ARRAY_BYTES,
};
use glint_encoding::specialization::Specialization;
use glint_encoding::RayStats;
use wgpu::util::DeviceExt;

use crate::error_scope::ErrorScope;
use crate::eye_tiles::{self, EyeTileBinding};
use crate::pipelines::Pipelines;
use crate::schedule::{BandScheduler, BATCH_TARGET};
use crate::scene_textures;
use crate::profile::DeviceProfile;
use crate::shaders::{Kernel, SceneArrays, ShaderSource};
use crate::tuning::Tuning;
use crate::workload::Workload;
use crate::{display, one_line, GpuError, Image, Readback, Region};

/// How linear radiance becomes a display value.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
#[repr(u32)]
pub enum ToneMap {
    #[default]
    Clamp = TONE_CLAMP,
    Reinhard = TONE_REINHARD,
    Aces = TONE_ACES,
}

#[derive(Debug, Clone, Copy, PartialEq)]
pub struct RenderOptions {
    pub view: View,
    /// Samples per pixel; 1 traces each pixel centre.
    pub spp: u32,
    pub seed: u32,
    pub filter: Filter,
    pub exposure: f32,
    pub tone_map: ToneMap,
    /// What maps a data view to [0, 1]: the far distance of the depth view, the
    /// node count shown hottest in the heat map.
    pub view_scale: f32,
    /// Rows per dispatch; `None` adapts the band height to the time a dispatch takes.
    pub band_rows: Option<u32>,
}

impl Default for RenderOptions {
    fn default() -> Self {
        Self {
            view: View::Shaded,
            spp: 1,
            seed: 0,
            filter: Filter::Box,
            exposure: 1.0,
            tone_map: ToneMap::Clamp,
            view_scale: 1.0,
            band_rows: None,
        }
    }
}

/// Size of the stats buffer.
pub(crate) const STAT_BYTES: u64 = STAT_SLOTS as u64 * STAT_COUNT as u64 * 4;
/// Bytes of one accumulated pixel (rgb sum and sample count), and of one
/// resolved pixel of each image read back.
const PIXEL_BYTES: u64 = 16;

/// The kernels on one device. Cheap to clone the device and queue handles
/// into it, so the viewer can share eframe's device.
pub struct Renderer {
    pub(crate) device: wgpu::Device,
    pub(crate) queue: wgpu::Queue,
    /// The trace kernel (the full Whitted render), the primary kernel (the
    /// primary ray alone, for the debug views, AOVs and picking: without the
    /// ray tree it compiles to far leaner code) and the resolve kernel.
    pub(crate) pipelines: Pipelines,
    /// The bind group layout the trace and primary kernels share.
    pub(crate) scene_layout: wgpu::BindGroupLayout,
    /// Group 1 of those kernels: the view's eye tiles, which the primary kernel reads.
    pub(crate) eye_tiles_layout: wgpu::BindGroupLayout,
    /// Every choice made for the device: how the kernels read the scene and
    /// are tuned, and whether the host resolves read-backs.
    pub(crate) profile: DeviceProfile,
    /// Why the device was lost, once it has been.
    lost: Arc<Mutex<Option<String>>>,
    /// The work its scenes are uploaded for, which their tuning serves.
    workload: Workload,
    /// Band sizes of batch renders, kept from frame to frame so the next one
    /// starts with bands of the right size.
    bands: Mutex<BandScheduler>,
    /// The most pixels a tile may have, below what the device's buffer limits
    /// allow (`None`: only those limits).
    max_tile_pixels: Option<u64>,
}

/// A scene uploaded for one image size.
pub struct SceneBuffers {
    pub(crate) width: u32,
    pub(crate) height: u32,
    pub(crate) layout: PackedLayout,
    pub(crate) uniforms: wgpu::Buffer,
    pub(crate) dispatch: wgpu::Buffer,
    pub(crate) accum: wgpu::Buffer,
    /// Pixels the accumulation buffer holds: the whole image when it fits the
    /// device, else the largest tile that does.
    pub(crate) accum_pixels: u64,
    pub(crate) stats: wgpu::Buffer,
    pub(crate) scene_bind: wgpu::BindGroup,
    pub(crate) eye_tiles: EyeTileBinding,
    pub(crate) materials: wgpu::Buffer,
    pub(crate) lights: wgpu::Buffer,
    /// Bytes of geometry and BVH on the device, what grows with the scene (the
    /// uniform buffers of the lights, the materials and the tree are a fixed
    /// 64 KiB each).
    pub scene_bytes: u64,
    /// What the kernels that render it are compiled for: the primitive kinds,
    /// the shading terms, and the view when a command renders one alone.
    pub specialization: Specialization,
    /// How those kernels are tuned for the device: its profile's choice for
    /// the renderer's work, read with [`SceneBuffers::tuning`].
    pub(crate) tuning: Tuning,
}

impl Renderer {
    /// A renderer that makes the choices of the device's profile, or of the
    /// one `GLINT_PROFILE` forces, for work it is not told of (see [`Renderer::plan`]).
    pub fn new(device: wgpu::Device, queue: wgpu::Queue, source: &ShaderSource) -> Result<Self, GpuError> {
        let profile = DeviceProfile::of_device(&device)?;
        Self::make(device, queue, source, profile)
    }

    /// A renderer whose kernels read the scene's arrays from `arrays`, whatever
    /// the device's profile would choose (tests that compare the ways).
    #[cfg(feature = "variants")]
    pub fn reading(device: wgpu::Device, queue: wgpu::Queue, source: &ShaderSource, arrays: SceneArrays) -> Result<Self, GpuError> {
        let profile = DeviceProfile::of_device(&device)?.reading(arrays);
        Self::make(device, queue, source, profile)
    }

    /// A renderer that makes the choices of `profile` (tests hold one profile's
    /// choices to another's on the same device; the `variants` feature).
    #[cfg(feature = "variants")]
    pub fn with_profile(device: wgpu::Device, queue: wgpu::Queue, source: &ShaderSource, profile: DeviceProfile) -> Result<Self, GpuError> {
        Self::make(device, queue, source, profile)
    }

    /// Tunes the scenes uploaded from now on for `workload`: where the
    /// profile traces packets, a one-off render traces them only once they
    /// repay their compile.
    pub fn plan(mut self, workload: Workload) -> Self {
        self.workload = workload;
        self
    }

    fn make(device: wgpu::Device, queue: wgpu::Queue, source: &ShaderSource, profile: DeviceProfile) -> Result<Self, GpuError> {
        let arrays = profile.scene_arrays;
        let scene_layout = scene_bind_group_layout(&device, arrays);
        let eye_tiles_layout = eye_tiles::bind_group_layout(&device);
        let pipeline_layout = device.create_pipeline_layout(&wgpu::PipelineLayoutDescriptor {
            label: Some("scene"),
            bind_group_layouts: &[Some(&scene_layout), Some(&eye_tiles_layout)],
            immediate_size: 0,
        });
        let pipelines = Pipelines::new(&device, source, pipeline_layout, arrays)?;
        let lost = Arc::new(Mutex::new(None));
        let record = Arc::clone(&lost);
        device.set_device_lost_callback(move |reason, message| {
            *record.lock().unwrap_or_else(|e| e.into_inner()) = Some(format!("{reason:?}: {message}"));
        });
        Ok(Self {
            device,
            queue,
            pipelines,
            scene_layout,
            eye_tiles_layout,
            profile,
            workload: Workload::UNDESCRIBED,
            lost,
            bands: Mutex::new(BandScheduler::before_compile(BATCH_TARGET)),
            max_tile_pixels: None,
        })
    }

    /// Limits tiles to `pixels` pixels for the scenes uploaded from now on, as
    /// if the device could hold no more: tiled renders can then be tested at
    /// sizes any device holds whole.
    pub fn with_max_tile_pixels(mut self, pixels: u64) -> Self {
        self.max_tile_pixels = Some(pixels.max(1));
        self
    }

    pub fn device(&self) -> &wgpu::Device {
        &self.device
    }

    /// The choices made for this device.
    pub fn profile(&self) -> &DeviceProfile {
        &self.profile
    }

    /// Single rays reading the scene as this renderer binds it, and the ray
    /// tree the profile walks: for kernels that serve any scene (the probe's).
    pub(crate) fn plain_tuning(&self) -> Tuning {
        Tuning { arrays: self.profile.scene_arrays, one_walk_tree: self.profile.one_walk_tree, mask_loops: self.profile.mask_loops, ..Tuning::PLAIN }
    }

    /// Creates the pipelines of `kernels` for `scene` now (those not made
    /// yet), so a shader the driver rejects fails before any work is done.
    pub fn create_pipelines(&self, scene: &SceneBuffers, kernels: &[Kernel]) -> Result<(), GpuError> {
        self.pipelines.create(kernels, scene.specialization, scene.view_tuning())
    }

    /// Creates now the pipelines that a viewer's progressive samples of
    /// `views` on `scene` use. (One sample a pixel takes the eye hits of the
    /// primary kernel, whose pipeline its first dispatch creates.)
    pub fn create_view_pipelines(&self, scene: &SceneBuffers, views: &[View]) -> Result<(), GpuError> {
        for &view in views {
            let kernel = kernel_for(view);
            let tuning = sampled_tuning(kernel, scene.view_tuning(), 0);
            self.pipelines.get(kernel, scene.specialization.dispatching(view), tuning)?;
        }
        Ok(())
    }

    /// Uploads `scene` for rendering at `width` × `height`, checking the device's
    /// buffer and texture limits first. The accumulation buffer holds the whole image if
    /// the device can bind it, else the largest tile it can: any image size
    /// renders, tile by tile.
    pub fn upload(&self, scene: &GpuScene, uniforms: SceneUniforms) -> Result<SceneBuffers, GpuError> {
        let (width, height) = (uniforms.width, uniforms.height);
        let limits = self.device.limits();
        let device_pixels = limits.max_storage_buffer_binding_size.min(limits.max_buffer_size) / PIXEL_BYTES;
        let accum_pixels =
            (u64::from(width) * u64::from(height)).min(device_pixels).min(self.max_tile_pixels.unwrap_or(u64::MAX)).max(1);
        let arrays: [(&str, &[u8]); 4] = [
            ("primitives", bytemuck::cast_slice(&scene.prims)),
            ("BVH nodes", bytemuck::cast_slice(&scene.nodes)),
            ("polygon vertices and normals", bytemuck::cast_slice(&scene.points)),
            ("BVH grids", bytemuck::cast_slice(&scene.grids)),
        ];
        let array_limits = match self.profile.scene_arrays {
            SceneArrays::Textures => vec![("max_texture_dimension_2d", scene_textures::capacity(limits.max_texture_dimension_2d))],
            SceneArrays::Buffers => vec![
                ("max_storage_buffer_binding_size", u64::from(limits.max_storage_buffer_binding_size)),
                ("max_buffer_size", limits.max_buffer_size),
            ],
        };
        for (what, bytes) in arrays {
            let need = bytes.len() as u64;
            for &(limit, have) in &array_limits {
                if need > have {
                    return Err(GpuError::Limit { what: what.into(), limit, need, have });
                }
            }
        }
        let (buffers, views);
        let mut prims_buffer = None;
        let [prims, nodes, points, grids]: [wgpu::BindingResource; 4] = match self.profile.scene_arrays {
            SceneArrays::Buffers => {
                buffers = arrays.map(|(what, contents)| {
                    let usage = wgpu::BufferUsages::STORAGE;
                    self.device.create_buffer_init(&wgpu::util::BufferInitDescriptor { label: Some(what), contents, usage })
                });
                prims_buffer = Some(buffers[0].clone());
                buffers.each_ref().map(|b| b.as_entire_binding())
            }
            SceneArrays::Textures => {
                views = arrays.map(|(what, bytes)| scene_textures::upload(&self.device, &self.queue, what, bytes));
                views.each_ref().map(wgpu::BindingResource::TextureView)
            }
        };
        let eye_tiles = self.no_eye_tiles(prims_buffer.as_ref());
        let uniform = |label: &str, contents: &[u8]| {
            self.device.create_buffer_init(&wgpu::util::BufferInitDescriptor {
                label: Some(label),
                contents,
                usage: wgpu::BufferUsages::UNIFORM | wgpu::BufferUsages::COPY_DST,
            })
        };
        let lights = uniform("lights", bytemuck::cast_slice(&scene.lights));
        let materials = uniform("materials", bytemuck::cast_slice(&scene.materials));
        let uniforms_buffer = uniform("scene uniforms", bytemuck::bytes_of(&uniforms));
        let specialization = Specialization::of(scene, &uniforms);
        let tuning = self.profile.tuning(scene, &self.workload);
        // Bound whether or not the kernels read them; zeros for a tree too large.
        let tree_uniform = |label: &str, records: &[u8]| {
            let mut contents = vec![0; UNIFORM_ARRAY_BYTES];
            if tuning.uniform_tree {
                contents[..records.len()].copy_from_slice(records);
            }
            uniform(label, &contents)
        };
        let uniform_nodes = tree_uniform("BVH nodes (uniform)", bytemuck::cast_slice(&scene.nodes));
        let uniform_grids = tree_uniform("BVH grids (uniform)", bytemuck::cast_slice(&scene.grids));
        let dispatch = uniform("dispatch params", bytemuck::bytes_of(&DispatchParams::zeroed()));
        let accum = self.device.create_buffer(&wgpu::BufferDescriptor {
            label: Some("accum"),
            size: accum_pixels * PIXEL_BYTES,
            usage: wgpu::BufferUsages::STORAGE | wgpu::BufferUsages::COPY_SRC | wgpu::BufferUsages::COPY_DST,
            mapped_at_creation: false,
        });
        let stats = self.device.create_buffer(&wgpu::BufferDescriptor {
            label: Some("stats"),
            size: STAT_BYTES,
            usage: wgpu::BufferUsages::STORAGE | wgpu::BufferUsages::COPY_SRC | wgpu::BufferUsages::COPY_DST,
            mapped_at_creation: false,
        });
        let resources = [
            uniforms_buffer.as_entire_binding(),
            prims,
            nodes,
            materials.as_entire_binding(),
            lights.as_entire_binding(),
            points,
            accum.as_entire_binding(),
            stats.as_entire_binding(),
            grids,
            dispatch.as_entire_binding(),
            uniform_nodes.as_entire_binding(),
            uniform_grids.as_entire_binding(),
        ];
        let entries: Vec<wgpu::BindGroupEntry> =
            resources.into_iter().enumerate().map(|(i, resource)| wgpu::BindGroupEntry { binding: i as u32, resource }).collect();
        let scene_bind = self.device.create_bind_group(&wgpu::BindGroupDescriptor {
            label: Some("scene"),
            layout: &self.scene_layout,
            entries: &entries,
        });
        let scene_bytes = match self.profile.scene_arrays {
            SceneArrays::Textures => arrays.iter().map(|(_, b)| scene_textures::device_bytes(b.len())).sum(),
            SceneArrays::Buffers => arrays.iter().map(|(_, b)| b.len() as u64).sum(),
        };
        Ok(SceneBuffers {
            width,
            height,
            layout: PackedLayout { bvh_root: uniforms.bvh_root, plane_first: uniforms.plane_first, plane_count: uniforms.plane_count },
            uniforms: uniforms_buffer,
            dispatch,
            accum,
            accum_pixels,
            stats,
            scene_bind,
            eye_tiles,
            materials,
            lights,
            scene_bytes,
            specialization,
            tuning,
        })
    }

    /// Renders `options.spp` samples per pixel and resolves them, calling
    /// `progress(done, total)` (in pixel samples) after each dispatch.
    pub fn render(
        &self,
        scene: &SceneBuffers,
        options: &RenderOptions,
        progress: &mut dyn FnMut(u64, u64),
    ) -> Result<(Image, RayStats), GpuError> {
        self.render_region(scene, Region::whole(scene.width, scene.height), options, progress)
    }

    /// Renders the pixels of `region` alone, exactly as they are in a render
    /// of the whole image, and returns them as one image (see [`Self::render_tiles`]).
    pub fn render_region(
        &self,
        scene: &SceneBuffers,
        region: Region,
        options: &RenderOptions,
        progress: &mut dyn FnMut(u64, u64),
    ) -> Result<(Image, RayStats), GpuError> {
        check_region(scene, region)?;
        let pixels = region.pixels() as usize;
        let (width, height) = (region.width(), region.height());
        let mut image = Image { width, height, display: vec![[0.0; 4]; pixels], linear: vec![[0.0; 4]; pixels] };
        let stats = self.render_tiles(scene, region, options, progress, &mut |tile, part| {
            image.paste(&part, tile.x0 - region.x0, tile.y0 - region.y0);
            Ok(())
        })?;
        Ok((image, stats))
    }

    /// Renders the pixels of `region` tile by tile, each exactly as it is in a
    /// render of the whole image: each tile is traced, resolved, read back and
    /// handed to `tile(place in the image, pixels)` in reading order, so the
    /// host holds one tile and whatever `tile` keeps. An error from `tile`
    /// ends the render.
    pub fn render_tiles(
        &self,
        scene: &SceneBuffers,
        region: Region,
        options: &RenderOptions,
        progress: &mut dyn FnMut(u64, u64),
        tile: &mut dyn FnMut(Region, Image) -> Result<(), GpuError>,
    ) -> Result<RayStats, GpuError> {
        check_region(scene, region)?;
        self.pipelines.get(kernel_for(options.view), scene.specialization.dispatching(options.view), scene.view_tuning())?;
        if !self.profile.resolves_on_host {
            self.pipelines.get(Kernel::Resolve, Specialization::ALL, Tuning::PLAIN)?;
        }
        let scope = ErrorScope::push(&self.device);
        let result = (|| {
            let mut stats = RayStats::default();
            let total = u64::from(options.spp) * region.pixels();
            let mut done = 0;
            for place in region.tiles(scene.accum_pixels) {
                stats += self.trace_tile(scene, place, options, &mut |pixels| progress(done + pixels, total))?;
                done += u64::from(options.spp) * place.pixels();
                tile(place, self.resolve_buffer(&scene.accum, place.width(), place.height(), options)?)?;
            }
            Ok(stats)
        })();
        let scoped = scope.pop();
        if let Some(reason) = self.lost.lock().unwrap_or_else(|e| e.into_inner()).clone() {
            return Err(GpuError::Runtime(format!("the GPU device was lost ({reason})")));
        }
        if let Some(e) = scoped {
            return Err(GpuError::Runtime(one_line(&e)));
        }
        result
    }

    /// Accumulates `options.spp` samples per pixel from scratch over the whole
    /// image, tile by tile, without resolving: what a frame costs on the device.
    pub fn trace_frame(
        &self,
        scene: &SceneBuffers,
        options: &RenderOptions,
        progress: &mut dyn FnMut(u64, u64),
    ) -> Result<RayStats, GpuError> {
        let image = Region::whole(scene.width, scene.height);
        let total = u64::from(options.spp) * image.pixels();
        let (mut stats, mut done) = (RayStats::default(), 0);
        for tile in image.tiles(scene.accum_pixels) {
            stats += self.trace_tile(scene, tile, options, &mut |pixels| progress(done + pixels, total))?;
            done += u64::from(options.spp) * tile.pixels();
        }
        Ok(stats)
    }

    /// Accumulates `options.spp` samples per pixel of `tile` from scratch in
    /// the accumulation buffer, calling `progress(pixel samples done)`.
    fn trace_tile(
        &self,
        scene: &SceneBuffers,
        tile: Region,
        options: &RenderOptions,
        progress: &mut dyn FnMut(u64),
    ) -> Result<RayStats, GpuError> {
        // No clear: the first sample writes every pixel of the tile.
        let mut stats = RayStats::default();
        for sample in 0..options.spp {
            let done = u64::from(sample) * tile.pixels();
            stats += self.trace_sample(scene, tile, sample, options, &mut |pixels| progress(done + pixels))?;
        }
        Ok(stats)
    }

    /// Adds sample `sample_index` to every pixel of `tile`, in bands of rows,
    /// calling `progress(pixels done)` after each band.
    fn trace_sample(
        &self,
        scene: &SceneBuffers,
        tile: Region,
        sample_index: u32,
        options: &RenderOptions,
        progress: &mut dyn FnMut(u64),
    ) -> Result<RayStats, GpuError> {
        let width = tile.width();
        let stats_readback = self.readback_buffer(STAT_BYTES);
        let mut stats = RayStats::default();
        let mut y = tile.y0;
        while y < tile.y1 {
            let band = match options.band_rows {
                Some(rows) => rows.clamp(1, tile.y1 - y),
                None => self.bands.lock().unwrap_or_else(|e| e.into_inner()).rows(width, tile.y1 - y),
            };
            let mut encoder = self.device.create_command_encoder(&Default::default());
            encoder.clear_buffer(&scene.stats, 0, None);
            self.encode_band(scene, tile, sample_index, options, y..y + band, &mut encoder)?;
            encoder.copy_buffer_to_buffer(&scene.stats, 0, &stats_readback, 0, STAT_BYTES);
            let start = Instant::now();
            self.queue.submit([encoder.finish()]);
            let counts: Vec<u32> = bytemuck::pod_collect_to_vec(&self.read(&stats_readback)?);
            stats += RayStats::from_slots(&counts);
            y += band;
            progress(u64::from(y - tile.y0) * u64::from(width));
            if options.band_rows.is_none() {
                self.bands.lock().unwrap_or_else(|e| e.into_inner()).record(width, band, start.elapsed());
            }
        }
        Ok(stats)
    }

    /// Records the dispatch that adds sample `sample_index` to `rows` of
    /// `tile`, the part of the image the accumulation buffer holds.
    pub(crate) fn encode_band(
        &self,
        scene: &SceneBuffers,
        tile: Region,
        sample_index: u32,
        options: &RenderOptions,
        rows: std::ops::Range<u32>,
        encoder: &mut wgpu::CommandEncoder,
    ) -> Result<(), GpuError> {
        let region = DispatchParams {
            origin: [tile.x0, rows.start],
            end: [tile.x1, rows.end],
            tile_x: tile.x0,
            tile_y: tile.y0,
            tile_width: tile.width(),
            sample_index,
            seed: options.seed,
            sample_count: options.spp,
            pixel_filter: options.filter as u32,
            ..Zeroable::zeroed()
        };
        self.encode_dispatch(scene, options.view, region, encoder)
    }

    /// Writes `region` with `view` and records the dispatch of the kernel that
    /// view needs over it.
    pub(crate) fn encode_dispatch(
        &self,
        scene: &SceneBuffers,
        view: View,
        region: DispatchParams,
        encoder: &mut wgpu::CommandEncoder,
    ) -> Result<(), GpuError> {
        let kernel = kernel_for(view);
        let specialization = scene.specialization.dispatching(view);
        let tuning = sampled_tuning(kernel, scene.dispatch_tuning(&region), region.sample_count);
        // The primary kernel first finds the eye hits the trace kernel shades from.
        let eye_hits = kernel == Kernel::Trace && tuning.for_kernel(kernel).eye_hits();
        let kernels: &[Kernel] = if eye_hits { &[Kernel::Primary, kernel] } else { &[kernel] };
        let pipelines = kernels.iter().map(|&k| self.pipelines.get(k, specialization, tuning)).collect::<Result<Vec<_>, _>>()?;
        let region = DispatchParams { view: view as u32, ..region };
        self.queue.write_buffer(&scene.dispatch, 0, bytemuck::bytes_of(&region));
        let mut pass = encoder.begin_compute_pass(&Default::default());
        pass.set_bind_group(0, &scene.scene_bind, &[]);
        pass.set_bind_group(1, &scene.eye_tiles.bind, &[]);
        let [width, height] = [0, 1].map(|a| region.end[a] - region.origin[a]);
        for (&kernel, pipeline) in kernels.iter().zip(&pipelines) {
            pass.set_pipeline(pipeline);
            let [across, down] = tuning.workgroup_size(kernel).map(|n| n * tuning.block_side(kernel));
            pass.dispatch_workgroups(width.div_ceil(across), height.div_ceil(down), 1);
        }
        Ok(())
    }

    /// Turns the accumulated samples of an accumulation that holds the whole
    /// image (the viewer's) into display values (tone mapped, sRGB) and linear
    /// values, and reads both back.
    pub fn resolve(&self, scene: &SceneBuffers, options: &RenderOptions) -> Result<Image, GpuError> {
        scene.check_whole_image()?;
        self.resolve_buffer(&scene.accum, scene.width, scene.height, options)
    }

    /// [`Renderer::resolve`] without waiting (how a browser saves an image):
    /// the samples are read back and resolved by the host twin of the resolve
    /// kernel, `display::resolve`.
    pub fn resolve_later(&self, scene: &SceneBuffers, options: &RenderOptions) -> Result<Readback<Image>, GpuError> {
        scene.check_whole_image()?;
        let (width, height, options) = (scene.width, scene.height, *options);
        let bytes = u64::from(width * height) * PIXEL_BYTES;
        let readback = self.readback_buffer(bytes);
        let mut encoder = self.device.create_command_encoder(&Default::default());
        encoder.copy_buffer_to_buffer(&scene.accum, 0, &readback, 0, bytes);
        self.queue.submit([encoder.finish()]);
        Ok(Readback::start(readback, move |bytes| Ok(display::resolve(&bytemuck::pod_collect_to_vec(bytes), width, height, &options))))
    }

    /// Resolves `samples` (rgb sums and sample counts) with the resolve kernel,
    /// whatever the adapter: what the CPU twin in `display.rs` is tested against.
    pub fn resolve_samples(&self, samples: &[[f32; 4]], width: u32, height: u32, options: &RenderOptions) -> Result<Image, GpuError> {
        let buffer = self.device.create_buffer_init(&wgpu::util::BufferInitDescriptor {
            label: Some("samples"),
            contents: bytemuck::cast_slice(samples),
            usage: wgpu::BufferUsages::STORAGE,
        });
        self.resolve_on_device(&buffer, width, height, options)
    }

    /// The kernels whose pipelines this renderer has created so far.
    pub fn kernels_created(&self) -> Vec<Kernel> {
        self.pipelines.kernels()
    }

    /// Each pipeline created so far, by kernel and the specialisation and
    /// tuning it was compiled for (a software rasteriser compiles each at its
    /// first dispatch).
    pub fn pipelines_created(&self) -> Vec<(Kernel, Specialization, Tuning)> {
        self.pipelines.built()
    }

    /// Whether renders resolve on the host (a CPU adapter) instead of with the
    /// resolve kernel.
    pub fn resolves_on_host(&self) -> bool {
        self.profile.resolves_on_host
    }

    fn resolve_buffer(&self, samples: &wgpu::Buffer, width: u32, height: u32, options: &RenderOptions) -> Result<Image, GpuError> {
        if !self.profile.resolves_on_host {
            return self.resolve_on_device(samples, width, height, options);
        }
        let bytes = u64::from(width * height) * PIXEL_BYTES;
        let readback = self.readback_buffer(bytes);
        let mut encoder = self.device.create_command_encoder(&Default::default());
        encoder.copy_buffer_to_buffer(samples, 0, &readback, 0, bytes);
        self.queue.submit([encoder.finish()]);
        let samples: Vec<[f32; 4]> = bytemuck::pod_collect_to_vec(&self.read(&readback)?);
        Ok(display::resolve(&samples, width, height, options))
    }

    fn resolve_on_device(&self, samples: &wgpu::Buffer, width: u32, height: u32, options: &RenderOptions) -> Result<Image, GpuError> {
        let resolve = self.pipelines.get(Kernel::Resolve, Specialization::ALL, Tuning::PLAIN)?;
        let pixels = width * height;
        let bytes = u64::from(pixels) * PIXEL_BYTES;
        let params = ResolveParams {
            pixel_count: pixels,
            tone_map: options.tone_map as u32,
            exposure: options.exposure,
            view: options.view as u32,
            scale: options.view_scale,
            ..Zeroable::zeroed()
        };
        let params_buffer = self.device.create_buffer_init(&wgpu::util::BufferInitDescriptor {
            label: Some("resolve params"),
            contents: bytemuck::bytes_of(&params),
            usage: wgpu::BufferUsages::UNIFORM,
        });
        let output = |label| {
            self.device.create_buffer(&wgpu::BufferDescriptor {
                label: Some(label),
                size: bytes,
                usage: wgpu::BufferUsages::STORAGE | wgpu::BufferUsages::COPY_SRC,
                mapped_at_creation: false,
            })
        };
        let (display, linear) = (output("display"), output("linear"));
        let bind = self.device.create_bind_group(&wgpu::BindGroupDescriptor {
            label: Some("resolve"),
            layout: &resolve.get_bind_group_layout(0),
            entries: &[
                wgpu::BindGroupEntry { binding: 0, resource: params_buffer.as_entire_binding() },
                wgpu::BindGroupEntry { binding: 1, resource: samples.as_entire_binding() },
                wgpu::BindGroupEntry { binding: 2, resource: display.as_entire_binding() },
                wgpu::BindGroupEntry { binding: 3, resource: linear.as_entire_binding() },
            ],
        });
        let display_readback = self.readback_buffer(bytes);
        let linear_readback = self.readback_buffer(bytes);
        let mut encoder = self.device.create_command_encoder(&Default::default());
        {
            let mut pass = encoder.begin_compute_pass(&Default::default());
            pass.set_pipeline(&resolve);
            pass.set_bind_group(0, &bind, &[]);
            dispatch_linear(&mut pass, pixels.div_ceil(64), self.device.limits().max_compute_workgroups_per_dimension);
        }
        encoder.copy_buffer_to_buffer(&display, 0, &display_readback, 0, bytes);
        encoder.copy_buffer_to_buffer(&linear, 0, &linear_readback, 0, bytes);
        self.queue.submit([encoder.finish()]);
        let display = bytemuck::pod_collect_to_vec(&self.read(&display_readback)?);
        let linear = bytemuck::pod_collect_to_vec(&self.read(&linear_readback)?);
        Ok(Image { width, height, display, linear })
    }

    pub(crate) fn readback_buffer(&self, size: u64) -> wgpu::Buffer {
        self.device.create_buffer(&wgpu::BufferDescriptor {
            label: Some("readback"),
            size,
            usage: wgpu::BufferUsages::MAP_READ | wgpu::BufferUsages::COPY_DST,
            mapped_at_creation: false,
        })
    }

    /// Waits for the queue and copies a mappable buffer's bytes out.
    pub(crate) fn read(&self, buffer: &wgpu::Buffer) -> Result<Vec<u8>, GpuError> {
        Readback::start(buffer.clone(), |bytes| Ok(bytes.to_vec())).wait(&self.device)
    }
}

/// Refuses a region that is empty or reaches outside the scene's image.
fn check_region(scene: &SceneBuffers, region: Region) -> Result<(), GpuError> {
    if region.is_empty() || !Region::whole(scene.width, scene.height).contains(&region) {
        return Err(GpuError::Region(format!(
            "the region {region} (x0 y0 x1 y1) is empty or not inside the {}x{} image",
            scene.width, scene.height
        )));
    }
    Ok(())
}

/// The kernel that traces `view`.
fn kernel_for(view: View) -> Kernel {
    match view {
        View::Diffuse => Kernel::Diffuse,
        _ if view.is_primary_only() => Kernel::Primary,
        _ => Kernel::Trace,
    }
}

/// The tuning `kernel` runs when a render takes `sample_count` samples a
/// pixel: the eye tiles serve rays through pixel centres, so only a
/// one-sample render's trace kernel takes their eye hits.
fn sampled_tuning(kernel: Kernel, tuning: Tuning, sample_count: u32) -> Tuning {
    if kernel == Kernel::Trace && sample_count != 1 { tuning.without_eye_tiles() } else { tuning }
}

/// A 1D dispatch of `groups` workgroups, folded into rows when it exceeds the
/// per-dimension limit; the kernel rebuilds the linear index from both.
fn dispatch_linear(pass: &mut wgpu::ComputePass, groups: u32, max_per_dim: u32) {
    let x = groups.clamp(1, max_per_dim);
    pass.dispatch_workgroups(x, groups.div_ceil(x), 1);
}

/// The resources of the trace and primary kernels (shaders/lib/bindings.wgsl,
/// scene_arrays.wgsl and bvh_records.wgsl, or their textures in shaders/fast/):
/// the scene uniforms, the scene's arrays (primitives, BVH records, polygon
/// points and BVH grids) as storage buffers or textures, as `arrays` says,
/// the materials' and lights' uniform buffers, the accumulation image, the ray
/// counts, the dispatch parameters and the BVH's records and grids again in
/// uniform buffers (shaders/fast/uniform_tree.wgsl).
fn scene_bind_group_layout(device: &wgpu::Device, arrays: SceneArrays) -> wgpu::BindGroupLayout {
    let buffer = |binding: u32, ty: wgpu::BufferBindingType| wgpu::BindGroupLayoutEntry {
        binding,
        visibility: wgpu::ShaderStages::COMPUTE,
        ty: wgpu::BindingType::Buffer { ty, has_dynamic_offset: false, min_binding_size: None },
        count: None,
    };
    let array = |binding: u32| match arrays {
        SceneArrays::Buffers => buffer(binding, wgpu::BufferBindingType::Storage { read_only: true }),
        SceneArrays::Textures => scene_textures::layout_entry(binding),
    };
    let read_write = wgpu::BufferBindingType::Storage { read_only: false };
    let entries = [
        buffer(0, wgpu::BufferBindingType::Uniform),
        array(1),
        array(2),
        buffer(3, wgpu::BufferBindingType::Uniform),
        buffer(4, wgpu::BufferBindingType::Uniform),
        array(5),
        buffer(6, read_write),
        buffer(7, read_write),
        array(8),
        buffer(9, wgpu::BufferBindingType::Uniform),
        buffer(10, wgpu::BufferBindingType::Uniform),
        buffer(11, wgpu::BufferBindingType::Uniform),
    ];
    device.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor { label: Some("scene"), entries: &entries })
}

