//! The ray-traced image: the canvas it accumulates on (the scene on the device
//! at the current render size), the texture egui draws, where it is drawn, and
//! whether it is behind the scene and settings. Each frame adds its share of
//! samples and presents them.

use std::path::Path;
use std::sync::Arc;
use std::time::Duration;

use web_time::Instant;
use egui::{Pos2, Rect, Vec2};
use glam::Vec3;
use glint_encoding::gpu_types::{self, View};
use glint_gpu::schedule::BandScheduler;
use glint_gpu::{Bits, GpuError, Readback};
use glint_scene::Camera;

use crate::one_line;
use crate::document::LoadedScene;
use crate::engine::{Accumulation, Canvas, CanvasKey, Completions, Kernels, Step};
use crate::jobs::{Job, Jobs};
use crate::settings::Settings;

pub(crate) struct TracedImage {
    device: wgpu::Device,
    egui_renderer: Arc<egui::mutex::RwLock<egui_wgpu::Renderer>>,
    /// The largest render side the device and the scene model allow.
    max_side: u32,
    canvas: Option<Canvas>,
    texture: Option<egui::TextureId>,
    pub preparing: bool,
    /// The canvas that could not be made, not tried again until something changes.
    failed_key: Option<CanvasKey>,
    pub acc: Accumulation,
    /// The scene or settings changed since the canvas was last written.
    pub dirty: bool,
    /// Only the display mapping changed: present again without tracing.
    pub represent: bool,
    /// Counts the writes of the scene into the canvas, so what was read back
    /// from it can tell when it is out of date.
    pub syncs: u64,
    /// Where the image is drawn, in points.
    pub rect: Option<Rect>,
    wanted_size: Option<(u32, u32)>,
    pub frame_time: FrameTime,
    completions: Completions,
}

impl TracedImage {
    pub fn new(device: wgpu::Device, egui_renderer: Arc<egui::mutex::RwLock<egui_wgpu::Renderer>>, max_side: u32) -> Self {
        Self {
            completions: Completions::of(device.adapter_info().backend),
            device,
            egui_renderer,
            max_side,
            canvas: None,
            texture: None,
            preparing: false,
            failed_key: None,
            acc: Accumulation::new(BandScheduler::first_image()),
            dirty: false,
            represent: false,
            syncs: 0,
            rect: None,
            wanted_size: None,
            frame_time: FrameTime::default(),
        }
    }

    /// The size of the rendered image in pixels.
    pub fn render_size(&self) -> Option<(u32, u32)> {
        self.canvas.as_ref().map(Canvas::size)
    }

    /// The texture to draw, once there is a canvas.
    pub fn texture(&self) -> Option<egui::TextureId> {
        self.canvas.as_ref().and(self.texture)
    }

    /// The canvas holds `doc`'s scene.
    pub fn canvas_is_current(&self, doc: Option<&LoadedScene>) -> bool {
        match (&self.canvas, doc) {
            (Some(c), Some(d)) => c.scene_generation == d.generation,
            _ => false,
        }
    }

    /// The canvas, when it holds `doc` as it is now.
    pub fn synced_canvas(&self, doc: Option<&LoadedScene>) -> Option<&Canvas> {
        self.canvas.as_ref().filter(|_| self.canvas_is_current(doc) && !self.dirty)
    }

    /// Samples per pixel in the image of `doc` as it is now.
    pub fn samples(&self, doc: Option<&LoadedScene>) -> u32 {
        if self.canvas_is_current(doc) && !self.dirty { self.acc.samples } else { 0 }
    }

    /// All `target` samples of `doc` as it is now are in and shown.
    pub fn is_converged(&self, doc: Option<&LoadedScene>, target: u32) -> bool {
        self.canvas_is_current(doc)
            && !self.dirty
            && !self.preparing
            && self.wanted_size == self.render_size()
            && self.acc.samples >= target
            && self.acc.presented
    }

    /// Draws the image in `rect`, rendered at `pixels` (width and height,
    /// rounded and kept within what the device allows).
    pub fn place(&mut self, rect: Rect, pixels: Vec2) {
        self.rect = Some(rect);
        let side = |pixels: f32| (pixels.round() as u32).clamp(1, self.max_side);
        self.wanted_size = Some((side(pixels.x), side(pixels.y)));
    }

    /// New kernels: a canvas that failed with the old ones is worth another try.
    pub fn kernels_changed(&mut self) {
        self.failed_key = None;
    }

    /// A new scene loaded: it is worth another try, and is written into the canvas.
    pub fn scene_changed(&mut self) {
        self.failed_key = None;
        self.dirty = true;
    }

    /// The canvas `doc` needs with `kernels`, if one can be made.
    fn canvas_key(&self, kernels: Option<&Arc<Kernels>>, doc: Option<&LoadedScene>) -> Option<CanvasKey> {
        let (kernels, doc, size) = (kernels?, doc?, self.wanted_size?);
        Some(CanvasKey {
            kernels: Arc::as_ptr(kernels) as usize,
            scene_generation: doc.generation,
            size,
        })
    }

