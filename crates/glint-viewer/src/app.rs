//! The viewer window: a side panel of settings, the ray-traced image in the
//! central panel, a status bar. The image is a GPU texture the present kernel
//! writes and egui draws; it never goes through the CPU.

use std::path::{Path, PathBuf};
use std::sync::{Arc, Mutex};
use std::time::{Duration, Instant};

use egui::{Color32, Pos2, Rect, Sense, Stroke, StrokeKind, Vec2};
use glam::Vec3;
use glint_gpu::shaders::{ShaderSource, SOURCES};
use glint_gpu::{GpuError, PngBits, RenderOptions, ToneMap};
use glint_scene::gpu_types::{self, View};
use glint_scene::toml_scene::MAX_IMAGE_SIDE;
use glint_scene::{Attenuation, Camera, DepthCue, Light, LightKind, LoadError, Material, Scene, SpecularModel};

use crate::camera_control;
use crate::engine::{Accumulation, Canvas, Kernels, Step};
use crate::jobs::Jobs;
use crate::watch::Watch;

/// Extra room in the lights buffer, so adding a light rarely needs a new upload.
const SPARE_LIGHTS: usize = 4;
/// How near (in points) a click must land to a light's marker to grab it.
const LIGHT_GRAB_RADIUS: f32 = 10.0;
/// Orbit speed, radians per point dragged.
const ORBIT_SPEED: f32 = 0.008;

/// What the viewer opens with.
pub struct ViewerOptions {
    pub scene: Option<PathBuf>,
    /// Where the WGSL comes from; a folder is watched and reloaded on change.
    pub shaders: ShaderSource,
    /// The TOML text of `scene` when it is built into the program rather than
    /// read from disk (`scene` then only names it, and is not watched).
    pub scene_text: Option<&'static str>,
}

impl ViewerOptions {
    /// Opens `scene`, with shaders hot-reloaded from this source tree's
    /// `shaders/` folder when it exists (else the built-in copies).
    pub fn new(scene: Option<PathBuf>) -> Self {
        let dir = ShaderSource::source_dir();
        let shaders = if dir.is_dir() { ShaderSource::Dir(dir) } else { ShaderSource::Embedded };
        Self { scene, shaders, scene_text: None }
    }
}

/// Which specular model shading uses.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum SpecularChoice {
    /// Each material's own.
    PerMaterial,
    Phong,
    Blinn,
}

impl SpecularChoice {
    pub fn apply(self, m: &Material) -> Material {
        let specular_model = match self {
            SpecularChoice::PerMaterial => m.specular_model,
            SpecularChoice::Phong => SpecularModel::Phong,
            SpecularChoice::Blinn => SpecularModel::BlinnPhong,
        };
        Material { specular_model, ..m.clone() }
    }
}

/// How the image is rendered and shown.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct Settings {
    /// Samples per pixel the image converges to.
    pub spp: u32,
    /// Show the image after every sample; otherwise only once all are in.
    pub progressive: bool,
    pub view: View,
    pub exposure: f32,
    pub tone_map: ToneMap,
    /// Render resolution relative to the panel's pixels.
    pub scale: f32,
    pub specular: SpecularChoice,
}

impl Default for Settings {
    fn default() -> Self {
        Self {
            spp: 16,
            progressive: true,
            view: View::Shaded,
            exposure: 1.0,
            tone_map: ToneMap::Clamp,
            scale: 1.0,
            specular: SpecularChoice::PerMaterial,
        }
    }
}

/// The scene being viewed and edited.
pub(crate) struct Document {
    pub scene: Scene,
    /// The camera the file gave, for "reset".
    pub file_camera: Camera,
    /// Counts loads, so work for an older scene is recognised.
    pub generation: u64,
    pub bounds: (Vec3, Vec3),
    /// Half the diagonal of the bounds: how large the scene is.
    pub radius: f32,
    /// The field of view to return to from an orthographic camera.
    pub fov: f32,
}

impl Document {
    fn new(scene: Scene, generation: u64) -> Self {
        let bounds = gpu_types::primitive_bounds(&scene)
            .into_iter()
            .fold((Vec3::INFINITY, Vec3::NEG_INFINITY), |(lo, hi), (a, b)| (lo.min(a), hi.max(b)));
        let radius = if bounds.0.cmple(bounds.1).all() { (bounds.1 - bounds.0).length() / 2.0 } else { 1.0 };
        let fov = match scene.camera.projection {
            glint_scene::Projection::Perspective { fov_y_degrees } => fov_y_degrees,
            glint_scene::Projection::Orthographic { .. } => 40.0,
        };
        Self { file_camera: scene.camera, scene, generation, bounds, radius: radius.max(1e-3), fov }
    }

    /// About the distance from the eye to the far side of the scene.
    pub fn depth_extent(&self) -> f32 {
        let (lo, hi) = self.bounds;
        let centre = if lo.cmple(hi).all() { (lo + hi) / 2.0 } else { self.scene.camera.look_at };
        (self.scene.camera.eye - centre).length() + self.radius
    }

