//! The page's app: glint-viewer's app under a bar of what only a page has
//! (the scene menu, opening files, downloads, the frame-time readout), the
//! link kept in the URL's fragment, and the state published for tests in
//! the page's `#glint-state` element (JSON): what is where on the canvas, so
//! a test clicks it with real input events, and what the viewer shows.

use std::path::PathBuf;

use egui::{Color32, Rect};
use glint_gpu::{Image, Readback};
use glint_scene::Camera;
use glint_viewer::{ViewerApp, ViewerOptions};
use glint_gpu::shaders::ShaderSource;
use wasm_bindgen::JsCast;
use web_time::Instant;

use crate::catalogue::{self, GALLERY, SCENES};
use crate::files::{Batch, Inbox};
use crate::fragment::{self, Link};
use crate::opening::scene_of;
use crate::download;

/// Runs the app on the page's canvas `glint`; a failure to start (no WebGPU)
/// is shown in the page.
pub(crate) async fn run() {
    let options = eframe::WebOptions { wgpu_options: wgpu_configuration(), ..Default::default() };
    let started = Instant::now();
    let result = match canvas() {
        Ok(canvas) => eframe::WebRunner::new()
            .start(canvas, options, Box::new(move |cc| Ok(Box::new(WebApp::new(cc, started)?))))
            .await
            .map_err(|e| e.as_string().unwrap_or_else(|| format!("{e:?}"))),
        Err(e) => Err(e),
    };
    if let Err(e) = result {
        let message = format!("Glint cannot start: {e}. It needs a browser with WebGPU (Chrome or Edge 113+, Safari 26, Firefox 141+ on Windows).");
        publish(&serde_json::json!({ "fatal": message }).to_string());
        if let Some(element) = element("glint-fatal") {
            element.set_text_content(Some(&message));
        }
    }
}

fn canvas() -> Result<web_sys::HtmlCanvasElement, String> {
    element("glint").and_then(|e| e.dyn_into().ok()).ok_or_else(|| "the page has no canvas `glint`".into())
}

fn element(id: &str) -> Option<web_sys::Element> {
    web_sys::window()?.document()?.get_element_by_id(id)
}

/// The browser's WebGPU adapter, with the adapter's own limits as the
/// native viewer asks (WebGPU's defaults suffice for the kernels).
fn wgpu_configuration() -> egui_wgpu::WgpuConfiguration {
    let mut setup = egui_wgpu::WgpuSetupCreateNew::without_display_handle();
    setup.instance_descriptor.backends = wgpu::Backends::BROWSER_WEBGPU;
    setup.device_descriptor = std::sync::Arc::new(|adapter| wgpu::DeviceDescriptor {
        label: Some("glint web"),
        required_limits: adapter.limits(),
        ..Default::default()
    });
    egui_wgpu::WgpuConfiguration { wgpu_setup: egui_wgpu::WgpuSetup::CreateNew(setup), ..Default::default() }
}

struct WebApp {
    viewer: ViewerApp,
    inbox: Inbox,
    /// The image asked for by "Save PNG", on its way back from the device.
    saving: Option<Readback<Image>>,
    /// The outcome of the last page action (message, is a problem).
    notice: Option<(String, bool)>,
    started: Instant,
    /// From the page's start to the first image on screen.
    first_image_ms: Option<f64>,
    /// The link's camera, given to its scene once that has loaded.
    link_camera: Option<Camera>,
    /// The fragment last written to the address bar.
    fragment: String,
    /// Where the bar's buttons are, by name, for tests.
    buttons: Vec<(&'static str, Rect)>,
    /// The state last published.
    published: String,
}

impl WebApp {
    fn new(cc: &eframe::CreationContext<'_>, started: Instant) -> Result<Self, glint_viewer::StartError> {
        let options = ViewerOptions { shaders: ShaderSource::Embedded, ..ViewerOptions::new(None) };
        let mut app = Self {
            viewer: ViewerApp::new(cc, options)?,
            inbox: Inbox::default(),
            saving: None,
            notice: None,
            started,
            first_image_ms: None,
            link_camera: None,
            fragment: String::new(),
            buttons: Vec::new(),
            published: String::new(),
        };
        let hash = web_sys::window().and_then(|w| w.location().hash().ok()).unwrap_or_default();
        let link = fragment::decode(&hash).unwrap_or_else(|e| {
            app.notice = Some((e, true));
            None
        });
        match link {
            Some(Link { scene, camera, spp }) if catalogue::is_known(&scene) => {
                app.link_camera = camera;
                if let Some(spp) = spp {
                    app.viewer.set_samples(spp);
                }
                app.open_known(&scene);
            }
            Some(Link { scene, .. }) => {
                app.notice = Some((format!("the link names {scene}, which is not built in: open the file"), true));
                app.open_known(catalogue::FIRST);
            }
            None => app.open_known(catalogue::FIRST),
        }
        Ok(app)
    }

