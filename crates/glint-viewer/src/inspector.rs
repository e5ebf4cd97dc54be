//! Inspect mode: a clicked pixel's ray tree, traced by the probe kernel (the
//! trace kernel's own code, recording every ray), drawn over the image as 3D
//! segments seen by the current camera and listed in the side panel. The pixel
//! stays pinned and is probed again whenever the scene in the canvas changes.
//!
//! The probe kernel is as large as the trace kernel, so it is compiled in the
//! background the first time inspect mode is used, not at start-up.

use std::sync::Arc;

use egui::{CollapsingHeader, Color32, Pos2, Shape, Stroke, Ui};
use glam::Vec3;
use glint_gpu::probe::{Prober, RayTree, TreeText};
use glint_gpu::{GpuError, RenderOptions};
use glint_scene::gpu_types::{ProbeRay, NO_RAY, PROBE_BLOCKED, PROBE_SHADOW_TRACED, RAY_EYE, RAY_REFLECT, RAY_REFRACT, RAY_SHADOW};
use glint_scene::{Camera, LightKind, Projection};

use crate::app::one_line;
use crate::document::LoadedScene;
use crate::engine::Kernels;
use crate::image::TracedImage;
use crate::jobs::{Job, Jobs};

const EYE_COLOR: Color32 = Color32::WHITE;
const REFLECT_COLOR: Color32 = Color32::from_rgb(80, 200, 255);
const REFRACT_COLOR: Color32 = Color32::from_rgb(120, 255, 120);
const LIT_COLOR: Color32 = Color32::from_rgb(255, 220, 60);
const BLOCKED_COLOR: Color32 = Color32::from_rgb(255, 60, 60);
const HIGHLIGHT_COLOR: Color32 = Color32::from_rgb(255, 0, 255);
const LINE_WIDTH: f32 = 2.0;