    /// Starts building a new canvas when the size, scene or kernels changed.
    /// Lights need none: the device holds room for as many as a scene may
    /// have (gpu_types::MAX_LIGHTS), and the viewer turns them on in place.
    pub fn ensure_canvas(&mut self, kernels: Option<&Arc<Kernels>>, doc: Option<&LoadedScene>, view: View, jobs: &Jobs<Job>) {
        if self.preparing {
            return;
        }
        let (Some(key), Some(doc), Some(kernels)) = (self.canvas_key(kernels, doc), doc, kernels) else { return };
        if self.failed_key.as_ref() == Some(&key) {
            return;
        }
        if let Some(c) = &self.canvas {
            if Arc::ptr_eq(&c.kernels, kernels) && c.scene_generation == doc.generation && c.size() == key.size {
                return;
            }
        }
        let snapshot = doc.scene.clone();
        let kernels = Arc::clone(kernels);
        self.preparing = true;
        let job_key = key.clone();
        jobs.spawn("upload", move || {
            let result = Canvas::new(kernels, &snapshot, view, key.size, key.scene_generation).map(Box::new);
            Job::Prepared { result, key: job_key }
        });
    }

    /// Takes a finished canvas, if `doc` with `kernels` still needs it; a
    /// failure goes to `error`.
    pub fn finish_prepare(
        &mut self,
        key: CanvasKey,
        result: Result<Box<Canvas>, GpuError>,
        kernels: Option<&Arc<Kernels>>,
        doc: Option<&LoadedScene>,
        error: &mut Option<String>,
    ) {
        self.preparing = false;
        match result {
            Ok(canvas) if Some(&key) == self.canvas_key(kernels, doc).as_ref() => self.install_canvas(*canvas),
            // Outdated: a fresh one is on its way.
            Ok(_) => {}
            Err(e) => {
                *error = Some(one_line(e));
                self.failed_key = Some(key);
            }
        }
    }

    fn install_canvas(&mut self, canvas: Canvas) {
        let mut renderer = self.egui_renderer.write();
        let filter = wgpu::FilterMode::Linear;
        match self.texture {
            Some(id) => renderer.update_egui_texture_from_wgpu_texture(&self.device, &canvas.target.view, filter, id),
            None => self.texture = Some(renderer.register_native_texture(&self.device, &canvas.target.view, filter)),
        }
        // Before the first canvas the window shows nothing, and the warm-up
        // compiled its kernel: its bands can be long from the second on.
        let bands = if self.canvas.is_none() { BandScheduler::first_image() } else { BandScheduler::new_canvas() };
        self.canvas = Some(canvas);
        self.acc = Accumulation::new(bands);
        self.dirty = true;
    }

    /// Writes the edited scene into the canvas and starts accumulating anew.
    /// False when there is no canvas yet; more lights than the device holds
    /// are an error.
    fn sync(&mut self, doc: &LoadedScene, settings: &Settings) -> Result<bool, GpuError> {
        let specular = settings.specular;
        let Some(canvas) = &mut self.canvas else { return Ok(false) };
        let scene = &doc.scene;
        let materials: Vec<_> = scene.materials.iter().map(|m| gpu_types::pack_material(&specular.apply(m))).collect();
        let lights: Vec<_> = scene.lights.iter().filter(|l| l.enabled).map(gpu_types::pack_light).collect();
        let (width, height) = canvas.size();
        let uniforms = gpu_types::scene_uniforms(scene, width, height, lights.len() as u32, canvas.prepared.buffers.layout());
        canvas.take_edits(&materials, &lights, &uniforms, settings.view)?;
        let renderer = &canvas.kernels.renderer;
        let buffers = &mut canvas.prepared.buffers;
        renderer.write_materials(buffers, &materials)?;
        renderer.write_lights(buffers, &lights)?;
        renderer.write_uniforms(buffers, &uniforms)?;
        self.acc.restart();
        self.syncs += 1;
        Ok(true)
    }