    fn aspect(&self) -> f32 {
        self.scene.width as f32 / self.scene.height as f32
    }
}

/// The parts of a scene the side panel edits, to notice a change.
#[derive(Clone, PartialEq)]
struct Editable {
    camera: Camera,
    background: Vec3,
    ambient: Vec3,
    lights: Vec<Light>,
    materials: Vec<Material>,
    depth_cue: Option<DepthCue>,
    render: glint_scene::RenderSettings,
}

impl Editable {
    fn of(s: &Scene) -> Self {
        Self {
            camera: s.camera,
            background: s.background,
            ambient: s.ambient,
            lights: s.lights.clone(),
            materials: s.materials.clone(),
            depth_cue: s.depth_cue,
            render: s.render,
        }
    }
}

/// One line per kind of problem, shown above the image until it is fixed.
#[derive(Default)]
pub(crate) struct Errors {
    pub scene: Option<String>,
    pub shader: Option<String>,
    pub gpu: Option<String>,
}

/// A finished background job.
enum Job {
    Compiled { result: Result<Kernels, GpuError>, fallback_error: Option<GpuError> },
    Loaded { generation: u64, path: PathBuf, reload: bool, result: Result<Scene, LoadError> },
    Prepared { key: CanvasKey, result: Result<Box<Canvas>, GpuError> },
}

/// What a canvas was made for; a canvas whose key differs is out of date.
#[derive(Clone, PartialEq)]
struct CanvasKey {
    kernels: usize,
    scene_generation: u64,
    size: (u32, u32),
    lights: usize,
}

pub struct ViewerApp {
    device: wgpu::Device,
    queue: wgpu::Queue,
    egui_renderer: Arc<egui::mutex::RwLock<egui_wgpu::Renderer>>,
    adapter: String,
    max_side: u32,
    jobs: Jobs<Job>,
    device_errors: Arc<Mutex<Vec<String>>>,

    shaders: ShaderSource,
    shader_watch: Option<Watch>,
    kernels: Option<Arc<Kernels>>,
    compiling: bool,
    compile_again: bool,

    pub(crate) scene_path: Option<PathBuf>,
    /// The text of a built-in scene, read instead of `scene_path`.
    scene_text: Option<&'static str>,
    scene_watch: Option<Watch>,
    load_generation: u64,
    scene_generation: u64,
    loading: bool,
    pub(crate) doc: Option<Document>,

    canvas: Option<Canvas>,
    texture: Option<egui::TextureId>,
    preparing: bool,
    failed_key: Option<CanvasKey>,
    acc: Accumulation,
    /// The scene or settings changed since the canvas was last written.
    dirty: bool,
    /// Only the display mapping changed: present again without tracing.
    represent: bool,

    pub(crate) settings: Settings,
    pub(crate) selected_object: Option<usize>,
    pub(crate) selected_light: Option<usize>,
    /// The light marker being dragged in the image.
    dragging_light: Option<usize>,
    image_rect: Option<Rect>,
    wanted_size: Option<(u32, u32)>,

    pub(crate) open_path: String,
    pub(crate) screenshot_path: String,
    pub(crate) save_path: String,
    /// The outcome of the last file action: (message, is an error).
    pub(crate) notice: Option<(String, bool)>,
    pub(crate) errors: Errors,

    last_frame: Option<Instant>,
    /// The last frame traced or waited for the device.
    rendering: bool,
    frame_ms: f32,
}

/// An error message on one line.
pub(crate) fn one_line(message: impl std::fmt::Display) -> String {
    message.to_string().split_whitespace().collect::<Vec<_>>().join(" ")
}

/// Error from starting the viewer.
#[derive(Debug)]
pub struct StartError(pub String);

impl std::fmt::Display for StartError {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(&self.0)
    }
}

impl std::error::Error for StartError {}

