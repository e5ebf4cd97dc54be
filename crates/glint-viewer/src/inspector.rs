//! Inspect mode: a clicked pixel's ray tree, traced by the probe kernel (the
//! trace kernel's own code, recording every ray), drawn over the image as 3D
//! segments seen by the current camera and listed in the side panel. The pixel
//! stays pinned and is probed again whenever the scene in the canvas changes,
//! except in observer mode (`observer.rs`), which freezes the trees of the
//! pixel (or its row or column) and the camera that traced them.
//!
//! The probe kernel is as large as the trace kernel, so it is compiled in the
//! background the first time inspect mode is used, not at start-up. A probe's
//! tree is read back at once natively, and in a later frame in a browser,
//! whose page may not wait for the device.

use std::sync::Arc;

use egui::{CollapsingHeader, Color32, Pos2, Stroke, Ui};
use glint_encoding::gpu_types::{ProbeRay, NO_RAY, PROBE_BLOCKED, PROBE_SHADOW_TRACED, RAY_EYE, RAY_SHADOW};
use glint_gpu::probe::{Prober, RayTree, TreeText};
use glint_gpu::{GpuError, Readback, RenderOptions};
use glint_observer::{Observer, Overlay, OverlayOptions, ProbedPixel, RayId, GRID_CELL_PIXELS};
use glint_scene::camera_frame::CameraFrame;
use glint_scene::{Camera, MAX_DEPTH_LIMIT};

use crate::one_line;
use crate::document::LoadedScene;
use crate::engine::Kernels;
use crate::image::TracedImage;
use crate::jobs::{Job, Jobs};
use crate::observer::{paint, Observed, Spread};

pub(crate) struct Inspector {
    /// A click pins a pixel instead of selecting an object.
    pub enabled: bool,
    /// The pinned pixel as a fraction of the image's width and height, so it
    /// stays put when the render size changes.
    pinned: Option<Pos2>,
    /// The kernels the probe kernel was compiled with (it binds their scene
    /// layout, so it only probes canvases made by them) and the outcome, so a
    /// broken probe kernel is not compiled again until the kernels change.
    prober: Option<(Arc<Kernels>, Result<Prober, ()>)>,
    compiling: bool,
    pub tree: Option<RayTree>,
    /// The canvas write and the pixel the tree was probed at.
    probed: Option<(u64, (u32, u32))>,
    /// The ray whose node the pointer is over in the side panel.
    pub hovered: Option<usize>,
    /// Observer mode is wanted: it begins with the next probe of the canvas.
    observe: bool,
    pub observed: Option<Observed>,
    /// The pixels observer mode follows.
    pub spread: Spread,
    /// The deepest rays drawn.
    pub max_depth: u32,
    /// Probes on their way back from the device.
    probing: Option<Probing>,
}

/// Probes asked of the device, with their pixels, and the camera and frame
/// of the observer mode they begin, if they do.
struct Probing {
    probes: Vec<((u32, u32), Readback<RayTree>)>,
    observer: Option<(Camera, CameraFrame)>,
}

impl Default for Inspector {
    fn default() -> Self {
        Self {
            enabled: false,
            pinned: None,
            prober: None,
            compiling: false,
            tree: None,
            probed: None,
            hovered: None,
            observe: false,
            observed: None,
            spread: Spread::default(),
            max_depth: MAX_DEPTH_LIMIT,
            probing: None,
        }
    }
}

impl Inspector {
    /// Pins the pixel under `pos`, turning inspect mode on.
    pub fn pin(&mut self, image: &TracedImage, pos: Pos2) {
        let Some(rect) = image.rect else { return };
        let fraction = ((pos - rect.min) / rect.size()).to_pos2();
        if (0.0..1.0).contains(&fraction.x) && (0.0..1.0).contains(&fraction.y) {
            self.enabled = true;
            self.pinned = Some(fraction);
        }
    }