    /// This frame's share of the ray tracing of `doc`; a failure goes to `error`.
    pub fn render(&mut self, ctx: &egui::Context, doc: Option<&LoadedScene>, settings: &Settings, error: &mut Option<String>) {
        let Some(doc) = doc.filter(|&d| self.canvas_is_current(Some(d))) else { return };
        if self.dirty {
            match self.sync(doc, settings) {
                Ok(true) => self.dirty = false,
                Ok(false) => return,
                Err(e) => {
                    *error = Some(one_line(e));
                    return;
                }
            }
        }
        let Some(options) = self.canvas.as_ref().map(|c| settings.trace_options(c)) else { return };
        let target = settings.target_samples();
        let Some(canvas) = self.canvas.as_mut() else { return };
        // A finished band asks for one frame. egui answers a request without
        // delay with two, and in a browser each frame is a paint that the
        // device queues before the next band.
        let wake = ctx.clone();
        let step = match self.acc.step(canvas, &options, target, move || wake.request_repaint_after(Duration::from_millis(1))) {
            Ok(step) => step,
            Err(e) => {
                *error = Some(one_line(e));
                return;
            }
        };
        self.frame_time.rendering = step != Step::Done;
        // Progressive display shows every band: after a change the new image
        // replaces the old one row by row, so the view stays live even when a
        // whole sample takes several frames.
        if step == Step::Traced && (settings.progressive || self.acc.samples >= target || !self.acc.presented) {
            canvas.present(&options);
            self.acc.presented = true;
            self.represent = false;
        }
        match self.completions.next_frame(step, self.acc.has_room()) {
            Some(Duration::ZERO) => ctx.request_repaint(),
            Some(after) => ctx.request_repaint_after(after),
            None => {}
        }
        if std::mem::take(&mut self.represent) && self.acc.samples > 0 && (settings.progressive || self.acc.samples >= target) {
            canvas.present(&options);
        }
        if let Err(e) = self.acc.count_rays(canvas) {
            *error = Some(one_line(e));
        }
    }

    /// Resolves the image of `doc` as `settings` show it and writes it to `path`,
    /// in the format its extension names (PNG, PPM, EXR or PFM).
    pub fn save_png(&self, path: &Path, doc: Option<&LoadedScene>, settings: &Settings) -> Result<glint_gpu::Image, GpuError> {
        match &self.canvas {
            Some(canvas) if self.canvas_is_current(doc) => canvas
                .renderer()
                .resolve(&canvas.prepared.buffers, &settings.present_options(canvas))
                .and_then(|image| glint_gpu::write_image(&image, path, Bits::Eight).map(|()| image).map_err(GpuError::from)),
            _ => Err(GpuError::Output("there is no image to save yet".into())),
        }
    }

    /// [`TracedImage::save_png`]'s image, read back when the device has it.
    pub fn image_later(&self, doc: Option<&LoadedScene>, settings: &Settings) -> Result<Readback<glint_gpu::Image>, GpuError> {
        match &self.canvas {
            Some(canvas) if self.canvas_is_current(doc) => canvas.renderer().resolve_later(&canvas.prepared.buffers, &settings.present_options(canvas)),
            _ => Err(GpuError::Output("there is no image to save yet".into())),
        }
    }

    /// Image position in render pixels of a point on screen.
    fn to_pixels(&self, pos: Pos2) -> Option<(f32, f32)> {
        let (rect, (w, h)) = (self.rect?, self.render_size()?);
        let p = (pos - rect.min) / rect.size();
        Some((p.x * w as f32, p.y * h as f32))
    }

    /// Screen position of a world point seen by `camera`, if in front of it.
    pub fn to_screen(&self, camera: &Camera, p: Vec3) -> Option<Pos2> {
        let (rect, (w, h)) = (self.rect?, self.render_size()?);
        let (x, y) = camera.project(w, h, p.as_dvec3())?;
        Some(rect.min + Vec2::new(x as f32 / w as f32, y as f32 / h as f32) * rect.size())
    }

    /// The object drawn at `pos` (`None` for the sky), read back from the
    /// device; nothing when the image shows no pixel of `doc` as it is now there.
    pub fn object_at(&self, doc: &LoadedScene, pos: Pos2) -> Option<Result<Option<u32>, GpuError>> {
        let (x, y) = self.to_pixels(pos)?;
        if !self.canvas_is_current(Some(doc)) || self.dirty {
            return None;
        }
        let canvas = self.canvas.as_ref()?;
        // Negative positions (left of or above the image) are not a pixel.
        let (x, y) = (x.floor().max(-1.0) as i64, y.floor().max(-1.0) as i64);
        let (Ok(x), Ok(y)) = (u32::try_from(x), u32::try_from(y)) else { return None };
        Some(canvas.renderer().pick(&canvas.prepared.buffers, x, y))
    }
}

/// How long a frame takes while the image renders.
#[derive(Default)]
pub(crate) struct FrameTime {
    last_frame: Option<Instant>,
    /// The last frame traced or waited for the device.
    rendering: bool,
    /// Milliseconds per frame, smoothed.
    pub ms: f32,
}

impl FrameTime {
    pub fn begin_frame(&mut self) {
        let now = Instant::now();
        // Frame time counts frames that follow a rendering frame, not idle waits.
        if let (Some(last), true) = (self.last_frame.replace(now), self.rendering) {
            let ms = now.duration_since(last).as_secs_f32() * 1000.0;
            self.ms = if self.ms == 0.0 { ms } else { 0.9 * self.ms + 0.1 * ms };
        }
    }
}