impl ViewerApp {
    /// Starts compiling the kernels and loading the scene in the background,
    /// on eframe's wgpu device.
    pub fn new(cc: &eframe::CreationContext<'_>, options: ViewerOptions) -> Result<Self, StartError> {
        let rs = cc
            .wgpu_render_state
            .as_ref()
            .ok_or_else(|| StartError("the viewer needs eframe's wgpu renderer".into()))?;
        let info = rs.adapter.get_info();
        let device_errors = Arc::new(Mutex::new(Vec::new()));
        let sink = Arc::clone(&device_errors);
        rs.device.on_uncaptured_error(Arc::new(move |e: wgpu::Error| {
            sink.lock().expect("never poisoned").push(one_line(e));
        }));
        let shader_watch = match &options.shaders {
            ShaderSource::Dir(dir) => {
                let files = SOURCES.iter().map(|f| dir.join(f)).collect();
                Some(Watch::new(files))
            }
            ShaderSource::Embedded => None,
        };
        let mut app = Self {
            device: rs.device.clone(),
            queue: rs.queue.clone(),
            egui_renderer: Arc::clone(&rs.renderer),
            adapter: format!("{} ({:?})", info.name, info.backend),
            max_side: rs.device.limits().max_texture_dimension_2d.min(MAX_IMAGE_SIDE),
            jobs: Jobs::new(cc.egui_ctx.clone()),
            device_errors,
            shaders: options.shaders,
            shader_watch,
            kernels: None,
            compiling: false,
            compile_again: false,
            scene_path: None,
            scene_text: None,
            scene_watch: None,
            load_generation: 0,
            scene_generation: 0,
            loading: false,
            doc: None,
            canvas: None,
            texture: None,
            preparing: false,
            failed_key: None,
            acc: Accumulation::default(),
            dirty: false,
            represent: false,
            settings: Settings::default(),
            selected_object: None,
            selected_light: None,
            dragging_light: None,
            image_rect: None,
            wanted_size: None,
            open_path: String::new(),
            screenshot_path: String::new(),
            save_path: String::new(),
            notice: None,
            errors: Errors::default(),
            last_frame: None,
            rendering: false,
            frame_ms: 0.0,
        };
        if let Some(warning) = glint_gpu::device::old_lavapipe_warning(&info) {
            app.notice = Some((warning, true));
        }
        app.start_compile();
        match (options.scene, options.scene_text) {
            (Some(name), Some(text)) => app.open_built_in(name, text),
            (Some(path), None) => app.open(path),
            (None, _) => {}
        }
        Ok(app)
    }

    // ---- for tests and the status bar ----

    pub fn scene(&self) -> Option<&Scene> {
        self.doc.as_ref().map(|d| &d.scene)
    }

    /// Samples per pixel the current image converges to.
    pub fn target_samples(&self) -> u32 {
        if self.settings.view.is_primary_only() { 1 } else { self.settings.spp }
    }

    /// Samples per pixel in the image of the current scene and settings.
    pub fn samples(&self) -> u32 {
        if self.canvas_is_current() && !self.dirty { self.acc.samples } else { 0 }
    }

    /// All samples of the current state are in and shown.
    pub fn is_converged(&self) -> bool {
        self.canvas_is_current()
            && !self.dirty
            && !self.preparing
            && self.wanted_size == self.canvas.as_ref().map(Canvas::size)
            && self.acc.samples >= self.target_samples()
            && self.acc.presented
    }

    /// Where the image is drawn, in points.
    pub fn image_rect(&self) -> Option<Rect> {
        self.image_rect
    }

    /// The size of the rendered image in pixels.
    pub fn render_size(&self) -> Option<(u32, u32)> {
        self.canvas.as_ref().map(Canvas::size)
    }

    pub fn selected_object(&self) -> Option<usize> {
        self.selected_object
    }

    /// The problems shown above the image, one line each.
    pub fn errors(&self) -> Vec<String> {
        let e = &self.errors;
        [&e.scene, &e.shader, &e.gpu].into_iter().flatten().cloned().collect()
    }

    fn canvas_is_current(&self) -> bool {
        match (&self.canvas, &self.doc) {
            (Some(c), Some(d)) => c.scene_generation == d.generation,
            _ => false,
        }
    }

    // ---- background work ----

    fn start_compile(&mut self) {
        if self.compiling {
            self.compile_again = true;
            return;
        }
        self.compiling = true;
        let (device, queue, source) = (self.device.clone(), self.queue.clone(), self.shaders.clone());
        let first = self.kernels.is_none();
        self.jobs.spawn("shaders", move || match Kernels::compile(&device, &queue, &source) {
            // A broken shader file at start-up still gives a working viewer.
            Err(e) if first && matches!(source, ShaderSource::Dir(_)) => Job::Compiled {
                result: Kernels::compile(&device, &queue, &ShaderSource::Embedded),
                fallback_error: Some(e),
            },
            result => Job::Compiled { result, fallback_error: None },
        });
    }

    /// Opens the scene at `path`, keeping the current one until it has loaded.
    pub(crate) fn open(&mut self, path: PathBuf) {
        self.scene_watch = Some(Watch::new(vec![path.clone()]));
        self.open_path = path.display().to_string();
        self.scene_path = Some(path);
        self.scene_text = None;
        self.start_load(false);
    }

    /// Opens a TOML scene built into the program, called `name`.
    fn open_built_in(&mut self, name: PathBuf, text: &'static str) {
        self.scene_watch = None;
        self.open_path = String::new();
        self.scene_path = Some(name);
        self.scene_text = Some(text);
        self.start_load(false);
    }

    fn start_load(&mut self, reload: bool) {
        let Some(path) = self.scene_path.clone() else { return };
        self.load_generation += 1;
        self.loading = true;
        let generation = self.load_generation;
        let text = self.scene_text;
        self.jobs.spawn("load", move || {
            let result = match text {
                Some(text) => glint_scene::toml_scene::parse(text, &path),
                None => glint_scene::load(&path),
            };
            Job::Loaded { generation, path, reload, result }
        });
    }

