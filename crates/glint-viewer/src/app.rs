//! The viewer window: a side panel of settings, the ray-traced image in the
//! central panel, a status bar. `ViewerApp` holds one state per part of the UI
//! (the document, shaders, render settings, selection, the image) and runs a
//! frame: background results first, then the panels, then the frame's tracing.

use std::path::PathBuf;
use std::sync::{Arc, Mutex};
use std::time::Duration;

use egui::Rect;
use glint_gpu::probe::RayTree;
use glint_gpu::shaders::ShaderSource;
use glint_scene::MAX_IMAGE_SIDE;
use glint_scene::{LoadError, Scene};

use crate::document::{Document, LoadedScene};
use crate::first_image::FirstImageWatch;
use crate::image::TracedImage;
use crate::inspector::Inspector;
use crate::jobs::{Job, Jobs};
use crate::one_line;
use crate::selection::Selection;
use crate::settings::Settings;
use crate::shaders::Shaders;
use crate::warm_up::WarmUp;

/// What the viewer opens with.
pub struct ViewerOptions {
    pub scene: Option<PathBuf>,
    /// Where the WGSL comes from; a folder is watched and reloaded on change.
    pub shaders: ShaderSource,
    /// The TOML text of `scene` when it is built into the program rather than
    /// read from disk (`scene` then only names it, and is not watched).
    pub scene_text: Option<&'static str>,
    /// Close once the first complete image is shown, recording when.
    pub first_image: Option<FirstImageWatch>,
}