    /// Opens a built-in scene or a database by name.
    fn open_known(&mut self, name: &str) {
        if let Some(scene) = catalogue::built_in(name) {
            glint_scene::opened_files::provide(scene.name, scene.text.as_bytes());
        }
        self.viewer.open_scene(PathBuf::from(name));
    }

    /// Opens files read together: each is kept by name, and the scene among
    /// them is opened.
    fn open_batch(&mut self, batch: Batch) {
        let mut names = Vec::new();
        for (name, bytes) in batch {
            match bytes {
                Ok(bytes) => glint_scene::opened_files::provide(name.as_str(), bytes),
                Err(e) => return self.notice = Some((e, true)),
            }
            names.push(name);
        }
        let names: Vec<&str> = names.iter().map(String::as_str).collect();
        match scene_of(&names) {
            Ok(scene) => {
                self.notice = None;
                self.viewer.open_scene(PathBuf::from(scene));
            }
            Err(e) => self.notice = Some((e, true)),
        }
    }

    fn bar(&mut self, ui: &mut egui::Ui) {
        self.buttons.clear();
        ui.horizontal_wrapped(|ui| {
            ui.menu_button("Scenes", |ui| {
                let mut chosen = None;
                for scene in SCENES {
                    if ui.button(scene.name).clicked() {
                        chosen = Some(scene.name.to_string());
                    }
                }
                ui.menu_button("gallery", |ui| {
                    for scene in GALLERY {
                        if ui.button(scene.name).clicked() {
                            chosen = Some(scene.name.to_string());
                        }
                    }
                });
                ui.menu_button("Standard Procedural Databases", |ui| {
                    for name in catalogue::spd_names() {
                        if ui.button(&name).clicked() {
                            chosen = Some(name);
                        }
                    }
                });
                if let Some(name) = chosen {
                    self.open_known(&name);
                    ui.close();
                }
            });
            let open = ui.button("Open file…").on_hover_text("a .toml, .nff, .ray or .obj scene (with its .mtl); or drop files on the page");
            if open.clicked() {
                if let Err(e) = self.inbox.pick(ui.ctx()) {
                    self.notice = Some((e, true));
                }
            }
            let png = ui.button("Save PNG");
            if png.clicked() {
                match self.viewer.image_later() {
                    Ok(image) => self.saving = Some(image),
                    Err(e) => self.notice = Some((e, true)),
                }
            }
            let toml = ui.button("Save TOML");
            if toml.clicked() {
                let saved = self.viewer.scene_toml().and_then(|text| download::offer(&self.file_name("toml"), "application/toml", text.as_bytes()));
                self.notice = Some(match saved {
                    Ok(()) => (format!("saved {}", self.file_name("toml")), false),
                    Err(e) => (e, true),
                });
            }
            self.buttons = vec![("open", open.rect), ("save_png", png.rect), ("save_toml", toml.rect)];
            ui.separator();
            ui.label(format!("{:.1} ms/frame", self.viewer.frame_ms()));
            if let Some(ms) = self.first_image_ms {
                ui.label(format!("first image {:.2} s", ms / 1000.0));
            }
            if let Some((text, problem)) = &self.notice {
                let colour = if *problem { ui.visuals().error_fg_color } else { Color32::GRAY };
                ui.colored_label(colour, text);
            }
        });
    }