    fn finish_jobs(&mut self, ctx: &egui::Context) {
        for job in self.jobs.finished() {
            match job {
                Job::Compiled { result, fallback_error } => {
                    self.compiling = false;
                    match result {
                        Ok(kernels) => {
                            self.kernels = Some(Arc::new(kernels));
                            self.errors.shader = fallback_error.map(|e| one_line(format!("{e} (using the built-in shaders)")));
                            self.failed_key = None;
                        }
                        Err(e) => self.errors.shader = Some(one_line(e)),
                    }
                    if std::mem::take(&mut self.compile_again) {
                        self.start_compile();
                    }
                }
                Job::Loaded { generation, path, reload, result } => {
                    if generation != self.load_generation {
                        continue;
                    }
                    self.loading = false;
                    match result {
                        Ok(scene) => self.install_scene(ctx, scene, &path, reload),
                        // The last good scene stays.
                        Err(e) => self.errors.scene = Some(one_line(e)),
                    }
                }
                Job::Prepared { key, result } => {
                    self.preparing = false;
                    match result {
                        Ok(canvas) if Some(&key) == self.canvas_key().as_ref() => self.install_canvas(*canvas),
                        // Outdated: a fresh one is on its way.
                        Ok(_) => {}
                        Err(e) => {
                            self.errors.gpu = Some(one_line(e));
                            self.failed_key = Some(key);
                        }
                    }
                }
            }
        }
    }

    fn install_scene(&mut self, ctx: &egui::Context, scene: Scene, path: &Path, reload: bool) {
        self.scene_generation += 1;
        let mut doc = Document::new(scene, self.scene_generation);
        if let (true, Some(old)) = (reload, &self.doc) {
            // Keep the user's view unless the file's camera changed.
            if old.file_camera == doc.scene.camera {
                doc.scene.camera = old.scene.camera;
                doc.fov = old.fov;
            }
        } else {
            self.selected_object = None;
            self.selected_light = None;
        }
        self.selected_object = self.selected_object.filter(|&i| i < doc.scene.objects.len());
        self.selected_light = self.selected_light.filter(|&i| i < doc.scene.lights.len());
        self.notice = match doc.scene.warnings.as_slice() {
            [] => None,
            [w] => Some((one_line(w), true)),
            [w, rest @ ..] => Some((one_line(format!("{w} (and {} more warnings)", rest.len())), true)),
        };
        self.errors.scene = None;
        self.failed_key = None;
        let name = path.file_name().map_or_else(|| path.display().to_string(), |n| n.to_string_lossy().into_owned());
        ctx.send_viewport_cmd(egui::ViewportCommand::Title(format!("Glint — {name}")));
        if !reload {
            // Saved files go beside the scene by default.
            let stem = path.file_stem().map_or("scene".into(), |s| s.to_string_lossy().into_owned());
            let dir = path.parent().unwrap_or(Path::new(""));
            self.screenshot_path = dir.join(format!("{stem}-view.png")).display().to_string();
            self.save_path = dir.join(format!("{stem}-view.toml")).display().to_string();
        }
        self.doc = Some(doc);
        self.dirty = true;
    }

    /// The canvas the current state needs, if one can be made.
    fn canvas_key(&self) -> Option<CanvasKey> {
        let (kernels, doc, size) = (self.kernels.as_ref()?, self.doc.as_ref()?, self.wanted_size?);
        Some(CanvasKey {
            kernels: Arc::as_ptr(kernels) as usize,
            scene_generation: doc.generation,
            size,
            lights: doc.scene.lights.len() + SPARE_LIGHTS,
        })
    }

    /// Starts building a new canvas when the size, scene or kernels changed, or
    /// the lights outgrew the room uploaded for them.
    fn ensure_canvas(&mut self) {
        if self.preparing {
            return;
        }
        let (Some(key), Some(doc), Some(kernels)) = (self.canvas_key(), &self.doc, &self.kernels) else { return };
        if self.failed_key.as_ref() == Some(&key) {
            return;
        }
        if let Some(c) = &self.canvas {
            let enabled = doc.scene.lights.iter().filter(|l| l.enabled).count();
            if Arc::ptr_eq(&c.kernels, kernels)
                && c.scene_generation == doc.generation
                && c.size() == key.size
                && c.prepared.buffers.light_capacity() >= enabled
            {
                return;
            }
        }
        let mut snapshot = doc.scene.clone();
        // Room for every light, on or off, and a few more.
        for l in &mut snapshot.lights {
            l.enabled = true;
        }
        let spare = Light {
            kind: LightKind::Point { position: Vec3::ZERO },
            color: Vec3::ZERO,
            intensity: 0.0,
            attenuation: Attenuation::None,
            enabled: true,
        };
        snapshot.lights.resize(key.lights, spare);
        let kernels = Arc::clone(kernels);
        self.preparing = true;
        let job_key = key.clone();
        self.jobs.spawn("upload", move || {
            let (w, h) = key.size;
            let result = Canvas::new(kernels, &snapshot, w, h, key.scene_generation).map(Box::new);
            Job::Prepared { result, key: job_key }
        });
    }