impl ViewerOptions {
    /// Opens `scene`, with shaders hot-reloaded from this source tree's
    /// `shaders/` folder when it exists (else the built-in copies).
    pub fn new(scene: Option<PathBuf>) -> Self {
        let dir = ShaderSource::source_dir();
        let shaders = if dir.is_dir() { ShaderSource::Dir(dir) } else { ShaderSource::Embedded };
        Self { scene, shaders, scene_text: None, first_image: None }
    }
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

/// One line per kind of problem, shown above the image until it is fixed.
#[derive(Default)]
pub(crate) struct Errors {
    pub scene: Option<String>,
    pub shader: Option<String>,
    pub gpu: Option<String>,
}

impl Errors {
    /// Each problem on its line, with a button to dismiss it.
    pub fn show(&mut self, ui: &mut egui::Ui) {
        for (error, label) in [(&mut self.scene, "scene"), (&mut self.shader, "shader"), (&mut self.gpu, "GPU")] {
            if let Some(text) = error.clone() {
                ui.horizontal(|ui| {
                    if ui.small_button("dismiss").clicked() {
                        *error = None;
                    }
                    ui.colored_label(ui.visuals().error_fg_color, format!("{label} error: {text}"));
                });
            }
        }
    }
}

pub struct ViewerApp {
    device: wgpu::Device,
    adapter: wgpu::AdapterInfo,
    device_errors: Arc<Mutex<Vec<String>>>,
    jobs: Jobs<Job>,
    pub(crate) shaders: Shaders,
    pub(crate) document: Document,
    pub(crate) settings: Settings,
    pub(crate) selection: Selection,
    pub(crate) image: TracedImage,
    pub(crate) inspector: Inspector,
    /// Shown in the Save section: the outcome of the last file action, or a
    /// warning (message, is a problem).
    pub(crate) notice: Option<(String, bool)>,
    pub(crate) errors: Errors,
    first_image: Option<FirstImageWatch>,
}

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
        let max_side = rs.device.limits().max_texture_dimension_2d.min(MAX_IMAGE_SIDE);
        let settings = Settings::default();
        let warm_up = WarmUp::new(settings.view, settings.traced_samples());
        let mut app = Self {
            device: rs.device.clone(),
            adapter: info.clone(),
            device_errors,
            jobs: Jobs::new(cc.egui_ctx.clone()),
            shaders: Shaders::new(rs.device.clone(), rs.queue.clone(), options.shaders, warm_up.clone()),
            document: Document::new(warm_up),
            settings,
            selection: Selection::default(),
            image: TracedImage::new(rs.device.clone(), Arc::clone(&rs.renderer), max_side),
            inspector: Inspector::default(),
            notice: glint_gpu::driver_warning(&info).map(|warning| (warning, true)),
            errors: Errors::default(),
            first_image: options.first_image,
        };
        app.shaders.start_compile(&app.jobs);
        match (options.scene, options.scene_text) {
            (Some(name), Some(text)) => app.document.open_built_in(name, text, &app.jobs),
            (Some(path), None) => app.open(path),
            (None, _) => {}
        }
        Ok(app)
    }

    // ---- for tests and the status bar ----

    pub fn scene(&self) -> Option<&Scene> {
        self.document.loaded.as_ref().map(|d| &d.scene)
    }

    /// Samples per pixel the current image converges to.
    pub fn target_samples(&self) -> u32 {
        self.settings.target_samples()
    }

    /// Samples per pixel in the image of the current scene and settings.
    pub fn samples(&self) -> u32 {
        self.image.samples(self.document.loaded.as_ref())
    }

    /// All samples of the current state are in and shown.
    pub fn is_converged(&self) -> bool {
        self.image.is_converged(self.document.loaded.as_ref(), self.target_samples())
    }

    /// Where the image is drawn, in points.
    pub fn image_rect(&self) -> Option<Rect> {
        self.image.rect
    }

    /// The size of the rendered image in pixels.
    pub fn render_size(&self) -> Option<(u32, u32)> {
        self.image.render_size()
    }

    pub fn selected_object(&self) -> Option<usize> {
        self.selection.object
    }

    /// The ray tree of the pixel pinned in inspect mode, as last probed.
    pub fn inspected_tree(&self) -> Option<&RayTree> {
        self.inspector.tree.as_ref()
    }

    /// The pixel pinned in inspect mode, in the image as rendered now.
    pub fn inspected_pixel(&self) -> Option<(u32, u32)> {
        self.inspector.pixel(&self.image)
    }

    /// In observer mode, the camera that traced the frozen trees and the
    /// pixels they were probed at.
    pub fn observed(&self) -> Option<(glint_scene::Camera, Vec<(u32, u32)>)> {
        let o = self.inspector.observed.as_ref()?;
        Some((o.camera, o.trees.iter().map(|(pixel, _)| *pixel).collect()))
    }

    /// What is drawn over the image, in 3-D, and the camera that sees it.
    pub fn overlay(&self) -> Option<(glint_observer::Observer, glint_observer::Overlay)> {
        self.inspector.overlay(&self.image, self.document.loaded.as_ref()?)
    }

    /// The ray whose node the pointer is over in the inspector.
    pub fn highlighted_ray(&self) -> Option<usize> {
        self.inspector.hovered
    }

    /// The problems shown above the image, one line each.
    pub fn errors(&self) -> Vec<String> {
        let e = &self.errors;
        [&e.scene, &e.shader, &e.gpu].into_iter().flatten().cloned().collect()
    }

    // ---- files ----

    /// Opens the scene at `path`, keeping the current one until it has loaded.
    pub(crate) fn open(&mut self, path: PathBuf) {
        self.document.open(path, &self.jobs);
    }

    pub(crate) fn save_screenshot(&mut self) {
        let path = PathBuf::from(self.document.screenshot_path.trim());
        let result = self.image.save_png(&path, self.document.loaded.as_ref(), &self.settings);
        self.notice = Some(match result {
            Ok(image) => (format!("saved {} ({}×{}, {} spp)", path.display(), image.width, image.height, self.image.acc.samples), false),
            Err(e) => (one_line(e), true),
        });
    }

    pub(crate) fn save_scene(&mut self) {
        let path = PathBuf::from(self.document.save_path.trim());
        let Some(doc) = &self.document.loaded else { return };
        self.notice = Some(match doc.save(&path, self.settings.specular) {
            Ok(()) => (format!("saved {}", path.display()), false),
            Err(e) => (e, true),
        });
    }

    // ---- the frame ----

    fn begin_frame(&mut self, ctx: &egui::Context) {
        self.image.frame_time.begin_frame();
        // Runs map and work-done callbacks; never waits.
        let _ = self.device.poll(wgpu::PollType::Poll);
        if let Some(e) = self.device_errors.lock().expect("never poisoned").drain(..).next_back() {
            self.errors.gpu = Some(e);
        }
        self.finish_jobs(ctx);
        if self.document.changed() {
            self.document.start_load(true, &self.jobs);
        }
        if self.shaders.changed() {
            self.shaders.start_compile(&self.jobs);
        }
        let dropped = ctx.input(|i| i.raw.dropped_files.first().map(|f| f.path().to_path_buf()));
        if let Some(path) = dropped {
            self.open(path);
        }
        self.fly_keys(ctx);
        let key = |key| !ctx.text_edit_focused() && ctx.input(|i| i.key_pressed(key));
        if let Some(doc) = self.document.loaded.as_mut() {
            if key(egui::Key::I) {
                self.inspector.set_enabled(!self.inspector.enabled, doc);
            }
            if key(egui::Key::O) {
                if self.inspector.is_observing() {
                    self.inspector.set_enabled(true, doc);
                } else {
                    self.inspector.enter_observer();
                }
            }
        }
        if self.shaders.is_watched() || self.document.is_watched() {
            // Keep looking at the files while idle.
            ctx.request_repaint_after(Duration::from_millis(500));
        }
    }

    fn finish_jobs(&mut self, ctx: &egui::Context) {
        for job in self.jobs.finished() {
            match job {
                Job::Compiled { result, fallback_error } => {
                    if self.shaders.finish_compile(result, fallback_error, &mut self.errors.shader, &self.jobs) {
                        self.image.kernels_changed();
                    }
                }
                Job::Loaded { generation, path, reload, result } => {
                    let Some(doc) = self.document.finish_load(generation, &path, reload, result, &mut self.errors.scene) else {
                        continue;
                    };
                    self.selection.for_scene(&doc.scene, reload);
                    self.notice = warnings_notice(&doc.scene.warnings);
                    self.image.scene_changed();
                    let name = path.file_name().map_or_else(|| path.display().to_string(), |n| n.to_string_lossy().into_owned());
                    ctx.send_viewport_cmd(egui::ViewportCommand::Title(format!("Glint — {name}")));
                }
                Job::Prepared { key, result } => {
                    let (kernels, doc) = (self.shaders.kernels.as_ref(), self.document.loaded.as_ref());
                    self.image.finish_prepare(key, result, kernels, doc, &mut self.errors.gpu);
                }
                Job::ProberCompiled { kernels, result } => self.inspector.finish_compile(kernels, result, &mut self.errors.shader),
            }
        }
    }

    fn watch_first_image(&mut self, ctx: &egui::Context) {
        let Some(watch) = &self.first_image else { return };
        let others: Vec<String> = [&self.errors.shader, &self.errors.gpu].into_iter().flatten().cloned().collect();
        let shown = || {
            let done = self.image.is_converged(self.document.loaded.as_ref(), 1);
            // Converged means submitted: the image is there once the device is done.
            done && self.device.poll(wgpu::PollType::wait_indefinitely()).is_ok()
        };
        if watch.check(self.errors.scene.as_deref(), &others, &self.adapter, shown) {
            ctx.send_viewport_cmd(egui::ViewportCommand::Close);
        }
    }

    fn status_bar(&self, ui: &mut egui::Ui) {
        ui.horizontal(|ui| {
            let mut parts = Vec::new();
            if let (Some(doc), Some((w, h))) = (&self.document.loaded, self.render_size()) {
                parts.push(format!("{:.1} ms/frame", self.image.frame_time.ms));
                parts.push(format!("{:.2} Mrays/s", self.image.acc.rays_per_second / 1e6));
                parts.push(format!("{}/{} spp", self.samples(), self.target_samples()));
                parts.push(format!("{w}×{h}"));
                parts.push(format!("{} primitives", doc.scene.primitive_count()));
            }
            let busy = [
                (self.shaders.compiling, "compiling shaders…"),
                (self.document.loading, "loading…"),
                (self.image.preparing, "uploading…"),
                (self.inspector.is_compiling(), "compiling the probe kernel…"),
            ];
            for (busy, what) in busy {
                if busy {
                    parts.push(what.into());
                }
            }
            parts.push(format!("{} ({:?})", self.adapter.name, self.adapter.backend));
            ui.label(parts.join("  ·  "));
        });
    }
}