    /// The name a download gets: the scene's, with `extension`.
    fn file_name(&self, extension: &str) -> String {
        let name = self.viewer.scene_name().unwrap_or_else(|| "scene".into());
        let stem = name.rsplit_once('.').map_or(name.as_str(), |(stem, _)| stem).replace([':', '/'], "-");
        format!("{stem}-view.{extension}")
    }

    fn finish_saving(&mut self, ctx: &egui::Context) {
        let Some(image) = self.saving.take_if(|s| s.is_ready()).and_then(|s| s.take()) else {
            if self.saving.is_some() {
                ctx.request_repaint();
            }
            return;
        };
        let name = self.file_name("png");
        let saved = image.map_err(|e| e.to_string()).and_then(|image| {
            let mut png = Vec::new();
            image.to_rgb8().write_to(&mut std::io::Cursor::new(&mut png), image::ImageFormat::Png).map_err(|e| e.to_string())?;
            download::offer(&name, "image/png", &png)
        });
        self.notice = Some(match saved {
            Ok(()) => (format!("saved {name}"), false),
            Err(e) => (e, true),
        });
    }

    /// Keeps the address bar's fragment on the scene and camera shown.
    fn keep_link(&mut self) {
        let (Some(name), Some(camera)) = (self.viewer.scene_name(), self.viewer.camera()) else { return };
        if let Some(camera) = self.link_camera.take() {
            self.viewer.set_camera(camera);
            return;
        }
        let fragment = fragment::encode(&name, &camera, self.viewer.target_samples());
        if fragment != self.fragment {
            let history = web_sys::window().and_then(|w| w.history().ok());
            if let Some(history) = history {
                let _ = history.replace_state_with_url(&wasm_bindgen::JsValue::NULL, "", Some(&format!("#{fragment}")));
            }
            self.fragment = fragment;
        }
    }

    fn publish_state(&mut self) {
        let rect = |r: Rect| [r.min.x, r.min.y, r.max.x, r.max.y];
        let mut errors = self.viewer.errors();
        errors.extend(self.notice.iter().filter(|(_, problem)| *problem).map(|(text, _)| text.clone()));
        let state = serde_json::json!({
            "scene": self.viewer.scene_name(),
            "render_size": self.viewer.render_size(),
            "samples": self.viewer.samples(),
            "target_samples": self.viewer.target_samples(),
            "converged": self.viewer.is_converged(),
            "errors": errors,
            "warnings": self.viewer.notice().filter(|(_, problem)| *problem).map(|(text, _)| text).into_iter().collect::<Vec<_>>(),
            "notice": self.notice.as_ref().map(|(text, _)| text),
            "frame_ms": self.viewer.frame_ms(),
            "first_image_ms": self.first_image_ms,
            "image_rect": self.viewer.image_rect().map(rect),
            "lights": self.viewer.light_markers().iter().map(|p| p.map(|p| [p.x, p.y])).collect::<Vec<_>>(),
            "buttons": self.buttons.iter().map(|(name, r)| (name.to_string(), serde_json::json!(rect(*r)))).collect::<serde_json::Map<_, _>>(),
            "tree": self.viewer.inspected_lines(),
            "link": self.fragment,
        })
        .to_string();
        if state != self.published {
            publish(&state);
            self.published = state;
        }
    }
}

fn publish(state: &str) {
    if let Some(element) = element("glint-state") {
        element.set_text_content(Some(state));
    }
}

impl eframe::App for WebApp {
    fn ui(&mut self, ui: &mut egui::Ui, frame: &mut eframe::Frame) {
        let ctx = ui.ctx().clone();
        // Dropped files are read here, as bytes; the viewer sees none.
        let dropped = ctx.input_mut(|i| std::mem::take(&mut i.raw.dropped_files));
        if !dropped.is_empty() {
            self.inbox.read_dropped(dropped, &ctx);
        }
        for batch in self.inbox.take() {
            self.open_batch(batch);
        }
        egui::Panel::top("page").show(ui, |ui| self.bar(ui));
        self.viewer.ui(ui, frame);
        self.finish_saving(&ctx);
        if self.first_image_ms.is_none() && self.viewer.samples() >= 1 {
            self.first_image_ms = Some(self.started.elapsed().as_secs_f64() * 1000.0);
        }
        self.keep_link();
        self.publish_state();
    }
}