    fn install_canvas(&mut self, canvas: Canvas) {
        let mut renderer = self.egui_renderer.write();
        let filter = wgpu::FilterMode::Linear;
        match self.texture {
            Some(id) => renderer.update_egui_texture_from_wgpu_texture(&self.device, &canvas.target.view, filter, id),
            None => self.texture = Some(renderer.register_native_texture(&self.device, &canvas.target.view, filter)),
        }
        self.canvas = Some(canvas);
        self.acc = Accumulation::default();
        self.dirty = true;
    }

    // ---- rendering ----

    fn present_options(&self, canvas: &Canvas) -> RenderOptions {
        let s = &self.settings;
        RenderOptions {
            view: s.view,
            exposure: s.exposure,
            tone_map: s.tone_map,
            view_scale: canvas.prepared.view_scale(s.view),
            ..RenderOptions::default()
        }
    }

    fn trace_options(&self, canvas: &Canvas) -> RenderOptions {
        let s = &self.settings;
        // One sample goes through pixel centres; progressive samples are
        // jittered without a fixed count (0), a fixed count is stratified.
        let spp = match (s.spp, s.progressive) {
            (1, _) => 1,
            (_, true) => 0,
            (n, false) => n,
        };
        RenderOptions { spp, ..self.present_options(canvas) }
    }

    /// Writes the edited scene into the canvas and starts accumulating anew.
    /// False when the lights no longer fit (a new canvas is on its way).
    fn sync(&mut self) -> Result<bool, GpuError> {
        let (Some(doc), Some(canvas)) = (&self.doc, &mut self.canvas) else { return Ok(false) };
        let scene = &doc.scene;
        let materials: Vec<_> = scene.materials.iter().map(|m| gpu_types::pack_material(&self.settings.specular.apply(m))).collect();
        let lights: Vec<_> = scene.lights.iter().filter(|l| l.enabled).map(gpu_types::pack_light).collect();
        if lights.len() > canvas.prepared.buffers.light_capacity() {
            return Ok(false);
        }
        let renderer = &canvas.kernels.renderer;
        renderer.write_materials(&canvas.prepared.buffers, &materials)?;
        let buffers = &canvas.prepared.buffers;
        renderer.write_lights(buffers, &lights)?;
        let uniforms = gpu_types::scene_uniforms(scene, buffers.width(), buffers.height(), lights.len() as u32, buffers.bvh_root());
        renderer.write_uniforms(buffers, &uniforms);
        self.acc.restart();
        Ok(true)
    }

    /// This frame's share of the ray tracing.
    fn render(&mut self, ctx: &egui::Context) {
        if !self.canvas_is_current() {
            return;
        }
        if self.dirty {
            match self.sync() {
                Ok(true) => self.dirty = false,
                Ok(false) => return,
                Err(e) => {
                    self.errors.gpu = Some(one_line(e));
                    return;
                }
            }
        }
        let Some(options) = self.canvas.as_ref().map(|c| self.trace_options(c)) else { return };
        let target = self.target_samples();
        let Some(canvas) = self.canvas.as_mut() else { return };
        let step = self.acc.step(canvas, &options, target);
        self.rendering = step != Step::Done;
        match step {
            Step::Traced => {
                // Progressive display shows every band: after a change the new
                // image replaces the old one row by row, so the view stays live
                // even when a whole sample takes several frames.
                if self.settings.progressive || self.acc.samples >= target || !self.acc.presented {
                    canvas.present(&options);
                    self.acc.presented = true;
                    self.represent = false;
                }
                ctx.request_repaint();
            }
            Step::Waiting => ctx.request_repaint_after(Duration::from_millis(2)),
            Step::Done => {}
        }
        if std::mem::take(&mut self.represent) && self.acc.samples > 0 && (self.settings.progressive || self.acc.samples >= target) {
            canvas.present(&options);
        }
        if let Err(e) = self.acc.count_rays(canvas) {
            self.errors.gpu = Some(one_line(e));
        }
    }

    // ---- interaction ----

    /// Image position in render pixels of a point on screen.
    fn to_pixels(&self, pos: Pos2) -> Option<(f32, f32)> {
        let (rect, (w, h)) = (self.image_rect?, self.render_size()?);
        let p = (pos - rect.min) / rect.size();
        Some((p.x * w as f32, p.y * h as f32))
    }

    /// Screen position of a world point, if in front of the camera.
    fn to_screen(&self, p: Vec3) -> Option<Pos2> {
        let (rect, (w, h), doc) = (self.image_rect?, self.render_size()?, self.doc.as_ref()?);
        let (x, y) = doc.scene.camera.project(w, h, p.as_dvec3())?;
        Some(rect.min + Vec2::new(x as f32 / w as f32, y as f32 / h as f32) * rect.size())
    }