    /// Sets inspect mode, and always ends observer mode, giving `doc` back the
    /// camera the trees were traced with; turning inspect mode off lets go of
    /// the pixel.
    pub fn set_enabled(&mut self, enabled: bool, doc: &mut LoadedScene) {
        self.enabled = enabled;
        self.observe = false;
        if let Some(observed) = self.observed.take() {
            doc.scene.camera = observed.camera;
            self.probed = None;
        }
        if !enabled {
            self.pinned = None;
            self.tree = None;
            self.probed = None;
            self.hovered = None;
            self.probing = None;
        }
    }

    /// The pinned pixel in the image as rendered now.
    pub fn pixel(&self, image: &TracedImage) -> Option<(u32, u32)> {
        let (fraction, (w, h)) = (self.pinned?, image.render_size()?);
        let side = |f: f32, n: u32| ((f * n as f32) as u32).min(n - 1);
        Some((side(fraction.x, w), side(fraction.y, h)))
    }

    /// Compiles the probe kernel for the canvas's kernels when inspect mode
    /// needs it, and probes the pinned pixel when the canvas's scene or the
    /// pixel changed since the last probe; a failed probe goes to `error`.
    pub fn update(&mut self, image: &TracedImage, doc: Option<&LoadedScene>, jobs: &Jobs<Job>, error: &mut Option<String>) {
        self.collect(error);
        if !self.enabled || self.probing.is_some() {
            return;
        }
        let Some(canvas) = image.synced_canvas(doc) else { return };
        match &self.prober {
            Some((kernels, _)) if Arc::ptr_eq(kernels, &canvas.kernels) => {}
            _ if self.compiling => return,
            _ => {
                self.compiling = true;
                let kernels = Arc::clone(&canvas.kernels);
                jobs.spawn("probe kernel", move || {
                    let result = Prober::new(&kernels.renderer, &kernels.source);
                    Job::ProberCompiled { kernels, result }
                });
                return;
            }
        }
        if self.observed.is_some() {
            return;
        }
        let (Some(pixel), Some((_, Ok(prober))), Some(size)) = (self.pixel(image), &self.prober, image.render_size()) else { return };
        // Through the pixel centre, as a one-sample render traces it.
        let options = RenderOptions { spp: 1, ..RenderOptions::default() };
        let probe = |pixels: Vec<(u32, u32)>| -> Result<Vec<_>, GpuError> {
            let renderer = canvas.renderer();
            let probes = pixels.into_iter().map(|(x, y)| prober.probe_later(renderer, &canvas.prepared.buffers, x, y, &options).map(|tree| ((x, y), tree)));
            let probes = probes.collect();
            // Natively the trees are read back in this frame.
            #[cfg(not(target_arch = "wasm32"))]
            renderer.device().poll(wgpu::PollType::wait_indefinitely()).map_err(|e| GpuError::Runtime(e.to_string()))?;
            probes
        };
        let (pixels, observer) = if self.observe {
            // The canvas is still the camera's own: probe every pixel followed now.
            self.observe = false;
            let Some(camera) = doc.map(|d| d.scene.camera) else { return };
            let Some(frame) = CameraFrame::new(&camera, size.0, size.1) else { return };
            (self.spread.pixels(pixel, size), Some((camera, frame)))
        } else {
            let key = (image.syncs, pixel);
            if self.probed == Some(key) {
                return;
            }
            self.probed = Some(key);
            (vec![pixel], None)
        };
        match probe(pixels) {
            Ok(probes) => self.probing = Some(Probing { probes, observer }),
            Err(e) => *error = Some(one_line(e)),
        }
        self.collect(error);
    }

    /// Takes the probes' trees once all have arrived.
    fn collect(&mut self, error: &mut Option<String>) {
        let Some(probing) = self.probing.take_if(|p| p.probes.iter().all(|(_, tree)| tree.is_ready())) else { return };
        let trees: Result<Vec<_>, GpuError> =
            probing.probes.into_iter().map(|(pixel, tree)| tree.take().expect("ready").map(|tree| (pixel, tree))).collect();
        match (trees, probing.observer) {
            (Ok(trees), Some((camera, frame))) => {
                self.tree = Some(trees[0].1.clone());
                self.observed = Some(Observed { camera, frame, trees });
            }
            (Ok(mut trees), None) => self.tree = trees.pop().map(|(_, tree)| tree),
            (Err(e), _) => *error = Some(one_line(e)),
        }
    }