/// A loaded scene's warnings, on one line.
fn warnings_notice(warnings: &[LoadError]) -> Option<(String, bool)> {
    match warnings {
        [] => None,
        [w] => Some((one_line(w), true)),
        [w, rest @ ..] => Some((one_line(format!("{w} (and {} more warnings)", rest.len())), true)),
    }
}

impl eframe::App for ViewerApp {
    fn ui(&mut self, ui: &mut egui::Ui, _frame: &mut eframe::Frame) {
        let ctx = ui.ctx().clone();
        // Before begin_frame, whose fly keys move the camera.
        let (edits_before, settings_before) = (self.document.loaded.as_ref().map(LoadedScene::edits), self.settings);
        self.begin_frame(&ctx);

        egui::Panel::bottom("status").show(ui, |ui| self.status_bar(ui));
        egui::Panel::right("controls").resizable(true).default_size(330.0).show(ui, |ui| {
            egui::ScrollArea::vertical().show(ui, |ui| self.controls(ui));
        });
        egui::CentralPanel::default().show(ui, |ui| self.viewport(ui));

        if self.document.loaded.as_ref().map(LoadedScene::edits) != edits_before || self.settings.changes_samples(&settings_before) {
            self.image.dirty = true;
        }
        if self.settings.changes_display(&settings_before) {
            self.image.represent = true;
        }
        let (kernels, doc) = (self.shaders.kernels.as_ref(), self.document.loaded.as_ref());
        self.image.ensure_canvas(kernels, doc, self.settings.view, &self.jobs);
        self.image.render(&ctx, doc, &self.settings, &mut self.errors.gpu);
        // After the render, which writes edits into the canvas the probe reads.
        self.inspector.update(&self.image, doc, &self.jobs, &mut self.errors.gpu);
        if self.inspector.is_probing() {
            // In a browser the tree arrives without waking the UI.
            ctx.request_repaint();
        }
        self.watch_first_image(&ctx);
    }
}