    /// The point light whose marker is within reach of `pos`.
    fn light_at(&self, pos: Pos2) -> Option<usize> {
        let doc = self.doc.as_ref()?;
        doc.scene
            .lights
            .iter()
            .enumerate()
            .filter_map(|(i, l)| match l.kind {
                LightKind::Point { position } => Some((i, self.to_screen(position)?.distance(pos))),
                LightKind::Directional { .. } => None,
            })
            .filter(|(_, d)| *d <= LIGHT_GRAB_RADIUS)
            .min_by(|a, b| a.1.total_cmp(&b.1))
            .map(|(i, _)| i)
    }

    fn pick(&mut self, pos: Pos2) {
        let Some((x, y)) = self.to_pixels(pos) else { return };
        if !self.canvas_is_current() || self.dirty {
            return;
        }
        let Some(canvas) = &self.canvas else { return };
        // Negative positions (left of or above the image) are not a pixel.
        let (x, y) = (x.floor().max(-1.0) as i64, y.floor().max(-1.0) as i64);
        let (Ok(x), Ok(y)) = (u32::try_from(x), u32::try_from(y)) else { return };
        match canvas.renderer().pick(&canvas.prepared.buffers, x, y) {
            Ok(id) => self.selected_object = id.map(|i| i as usize),
            Err(e) => self.errors.gpu = Some(one_line(e)),
        }
    }

    /// Mouse and wheel on the image: orbit, pan, zoom, pick, drag lights.
    fn image_input(&mut self, ui: &egui::Ui, response: &egui::Response) {
        let (Some(rect), Some((_, h))) = (self.image_rect, self.render_size()) else { return };
        // Render pixels per point, to turn pointer motion into image motion.
        let px = h as f32 / rect.height();
        let press = ui.input(|i| i.pointer.press_origin());
        if response.drag_started_by(egui::PointerButton::Primary) {
            self.dragging_light = press.and_then(|p| self.light_at(p));
            if self.dragging_light.is_some() {
                self.selected_light = self.dragging_light;
            }
        }
        if response.drag_stopped() {
            self.dragging_light = None;
        }
        // The motion before a drag is recognised counts too, so a dragged
        // marker stays under the pointer.
        let delta = match (response.drag_started(), press, response.interact_pointer_pos()) {
            (true, Some(origin), Some(now)) => now - origin,
            _ => response.drag_delta(),
        };
        let Some(doc) = self.doc.as_mut() else { return };
        let cam = &mut doc.scene.camera;
        if response.dragged_by(egui::PointerButton::Primary) && delta != Vec2::ZERO {
            match self.dragging_light.and_then(|i| doc.scene.lights.get_mut(i)) {
                Some(Light { kind: LightKind::Point { position }, .. }) => {
                    *position = camera_control::drag_point(cam, *position, delta.x * px, delta.y * px, h);
                }
                _ => camera_control::orbit(cam, -delta.x * ORBIT_SPEED, delta.y * ORBIT_SPEED),
            }
        }
        if (response.dragged_by(egui::PointerButton::Secondary) || response.dragged_by(egui::PointerButton::Middle))
            && delta != Vec2::ZERO
        {
            camera_control::pan(cam, delta.x * px, delta.y * px, h);
        }
        if response.hovered() {
            let scroll = ui.input(|i| i.smooth_scroll_delta.y);
            if scroll != 0.0 {
                camera_control::zoom(cam, (-scroll * 0.002).exp(), doc.radius);
            }
        }
        if response.clicked_by(egui::PointerButton::Primary)
            && let Some(pos) = response.interact_pointer_pos()
        {
            match self.light_at(pos) {
                Some(i) => self.selected_light = Some(i),
                None => self.pick(pos),
            }
        }
    }

    /// WASD/QE fly through the scene; Shift is faster.
    fn fly_keys(&mut self, ctx: &egui::Context) {
        // Other widgets may hold focus (the image does once clicked); only
        // typing into a text field takes the keys.
        if ctx.text_edit_focused() {
            return;
        }
        let Some(doc) = self.doc.as_mut() else { return };
        let (forward, right, up, fast, dt) = ctx.input(|i| {
            let axis = |plus, minus| f32::from(i8::from(i.key_down(plus)) - i8::from(i.key_down(minus)));
            (
                axis(egui::Key::W, egui::Key::S),
                axis(egui::Key::D, egui::Key::A),
                axis(egui::Key::E, egui::Key::Q),
                i.modifiers.shift,
                i.stable_dt.min(0.1),
            )
        });
        if forward == 0.0 && right == 0.0 && up == 0.0 {
            return;
        }
        let speed = doc.radius * 0.6 * if fast { 4.0 } else { 1.0 } * dt;
        camera_control::fly(&mut doc.scene.camera, forward * speed, right * speed, up * speed);
        ctx.request_repaint();
    }

    pub(crate) fn reset_camera(&mut self) {
        if let Some(doc) = &mut self.doc {
            doc.scene.camera = doc.file_camera;
        }
    }

    pub(crate) fn frame_all(&mut self) {
        if let Some(doc) = &mut self.doc {
            let aspect = doc.aspect();
            camera_control::frame_all(&mut doc.scene.camera, doc.bounds.0, doc.bounds.1, aspect);
        }
    }

