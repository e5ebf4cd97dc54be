//! What a page that hosts the viewer asks of it (glint-web): opening scenes
//! by name (files handed over as bytes among them), the image and the scene to save as
//! downloads, the camera for a shared link, and what is where on screen, so
//! that a test can click it with real input events.

use std::path::PathBuf;

use egui::Pos2;
use glint_gpu::{Image, Readback};
use glint_scene::{Camera, LightKind};

use crate::one_line;
use crate::ViewerApp;

impl ViewerApp {
    /// Opens a scene file (or `spd:NAME`) by name; files handed over as bytes
    /// are found through `glint_scene::opened_files`.
    pub fn open_scene(&mut self, path: PathBuf) {
        self.open(path);
    }

    /// The name of the scene viewed, as opened.
    pub fn scene_name(&self) -> Option<String> {
        self.document.path.as_ref().map(|p| p.display().to_string())
    }

    /// The image as shown, read back from the device when it is ready (a
    /// browser cannot wait for it).
    pub fn image_later(&self) -> Result<Readback<Image>, String> {
        self.image.image_later(self.document.loaded.as_ref(), &self.settings).map_err(one_line)
    }

    /// The scene as edited, as "Save scene as" writes it.
    pub fn scene_toml(&self) -> Result<String, String> {
        let doc = self.document.loaded.as_ref().ok_or("there is no scene to save yet")?;
        doc.toml(self.settings.specular)
    }

    pub fn camera(&self) -> Option<Camera> {
        self.scene().map(|s| s.camera)
    }

    pub fn set_camera(&mut self, camera: Camera) {
        if let Some(doc) = self.document.loaded.as_mut() {
            doc.scene.camera = camera;
        }
    }

    /// The warnings of the scene viewed, or the outcome of the last file
    /// action, as the Save section shows it (message, is a problem).
    pub fn notice(&self) -> Option<&(String, bool)> {
        self.notice.as_ref()
    }

    /// Sets the samples per pixel the image converges to.
    pub fn set_samples(&mut self, spp: u32) {
        self.settings.spp = spp;
    }

    /// Milliseconds per frame while the image renders, smoothed.
    pub fn frame_ms(&self) -> f32 {
        self.image.frame_time.ms
    }

    /// Where each point light's marker is on screen, in points (`None` for
    /// a light that has no marker in view).
    pub fn light_markers(&self) -> Vec<Option<Pos2>> {
        let Some(scene) = self.scene() else { return Vec::new() };
        let marker = |kind: &LightKind| match *kind {
            LightKind::Point { position } => self.image.to_screen(&scene.camera, position),
            LightKind::Directional { .. } => None,
        };
        scene.lights.iter().map(|l| marker(&l.kind)).collect()
    }

    /// The pinned pixel's ray tree as the side panel heads it, one line for
    /// the pixel and one per ray.
    pub fn inspected_lines(&self) -> Vec<String> {
        match (self.scene(), self.inspected_tree(), self.inspected_pixel()) {
            (Some(scene), Some(tree), Some(pixel)) => crate::inspector::tree_lines(scene, tree, pixel),
            _ => Vec::new(),
        }
    }
}