#[derive(Default)]
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

    /// Turning inspect mode off lets go of the pixel.
    pub fn set_enabled(&mut self, enabled: bool) {
        self.enabled = enabled;
        if !enabled {
            self.pinned = None;
            self.tree = None;
            self.probed = None;
            self.hovered = None;
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
        if !self.enabled {
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
        let (Some(pixel), Some((_, Ok(prober)))) = (self.pixel(image), &self.prober) else { return };
        let key = (image.syncs, pixel);
        if self.probed == Some(key) {
            return;
        }
        self.probed = Some(key);
        // Through the pixel centre, as a one-sample render traces it.
        let options = RenderOptions { spp: 1, ..RenderOptions::default() };
        match prober.probe(canvas.renderer(), &canvas.prepared.buffers, pixel.0, pixel.1, &options) {
            Ok(tree) => self.tree = Some(tree),
            Err(e) => *error = Some(one_line(e)),
        }
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

    /// The tree's rays as segments seen by `doc`'s camera, the hovered one
    /// highlighted, and a ring around the pinned pixel.
    pub fn draw(&self, painter: &egui::Painter, image: &TracedImage, doc: &LoadedScene) {
        let (Some(tree), Some(pixel)) = (&self.tree, self.pixel(image)) else { return };
        let text = TreeText { scene: &doc.scene, tree, first_number: 1 };
        let camera = &doc.scene.camera;
        // Children after their parents, so a reflection draws over its eye ray.
        for (id, ray) in tree.rays.iter().enumerate() {
            let (start, end) = (Vec3::from(ray.origin), segment_end(&text, doc, ray));
            let Some((a, b)) = on_screen(image, camera, doc.radius, start, end) else { continue };
            let blocked = ray.kind == RAY_SHADOW && ray.flags & PROBE_BLOCKED != 0;
            let color = if self.hovered == Some(id) { HIGHLIGHT_COLOR } else { ray_color(ray) };
            let width = if self.hovered == Some(id) { LINE_WIDTH * 2.0 } else { LINE_WIDTH };
            let outline = Stroke::new(width + 2.0, Color32::from_black_alpha(160));
            if ray.kind == RAY_SHADOW {
                // Dashed: a shadow ray adds no light of its own, it only asks.
                painter.extend(Shape::dashed_line(&[a, b], outline, 6.0, 4.0));
                painter.extend(Shape::dashed_line(&[a, b], Stroke::new(width, color), 6.0, 4.0));
            } else {
                painter.line_segment([a, b], outline);
                painter.line_segment([a, b], Stroke::new(width, color));
            }
            if blocked {
                let r = 5.0;
                for d in [egui::vec2(r, r), egui::vec2(r, -r)] {
                    painter.line_segment([b - d, b + d], Stroke::new(width + 1.0, color));
                }
            } else if ray.kind != RAY_SHADOW && ray.object != NO_RAY {
                painter.circle_filled(b, width + 1.5, color);
            }
        }
        if let Some(rect) = image.rect {
            let (w, h) = image.render_size().unwrap_or((1, 1));
            let centre = rect.min + egui::vec2((pixel.0 as f32 + 0.5) / w as f32, (pixel.1 as f32 + 0.5) / h as f32) * rect.size();
            painter.circle_stroke(centre, 7.0, Stroke::new(2.0, Color32::BLACK));
            painter.circle_stroke(centre, 6.0, Stroke::new(1.5, EYE_COLOR));
        }
    }

    /// The Inspect section: the toggle and the pinned pixel's tree, a node per ray.
    pub fn section(&mut self, ui: &mut Ui, image: &TracedImage, doc: &LoadedScene) {
        CollapsingHeader::new("Inspect rays").default_open(true).show(ui, |ui| {
            let mut enabled = self.enabled;
            ui.checkbox(&mut enabled, "inspect mode (I)");
            self.set_enabled(enabled);
            ui.small("In inspect mode a click (or Ctrl-click at any time) pins a pixel and shows its ray tree.");
            self.hovered = None;
            let (Some(tree), Some((x, y))) = (&self.tree, self.pixel(image)) else {
                if self.compiling {
                    ui.label("compiling the probe kernel…");
                }
                return;
            };
            let text = TreeText { scene: &doc.scene, tree, first_number: 1 };
            ui.label(format!("pixel ({x}, {y}), through its centre: colour {}", glint_gpu::probe::vec3_text(tree.color)));
            ui.small("The contributions of all rays add up to the pixel's linear colour.");
            let mut hovered = None;
            if !tree.rays.is_empty() {
                node(ui, &text, 0, &mut hovered);
            }
            if tree.truncated {
                ui.label("(the tree has more rays than the probe records; the rest are left out)");
            }
            self.hovered = hovered;
        });
    }
}

/// Ray `id`'s node: its header, its numbers, then the rays it cast.
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

fn ray_color(ray: &ProbeRay) -> Color32 {
    match ray.kind {
        RAY_EYE => EYE_COLOR,
        RAY_REFLECT => REFLECT_COLOR,
        RAY_REFRACT => REFRACT_COLOR,
        _ if ray.flags & PROBE_BLOCKED != 0 => BLOCKED_COLOR,
        _ => LIT_COLOR,
    }
}

/// Where `ray`'s segment ends: at its hit, at the blocker or light of a shadow
/// ray, and where it leaves the scene's bounds when it found nothing.
fn segment_end(text: &TreeText<'_>, doc: &LoadedScene, ray: &ProbeRay) -> Vec3 {
    let (origin, dir) = (Vec3::from(ray.origin), Vec3::from(ray.dir));
    if ray.kind == RAY_SHADOW {
        if ray.flags & PROBE_BLOCKED != 0 {
            return origin + dir * ray.t;
        }
        let directional = text.scene_light(ray).is_some_and(|i| matches!(doc.scene.lights[i].kind, LightKind::Directional { .. }));
        return origin + dir * if directional { reach(doc, origin, dir) } else { ray.distance };
    }
    if ray.object == NO_RAY { origin + dir * reach(doc, origin, dir) } else { Vec3::from(ray.point) }
}

/// How far along `dir` from `origin` the scene's bounds end (its size when
/// the ray never meets them).
fn reach(doc: &LoadedScene, origin: Vec3, dir: Vec3) -> f32 {
    let (lo, hi) = (doc.bounds.0 - doc.radius * 0.1, doc.bounds.1 + doc.radius * 0.1);
    let (a, b) = ((lo - origin) / dir, (hi - origin) / dir);
    let exit = a.max(b).min_element();
    if exit.is_finite() && exit > 0.0 { exit } else { doc.radius * 2.0 }
}

/// Segment `a`–`b` on screen, cut where it passes behind a perspective camera.
fn on_screen(image: &TracedImage, camera: &Camera, scene_radius: f32, a: Vec3, b: Vec3) -> Option<(Pos2, Pos2)> {
    let (mut a, mut b) = (a, b);
    if let (Projection::Perspective { .. }, Some(basis)) = (camera.projection, camera.basis()) {
        let forward = -basis.w.as_vec3();
        let depth = |p: Vec3| (p - camera.eye).dot(forward);
        // Not at the eye itself, where the eye ray starts and nothing projects.
        let near = scene_radius * 1e-3;
        let (da, db) = (depth(a), depth(b));
        if da < near && db < near {
            return None;
        }
        if da < near {
            a = b + (a - b) * ((db - near) / (db - da));
        } else if db < near {
            b = a + (b - a) * ((da - near) / (da - db));
        }
    }
    Some((image.to_screen(camera, a)?, image.to_screen(camera, b)?))
}