    // ---- files ----

    fn dropped_files(&mut self, ctx: &egui::Context) {
        let dropped = ctx.input(|i| i.raw.dropped_files.first().map(|f| f.path().to_path_buf()));
        if let Some(path) = dropped {
            self.open(path);
        }
    }

    pub(crate) fn save_screenshot(&mut self) {
        let path = PathBuf::from(self.screenshot_path.trim());
        let result = match &self.canvas {
            Some(canvas) if self.canvas_is_current() => canvas
                .renderer()
                .resolve(&canvas.prepared.buffers, &self.present_options(canvas))
                .and_then(|image| glint_gpu::write_image(&image, &path, PngBits::Eight).map(|()| image)),
            _ => Err(GpuError::Output("there is no image to save yet".into())),
        };
        self.notice = Some(match result {
            Ok(image) => (format!("saved {} ({}×{}, {} spp)", path.display(), image.width, image.height, self.acc.samples), false),
            Err(e) => (one_line(e), true),
        });
    }

    pub(crate) fn save_scene(&mut self) {
        let path = PathBuf::from(self.save_path.trim());
        let Some(doc) = &self.doc else { return };
        let mut scene = doc.scene.clone();
        for m in &mut scene.materials {
            *m = self.settings.specular.apply(m);
        }
        let result = glint_scene::toml_write::to_string(&scene)
            .map_err(one_line)
            .and_then(|text| glint_gpu::write_atomically(&path, text.as_bytes()).map_err(|e| one_line(format!("{}: {e}", path.display()))));
        self.notice = Some(match result {
            Ok(()) => (format!("saved {}", path.display()), false),
            Err(e) => (e, true),
        });
    }

    // ---- the frame ----

    fn begin_frame(&mut self, ctx: &egui::Context) {
        let now = Instant::now();
        // Frame time counts frames that follow a rendering frame, not idle waits.
        if let (Some(last), true) = (self.last_frame.replace(now), self.rendering) {
            let ms = now.duration_since(last).as_secs_f32() * 1000.0;
            self.frame_ms = if self.frame_ms == 0.0 { ms } else { 0.9 * self.frame_ms + 0.1 * ms };
        }
        // Runs map and work-done callbacks; never waits.
        let _ = self.device.poll(wgpu::PollType::Poll);
        if let Some(e) = self.device_errors.lock().expect("never poisoned").drain(..).next_back() {
            self.errors.gpu = Some(e);
        }
        self.finish_jobs(ctx);
        if self.scene_watch.as_mut().is_some_and(Watch::changed) {
            self.start_load(true);
        }
        if self.shader_watch.as_mut().is_some_and(Watch::changed) {
            self.start_compile();
        }
        self.dropped_files(ctx);
        self.fly_keys(ctx);
        if self.shader_watch.is_some() || self.scene_watch.is_some() {
            // Keep looking at the files while idle.
            ctx.request_repaint_after(Duration::from_millis(500));
        }
    }

    fn status_bar(&self, ui: &mut egui::Ui) {
        ui.horizontal(|ui| {
            let mut parts = Vec::new();
            if let (Some(doc), Some((w, h))) = (&self.doc, self.render_size()) {
                parts.push(format!("{:.1} ms/frame", self.frame_ms));
                parts.push(format!("{:.2} Mrays/s", self.acc.rays_per_second / 1e6));
                parts.push(format!("{}/{} spp", self.samples(), self.target_samples()));
                parts.push(format!("{w}×{h}"));
                parts.push(format!("{} primitives", doc.scene.primitive_count()));
            }
            for (busy, what) in [(self.compiling, "compiling shaders…"), (self.loading, "loading…"), (self.preparing, "uploading…")] {
                if busy {
                    parts.push(what.into());
                }
            }
            parts.push(self.adapter.clone());
            ui.label(parts.join("  ·  "));
        });
    }