    /// Whether a probe's tree is still on its way (in a browser).
    pub fn is_probing(&self) -> bool {
        self.probing.is_some()
    }

    /// Asks for observer mode, which begins once the pinned pixel's canvas is
    /// probed (the tree must be there to freeze).
    pub fn enter_observer(&mut self) {
        if self.enabled && self.tree.is_some() && self.observed.is_none() {
            self.observe = true;
        }
    }

    pub fn is_observing(&self) -> bool {
        self.observed.is_some()
    }

    /// Takes a compiled probe kernel; a failure goes to `error`.
    pub fn finish_compile(&mut self, kernels: Arc<Kernels>, result: Result<Prober, GpuError>, error: &mut Option<String>) {
        self.compiling = false;
        if let Err(e) = &result {
            *error = Some(one_line(format!("probe kernel: {e}")));
        }
        self.prober = Some((kernels, result.map_err(drop)));
        self.probed = None;
    }

    pub fn is_compiling(&self) -> bool {
        self.compiling
    }

    /// The overlay as drawn now and the camera that sees it: in observer
    /// mode, the frozen frame and trees; else the pinned pixel's tree.
    pub fn overlay(&self, image: &TracedImage, doc: &LoadedScene) -> Option<(Observer, Overlay)> {
        let (width, height) = image.render_size()?;
        let observer = Observer { camera: doc.scene.camera, width, height };
        let bounds = doc.bounds;
        let depth = OverlayOptions { max_depth: self.max_depth, grid: false };
        let overlay = match &self.observed {
            Some(observed) => {
                let probed: Vec<_> = observed.trees.iter().map(|(pixel, tree)| ProbedPixel { pixel: *pixel, rays: &tree.rays }).collect();
                let options = OverlayOptions { grid: observer.cell_size(&observed.frame) >= GRID_CELL_PIXELS, ..depth };
                Overlay::new(&doc.scene, &observed.frame, bounds, &probed, options)
            }
            None => {
                let (tree, pixel) = (self.tree.as_ref()?, self.pixel(image)?);
                let frame = CameraFrame::new(&doc.scene.camera, width, height)?;
                Overlay::new(&doc.scene, &frame, bounds, &[ProbedPixel { pixel, rays: &tree.rays }], depth)
            }
        };
        Some((observer, overlay))
    }

    /// The overlay over the image, the hovered ray highlighted; outside
    /// observer mode the tree's rays alone, and a ring around the pinned pixel.
    pub fn draw(&self, painter: &egui::Painter, image: &TracedImage, doc: &LoadedScene) {
        let (Some(rect), Some((observer, overlay))) = (image.rect, self.overlay(image, doc)) else { return };
        let highlighted = self.hovered.map(|ray| RayId { tree: 0, ray });
        paint(painter, rect, &observer, &overlay, highlighted, self.observed.is_none());
        if let (None, Some(pixel)) = (&self.observed, self.pixel(image)) {
            let (w, h) = (observer.width as f32, observer.height as f32);
            let centre = rect.min + egui::vec2((pixel.0 as f32 + 0.5) / w, (pixel.1 as f32 + 0.5) / h) * rect.size();
            painter.circle_stroke(centre, 7.0, Stroke::new(2.0, Color32::BLACK));
            painter.circle_stroke(centre, 6.0, Stroke::new(1.5, Color32::WHITE));
        }
    }

