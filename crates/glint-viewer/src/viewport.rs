//! The central panel: the problems above the image, the image with its
//! overlays, and what the pointer and keys do to the camera and the selection
//! (orbit, pan, zoom, fly, pick, drag lights).

use egui::{Color32, Pos2, Rect, Sense, Vec2};
use glint_scene::{Light, LightKind};

use crate::app::ViewerApp;
use crate::camera_control;
use crate::document::LoadedScene;
use crate::selection;

/// Orbit speed, radians per point dragged.
const ORBIT_SPEED: f32 = 0.008;

impl ViewerApp {
    pub(crate) fn viewport(&mut self, ui: &mut egui::Ui) {
        let ctx = ui.ctx().clone();
        self.errors.show(ui);
        let avail = ui.available_rect_before_wrap();
        let Some(aspect) = self.document.loaded.as_ref().map(LoadedScene::aspect) else {
            self.image.rect = None;
            let text = if self.document.loading {
                "loading…"
            } else {
                "Drop a scene file (.toml, .nff, .ray, .obj) here, or start with `glint view SCENE`."
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
        self.image.place(rect, size * ctx.pixels_per_point() * self.settings.scale);

        let response = ui.allocate_rect(rect, Sense::click_and_drag());
        let before = self.document.loaded.as_ref().map(|d| d.scene.camera);
        self.image_input(ui, &response);
        if self.document.loaded.as_ref().map(|d| d.scene.camera) != before {
            self.image.dirty = true;
        }

        let painter = ui.painter_at(rect);
        match self.image.texture() {
            Some(id) => {
                let uv = Rect::from_min_max(Pos2::ZERO, Pos2::new(1.0, 1.0));
                painter.image(id, rect, uv, Color32::WHITE);
            }
            None => {
                painter.rect_filled(rect, 0.0, Color32::from_gray(20));
                let text = if self.shaders.compiling { "compiling shaders…" } else { "uploading…" };
                painter.text(rect.center(), egui::Align2::CENTER_CENTER, text, egui::FontId::proportional(16.0), Color32::GRAY);
            }
        }
        if let Some(doc) = &self.document.loaded
            && self.image.canvas_is_current(Some(doc))
        {
            self.selection.draw(&painter, &self.image, &doc.scene);
            self.inspector.draw(&painter, &self.image, doc);
        }
        if ctx.input(|i| !i.raw.hovered_files.is_empty()) {
            painter.rect_filled(rect, 0.0, Color32::from_black_alpha(160));
            painter.text(rect.center(), egui::Align2::CENTER_CENTER, "drop to open", egui::FontId::proportional(22.0), Color32::WHITE);
        }
    }

    /// Mouse and wheel on the image: orbit, pan, zoom, pick, drag lights.
    fn image_input(&mut self, ui: &egui::Ui, response: &egui::Response) {
        let (Some(rect), Some((_, h))) = (self.image.rect, self.image.render_size()) else { return };
        // Always there once an image is.
        let Some(doc) = self.document.loaded.as_mut() else { return };
        // Render pixels per point, to turn pointer motion into image motion.
        let px = h as f32 / rect.height();
        let press = ui.input(|i| i.pointer.press_origin());
        if response.drag_started_by(egui::PointerButton::Primary) {
            self.selection.start_drag(press.and_then(|p| selection::light_at(&self.image, &doc.scene, p)));
        }
        if response.drag_stopped() {
            self.selection.stop_drag();
        }
        // The motion before a drag is recognised counts too, so a dragged
        // marker stays under the pointer.
        let delta = match (response.drag_started(), press, response.interact_pointer_pos()) {
            (true, Some(origin), Some(now)) => now - origin,
            _ => response.drag_delta(),
        };
        let cam = &mut doc.scene.camera;
        if response.dragged_by(egui::PointerButton::Primary) && delta != Vec2::ZERO {
            match self.selection.dragged_light().and_then(|i| doc.scene.lights.get_mut(i)) {
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
            let pins = self.inspector.enabled || ui.input(|i| i.modifiers.command);
            // The observer's image has no pixel of the frozen camera to pin.
            if pins && !self.inspector.is_observing() {
                self.inspector.pin(&self.image, pos);
            } else if !pins {
                self.selection.click(&self.image, doc, pos, &mut self.errors.gpu);
            }
        }
    }

    /// WASD/QE fly through the scene; Shift is faster.
    pub(crate) fn fly_keys(&mut self, ctx: &egui::Context) {
        // Other widgets may hold focus (the image does once clicked); only
        // typing into a text field takes the keys.
        if ctx.text_edit_focused() {
            return;
        }
        let Some(doc) = self.document.loaded.as_mut() else { return };
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
}