    fn viewport(&mut self, ui: &mut egui::Ui) {
        let ctx = ui.ctx().clone();
        for (slot, label) in [(0, "scene"), (1, "shader"), (2, "GPU")] {
            let error = match slot {
                0 => &mut self.errors.scene,
                1 => &mut self.errors.shader,
                _ => &mut self.errors.gpu,
            };
            if let Some(text) = error.clone() {
                ui.horizontal(|ui| {
                    if ui.small_button("dismiss").clicked() {
                        *error = None;
                    }
                    ui.colored_label(ui.visuals().error_fg_color, format!("{label} error: {text}"));
                });
            }
        }
        let avail = ui.available_rect_before_wrap();
        let Some(aspect) = self.doc.as_ref().map(Document::aspect) else {
            self.image_rect = None;
            let text = if self.loading {
                "loading…"
            } else {
                "Drop a scene file (.toml, .nff, .obj) here, or start with `glint view SCENE`."
            };
            ui.centered_and_justified(|ui| ui.heading(text));
            return;
        };
        let size = if avail.width() / avail.height().max(1.0) > aspect {
            Vec2::new(avail.height() * aspect, avail.height())
        } else {
            Vec2::new(avail.width(), avail.width() / aspect)
        };
        let rect = Rect::from_center_size(avail.center(), size);
        self.image_rect = Some(rect);
        let ppp = ctx.pixels_per_point();
        let side = |points: f32| ((points * ppp * self.settings.scale).round() as u32).clamp(1, self.max_side);
        self.wanted_size = Some((side(size.x), side(size.y)));

        let response = ui.allocate_rect(rect, Sense::click_and_drag());
        let before = self.doc.as_ref().map(|d| d.scene.camera);
        self.image_input(ui, &response);
        if self.doc.as_ref().map(|d| d.scene.camera) != before {
            self.dirty = true;
        }

        let painter = ui.painter_at(rect);
        match (self.texture, &self.canvas) {
            (Some(id), Some(_)) => {
                let uv = Rect::from_min_max(Pos2::ZERO, Pos2::new(1.0, 1.0));
                painter.image(id, rect, uv, Color32::WHITE);
            }
            _ => {
                painter.rect_filled(rect, 0.0, Color32::from_gray(20));
                let text = if self.compiling { "compiling shaders…" } else { "uploading…" };
                painter.text(rect.center(), egui::Align2::CENTER_CENTER, text, egui::FontId::proportional(16.0), Color32::GRAY);
            }
        }
        self.draw_overlays(&painter);
        if ctx.input(|i| !i.raw.hovered_files.is_empty()) {
            painter.rect_filled(rect, 0.0, Color32::from_black_alpha(160));
            painter.text(rect.center(), egui::Align2::CENTER_CENTER, "drop to open", egui::FontId::proportional(22.0), Color32::WHITE);
        }
    }

    /// The selected object's outline and the point lights' markers.
    fn draw_overlays(&self, painter: &egui::Painter) {
        if !self.canvas_is_current() {
            return;
        }
        let Some(doc) = &self.doc else { return };
        if let Some(object) = self.selected_object.and_then(|i| doc.scene.objects.get(i)) {
            let (lo, hi) = object
                .shapes
                .iter()
                .map(glint_scene::Shape::bounds)
                .fold((Vec3::INFINITY, Vec3::NEG_INFINITY), |(lo, hi), (a, b)| (lo.min(a), hi.max(b)));
            let corners: Option<Vec<Pos2>> = (0..8)
                .map(|i| {
                    let pick = |bit: u32, a: f32, b: f32| if i & bit == 0 { a } else { b };
                    self.to_screen(Vec3::new(pick(1, lo.x, hi.x), pick(2, lo.y, hi.y), pick(4, lo.z, hi.z)))
                })
                .collect();
            if let Some(corners) = corners {
                let outline = Rect::from_points(&corners);
                painter.rect_stroke(outline, 2.0, Stroke::new(2.0, Color32::from_rgb(255, 200, 40)), StrokeKind::Outside);
            }
        }
        for (i, light) in doc.scene.lights.iter().enumerate() {
            let LightKind::Point { position } = light.kind else { continue };
            let Some(at) = self.to_screen(position) else { continue };
            let c = light.color.clamp(Vec3::ZERO, Vec3::ONE) * 255.0;
            let fill = if light.enabled { Color32::from_rgb(c.x as u8, c.y as u8, c.z as u8) } else { Color32::from_gray(60) };
            painter.circle_filled(at, 6.0, fill);
            painter.circle_stroke(at, 6.0, Stroke::new(1.5, Color32::BLACK));
            if self.selected_light == Some(i) {
                painter.circle_stroke(at, 10.0, Stroke::new(2.0, Color32::WHITE));
            }
        }
    }
}

impl eframe::App for ViewerApp {
    fn ui(&mut self, ui: &mut egui::Ui, _frame: &mut eframe::Frame) {
        let ctx = ui.ctx().clone();
        // Before begin_frame, whose fly keys move the camera.
        let (edits_before, settings_before) = (self.doc.as_ref().map(|d| Editable::of(&d.scene)), self.settings);
        self.begin_frame(&ctx);

        egui::Panel::bottom("status").show(ui, |ui| self.status_bar(ui));
        egui::Panel::right("controls").resizable(true).default_size(330.0).show(ui, |ui| {
            egui::ScrollArea::vertical().show(ui, |ui| self.controls(ui));
        });
        egui::CentralPanel::default().show(ui, |ui| self.viewport(ui));

        if self.doc.as_ref().map(|d| Editable::of(&d.scene)) != edits_before {
            self.dirty = true;
        }
        let (now, was) = (self.settings, settings_before);
        if (now.spp, now.progressive, now.view, now.specular) != (was.spp, was.progressive, was.view, was.specular) {
            self.dirty = true;
        }
        if (now.exposure, now.tone_map) != (was.exposure, was.tone_map) {
            self.represent = true;
        }
        self.ensure_canvas();
        self.render(&ctx);
    }
}