    /// The Inspect section: the toggles, the pinned pixel's tree, a node per
    /// ray, and what observer mode draws.
    pub fn section(&mut self, ui: &mut Ui, image: &TracedImage, doc: &mut LoadedScene) {
        let mut observing = self.observed.is_some() || self.observe;
        CollapsingHeader::new("Inspect rays").default_open(true).show(ui, |ui| {
            ui.checkbox(&mut self.enabled, "inspect mode (I)");
            ui.small("In inspect mode a click (or Ctrl-click at any time) pins a pixel and shows its ray tree.");
            self.hovered = None;
            let pixel = self.observed.as_ref().map(|o| o.trees[0].0).or_else(|| self.pixel(image));
            let (Some(tree), Some((x, y))) = (&self.tree, pixel) else {
                if self.compiling {
                    ui.label("compiling the probe kernel…");
                }
                return;
            };
            let text = TreeText { scene: &doc.scene, tree, first_number: 1 };
            ui.label(pixel_line(tree, (x, y)));
            ui.small("The contributions of all rays add up to the pixel's linear colour.");
            let mut hovered = None;
            if !tree.rays.is_empty() {
                node(ui, &text, 0, &mut hovered);
            }
            if tree.truncated {
                ui.label("(the tree has more rays than the probe records; the rest are left out)");
            }
            self.hovered = hovered;
            ui.separator();
            ui.checkbox(&mut observing, "observer mode (O)")
                .on_hover_text("freeze the tree and the camera that traced it, then move around them");
            ui.add_enabled_ui(self.observed.is_none(), |ui| {
                ui.horizontal(|ui| {
                    ui.label("follow");
                    ui.radio_value(&mut self.spread, Spread::Pixel, "the pixel");
                    ui.radio_value(&mut self.spread, Spread::Row, "its row");
                    ui.radio_value(&mut self.spread, Spread::Column, "its column");
                });
            });
            ui.add(egui::Slider::new(&mut self.max_depth, 1..=MAX_DEPTH_LIMIT).text("deepest rays drawn"));
            ui.small(
                "Observer mode shows the camera's frame (e, u red, v green, w blue), its view window with the pixel, \
and the rays in 3-D: orbit, pan and zoom around them. Leaving it returns to the camera.",
            );
        });
        if !self.enabled || !observing {
            self.set_enabled(self.enabled, doc);
        } else {
            self.enter_observer();
        }
    }
}

/// Ray `id`'s node: its header, its numbers, then the rays it cast.
/// The pinned pixel's tree as the side panel heads it: the pixel, then one
/// line per ray in the order traced.
pub(crate) fn tree_lines(scene: &glint_scene::Scene, tree: &RayTree, pixel: (u32, u32)) -> Vec<String> {
    let text = TreeText { scene, tree, first_number: 1 };
    std::iter::once(pixel_line(tree, pixel)).chain(tree.rays.iter().enumerate().map(|(id, ray)| headline(&text, id, ray))).collect()
}

fn pixel_line(tree: &RayTree, (x, y): (u32, u32)) -> String {
    format!("pixel ({x}, {y}), through its centre: colour {}", glint_gpu::probe::vec3_text(tree.color))
}

fn node(ui: &mut Ui, text: &TreeText<'_>, id: usize, hovered: &mut Option<usize>) {
    let ray = &text.tree.rays[id];
    let response = CollapsingHeader::new(headline(text, id, ray)).id_salt(("ray", id)).default_open(ray.kind == RAY_EYE).show(ui, |ui| {
        for line in text.describe(ray) {
            ui.label(line);
        }
        for (child, _) in text.tree.rays.iter().enumerate().filter(|(_, r)| r.parent as usize == id) {
            node(ui, text, child, hovered);
        }
    });
    if response.header_response.hovered() {
        *hovered = Some(id);
    }
}

/// What a node's header says: the ray and what it found.
fn headline(text: &TreeText<'_>, id: usize, ray: &ProbeRay) -> String {
    let kind = glint_gpu::probe::kind_name(ray.kind);
    if ray.kind == RAY_SHADOW {
        let light = text.scene_light(ray).map_or_else(|| "a light".to_string(), |i| format!("light {}", i + 1));
        let state = match ray.flags {
            f if f & PROBE_SHADOW_TRACED == 0 => "not traced",
            f if f & PROBE_BLOCKED != 0 => "blocked",
            _ if ray.transmittance != [1.0; 3] => "tinted",
            _ => "lit",
        };
        return format!("#{id} shadow ray to {light}: {state}");
    }
    let found = if ray.object == NO_RAY { "misses: the background".to_string() } else { format!("hits {}", text.object(ray.object)) };
    format!("#{id} {kind} ray {found}")
}
