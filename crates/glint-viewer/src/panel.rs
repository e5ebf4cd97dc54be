//! The side panel: scene, camera, render settings, lights, environment, the
//! selected object's material, and files. Widgets edit the scene and settings
//! in place; the app notices changes and restarts the accumulation.

use std::ops::RangeInclusive;

use egui::{CollapsingHeader, ComboBox, Slider, SliderClamping, Ui};
use glam::Vec3;
use glint_encoding::gpu_types::View;
use glint_gpu::ToneMap;
use glint_scene::MAX_DEPTH_LIMIT;
use glint_scene::{Attenuation, Checker, DepthCue, Light, LightKind, Projection, ShadowMode, Shape, SpecularModel};

use crate::app::ViewerApp;
use crate::camera_control;
use crate::settings::SpecularChoice;

const VIEWS: [(View, &str); 7] = [
    (View::Shaded, "shaded"),
    (View::Normal, "normals"),
    (View::Depth, "depth"),
    (View::Albedo, "albedo"),
    (View::Diffuse, "direct diffuse"),
    (View::Id, "object ids"),
    (View::Heatmap, "BVH heat map"),
];

/// A slider that leaves values outside its range alone until dragged.
fn slider<'a>(value: &'a mut f32, range: RangeInclusive<f32>, text: &str) -> Slider<'a> {
    Slider::new(value, range).text(text).clamping(SliderClamping::Never)
}

/// A colour button for a linear RGB colour.
fn colour(ui: &mut Ui, label: &str, c: &mut Vec3) {
    ui.horizontal(|ui| {
        let mut rgb = c.to_array();
        ui.color_edit_button_rgb(&mut rgb);
        ui.label(label);
        *c = Vec3::from(rgb);
    });
}

/// Three sliders for a point, each over `range` widened to hold its value.
fn point(ui: &mut Ui, p: &mut Vec3, lo: Vec3, hi: Vec3) {
    for (axis, name) in ["x", "y", "z"].into_iter().enumerate() {
        let v = &mut p[axis];
        let range = lo[axis].min(*v)..=hi[axis].max(*v);
        ui.add(slider(v, range, name));
    }
}

impl ViewerApp {
    pub(crate) fn controls(&mut self, ui: &mut Ui) {
        self.scene_section(ui);
        if self.document.loaded.is_none() {
            return;
        }
        self.selection_section(ui);
        if let Some(doc) = &mut self.document.loaded {
            self.inspector.section(ui, &self.image, doc);
        }
        self.camera_section(ui);
        self.render_section(ui);
        self.lights_section(ui);
        self.files_section(ui);
        self.environment_section(ui);
    }

    fn scene_section(&mut self, ui: &mut Ui) {
        CollapsingHeader::new("Scene").default_open(true).show(ui, |ui| {
            if let Some(path) = &self.document.path {
                ui.label(path.display().to_string());
            }
            ui.horizontal(|ui| {
                let label = ui.label("file");
                ui.text_edit_singleline(&mut self.document.open_path).labelled_by(label.id);
                if ui.button("Open").clicked() && !self.document.open_path.trim().is_empty() {
                    self.open(self.document.open_path.trim().into());
                }
            });
            ui.small("Or drop a .toml, .nff, .ray or .obj file on the window. The file is reloaded when it changes.");
        });
    }

    fn camera_section(&mut self, ui: &mut Ui) {
        let mut reset = false;
        let mut frame = false;
        CollapsingHeader::new("Camera").default_open(true).show(ui, |ui| {
            let Some(doc) = self.document.loaded.as_mut() else { return };
            let cam = &mut doc.scene.camera;
            let mut orthographic = matches!(cam.projection, Projection::Orthographic { .. });
            ui.horizontal(|ui| {
                ui.radio_value(&mut orthographic, false, "perspective");
                ui.radio_value(&mut orthographic, true, "orthographic");
            });
            camera_control::set_orthographic(cam, orthographic, doc.fov);
            match &mut cam.projection {
                Projection::Perspective { fov_y_degrees } => {
                    ui.add(Slider::new(fov_y_degrees, 5.0..=150.0).text("field of view").suffix("°"));
                    doc.fov = *fov_y_degrees;
                }
                Projection::Orthographic { height } => {
                    let max = (doc.radius * 20.0).max(*height);
                    ui.add(Slider::new(height, 1e-3..=max).logarithmic(true).text("view height"));
                }
            }
            ui.horizontal(|ui| {
                reset = ui.button("Reset").on_hover_text("the camera of the scene file").clicked();
                frame = ui.button("Frame all").on_hover_text("aim at the whole scene").clicked();
            });
            if let Some(frames) = doc.scene.animation.as_ref().map(|a| a.frames) {
                let slider = Slider::new(&mut doc.frame, 0..=frames - 1).text("animation frame");
                if ui.add(slider).on_hover_text("the camera and lights of this frame of the [animation]").changed() {
                    doc.scene.set_frame(doc.frame);
                }
            }
            ui.small("Left drag: orbit · right or middle drag: pan · wheel: zoom · W A S D Q E: fly (Shift: faster)");
        });
        let Some(doc) = self.document.loaded.as_mut() else { return };
        if reset {
            doc.reset_camera();
        }
        if frame {
            doc.frame_all();
        }
    }

    fn render_section(&mut self, ui: &mut Ui) {
        CollapsingHeader::new("Render").default_open(true).show(ui, |ui| {
            let s = &mut self.settings;
            ComboBox::from_label("view")
                .selected_text(VIEWS.iter().find(|(v, _)| *v == s.view).map_or("?", |(_, n)| n))
                .show_ui(ui, |ui| {
                    for (v, name) in VIEWS {
                        ui.selectable_value(&mut s.view, v, name);
                    }
                });
            ui.add(Slider::new(&mut s.spp, 1..=1024).logarithmic(true).text("samples per pixel"));
            ui.checkbox(&mut s.progressive, "progressive (show every sample)");
            ui.add(Slider::new(&mut s.scale, 0.1..=1.0).text("resolution scale"));
            ui.add(Slider::new(&mut s.exposure, 0.05..=20.0).logarithmic(true).text("exposure"));
            ComboBox::from_label("tone map")
                .selected_text(match s.tone_map {
                    ToneMap::Clamp => "clamp",
                    ToneMap::Reinhard => "Reinhard",
                    ToneMap::Aces => "ACES",
                })
                .show_ui(ui, |ui| {
                    ui.selectable_value(&mut s.tone_map, ToneMap::Clamp, "clamp");
                    ui.selectable_value(&mut s.tone_map, ToneMap::Reinhard, "Reinhard");
                    ui.selectable_value(&mut s.tone_map, ToneMap::Aces, "ACES");
                });
            ComboBox::from_label("specular")
                .selected_text(match s.specular {
                    SpecularChoice::PerMaterial => "per material",
                    SpecularChoice::Phong => "Phong",
                    SpecularChoice::Blinn => "Blinn-Phong",
                })
                .show_ui(ui, |ui| {
                    ui.selectable_value(&mut s.specular, SpecularChoice::PerMaterial, "per material");
                    ui.selectable_value(&mut s.specular, SpecularChoice::Phong, "Phong");
                    ui.selectable_value(&mut s.specular, SpecularChoice::Blinn, "Blinn-Phong");
                });
            let Some(doc) = self.document.loaded.as_mut() else { return };
            let r = &mut doc.scene.render;
            ui.add(Slider::new(&mut r.max_depth, 1..=MAX_DEPTH_LIMIT).text("max depth"));
            ui.horizontal(|ui| {
                ui.checkbox(&mut r.shadows, "shadows");
                ui.checkbox(&mut r.reflections, "reflection");
                ui.checkbox(&mut r.refractions, "refraction");
            });
            ui.horizontal(|ui| {
                ui.label("shadows of transparent objects:");
                ui.radio_value(&mut r.shadow_mode, ShadowMode::Opaque, "opaque");
                ui.radio_value(&mut r.shadow_mode, ShadowMode::Tinted, "tinted");
            });
        });
    }

    fn lights_section(&mut self, ui: &mut Ui) {
        let selected = self.selection.light;
        let mut remove = None;
        let mut add = false;
        CollapsingHeader::new("Lights").default_open(true).show(ui, |ui| {
            let Some(doc) = self.document.loaded.as_mut() else { return };
            // Sliders reach a scene's size beyond its bounds.
            let (lo, hi) = (doc.bounds.0 - doc.radius * 2.0, doc.bounds.1 + doc.radius * 2.0);
            let (lo, hi) = if lo.cmple(hi).all() { (lo, hi) } else { (Vec3::splat(-10.0), Vec3::splat(10.0)) };
            for (i, light) in doc.scene.lights.iter_mut().enumerate() {
                let kind = match light.kind {
                    LightKind::Point { .. } => "point",
                    LightKind::Directional { .. } => "directional",
                };
                let mut header = CollapsingHeader::new(format!("Light {} ({kind})", i + 1)).id_salt(("light", i)).default_open(true);
                if selected == Some(i) {
                    header = header.open(Some(true));
                }
                header.show(ui, |ui| {
                    ui.checkbox(&mut light.enabled, "on");
                    match &mut light.kind {
                        LightKind::Point { position } => point(ui, position, lo, hi),
                        LightKind::Directional { direction } => {
                            let mut d = *direction;
                            point(ui, &mut d, Vec3::splat(-1.0), Vec3::ONE);
                            if d.length() > 1e-6 {
                                *direction = d.normalize();
                            }
                        }
                    }
                    colour(ui, "colour", &mut light.color);
                    ui.add(slider(&mut light.intensity, 0.0..=10.0, "intensity").logarithmic(true));
                    attenuation(ui, i, &mut light.attenuation);
                    if ui.button("Remove").clicked() {
                        remove = Some(i);
                    }
                });
            }
            add = ui.button("Add light").clicked();
        });
        let Some(doc) = self.document.loaded.as_mut() else { return };
        if let Some(i) = remove {
            doc.scene.lights.remove(i);
            self.selection.light = None;
        }
        if add {
            // Above the scene, near the camera's side of it.
            let (lo, hi) = doc.bounds;
            let centre = if lo.cmple(hi).all() { (lo + hi) / 2.0 } else { doc.scene.camera.look_at };
            let toward_eye = (doc.scene.camera.eye - centre).normalize_or_zero();
            let position = centre + (doc.scene.camera.up.normalize() + toward_eye) * doc.radius * 1.5;
            doc.scene.lights.push(Light {
                kind: LightKind::Point { position },
                color: Vec3::ONE,
                intensity: 0.5,
                attenuation: Attenuation::None,
                enabled: true,
            });
            self.selection.light = Some(doc.scene.lights.len() - 1);
        }
    }

    fn environment_section(&mut self, ui: &mut Ui) {
        CollapsingHeader::new("Ambient, background, depth cue").default_open(false).show(ui, |ui| {
            let Some(doc) = self.document.loaded.as_mut() else { return };
            let s = &mut doc.scene;
            // I_a is a colour times an intensity; edit them apart.
            let mut intensity = s.ambient.max_element();
            let mut tint = if intensity > 0.0 { s.ambient / intensity } else { Vec3::ONE };
            colour(ui, "ambient colour", &mut tint);
            ui.add(slider(&mut intensity, 0.0..=1.0, "ambient intensity"));
            s.ambient = tint * intensity.max(0.0);
            colour(ui, "background", &mut s.background);
            let mut on = s.depth_cue.is_some();
            ui.checkbox(&mut on, "depth cue");
            let far = doc.depth_extent() * 1.5;
            let s = &mut doc.scene;
            match (on, &mut s.depth_cue) {
                (true, None) => {
                    s.depth_cue = Some(DepthCue { color: s.background, near: far / 8.0, far: far / 2.0, near_scale: 1.0, far_scale: 0.2 })
                }
                (false, Some(_)) => s.depth_cue = None,
                (true, Some(d)) => {
                    colour(ui, "depth cue colour", &mut d.color);
                    ui.add(slider(&mut d.near, 0.0..=far, "near"));
                    ui.add(slider(&mut d.far, 0.0..=far, "far"));
                    ui.add(slider(&mut d.near_scale, 0.0..=1.0, "near scale"));
                    ui.add(slider(&mut d.far_scale, 0.0..=1.0, "far scale"));
                    // The loader requires far > near; so does the kernel's ramp.
                    d.far = d.far.max(d.near + far * 1e-3);
                }
                (false, None) => {}
            }
        });
    }

    fn selection_section(&mut self, ui: &mut Ui) {
        let Some(index) = self.selection.object else { return };
        let mut deselect = false;
        CollapsingHeader::new("Selected object").default_open(true).show(ui, |ui| {
            let Some(doc) = self.document.loaded.as_mut() else { return };
            let Some(object) = doc.scene.objects.get(index) else { return };
            let kind = object.shapes.first().map_or("empty", Shape::name);
            let m = object.material;
            let users = doc.scene.objects.iter().filter(|o| o.material == m).count();
            ui.label(format!("Object {}: {kind}, {} primitive(s)", index + 1, object.shapes.len()));
            let Some(mat) = doc.scene.materials.get_mut(m) else { return };
            ui.label(format!("material “{}”, used by {users} object(s)", mat.name));
            ui.add(slider(&mut mat.ambient, 0.0..=1.0, "k_a ambient"));
            ui.add(slider(&mut mat.diffuse, 0.0..=1.0, "k_d diffuse"));
            ui.add(slider(&mut mat.specular, 0.0..=1.0, "k_s specular"));
            ui.add(slider(&mut mat.shininess, 1.0..=1000.0, "n shininess").logarithmic(true));
            colour(ui, "O_d colour", &mut mat.color);
            let mut custom = mat.specular_color.is_some();
            ui.checkbox(&mut custom, "coloured highlights");
            match (custom, &mut mat.specular_color) {
                (true, None) => mat.specular_color = Some(Vec3::ONE),
                (false, Some(_)) => mat.specular_color = None,
                (true, Some(c)) => colour(ui, "O_s highlight colour", c),
                (false, None) => {}
            }
            ui.horizontal(|ui| {
                ui.radio_value(&mut mat.specular_model, SpecularModel::Phong, "Phong");
                ui.radio_value(&mut mat.specular_model, SpecularModel::BlinnPhong, "Blinn-Phong");
            });
            let mut metallic = mat.metallic_f0.is_some();
            ui.checkbox(&mut metallic, "metallic (Schlick F0)");
            match (metallic, &mut mat.metallic_f0) {
                (true, None) => mat.metallic_f0 = Some(mat.color),
                (false, Some(_)) => mat.metallic_f0 = None,
                (true, Some(f0)) => colour(ui, "F0", f0),
                (false, None) => {}
            }
            let mut checkered = mat.checker.is_some();
            ui.checkbox(&mut checkered, "checker (O_d above on even tiles)");
            match (checkered, &mut mat.checker) {
                (true, None) => mat.checker = Some(Checker { color: mat.color * 0.25, size: 1.0 }),
                (false, Some(_)) => mat.checker = None,
                (true, Some(c)) => {
                    colour(ui, "O_d of the odd tiles", &mut c.color);
                    ui.add(slider(&mut c.size, 0.01..=100.0, "tile size").logarithmic(true));
                    c.size = c.size.max(0.01);
                }
                (false, None) => {}
            }
            colour(ui, "k_m reflectance", &mut mat.reflect);
            colour(ui, "k_t transmittance", &mut mat.transmit);
            ui.add(slider(&mut mat.ior, 1.0..=3.0, "index of refraction"));
            mat.ior = mat.ior.clamp(0.01, 100.0);
            ui.checkbox(&mut mat.fresnel, "Fresnel (Schlick)");
            deselect = ui.button("Deselect").clicked();
        });
        if deselect {
            self.selection.object = None;
        }
    }

    fn files_section(&mut self, ui: &mut Ui) {
        CollapsingHeader::new("Save").default_open(true).show(ui, |ui| {
            // A page cannot write to a path: it saves by download from its bar.
            if cfg!(not(target_arch = "wasm32")) {
                self.save_rows(ui);
            }
            if let Some((text, is_error)) = &self.notice {
                let color = if *is_error { ui.visuals().warn_fg_color } else { ui.visuals().text_color() };
                ui.colored_label(color, text);
            }
        });
    }

    fn save_rows(&mut self, ui: &mut Ui) {
        ui.horizontal(|ui| {
            let label = ui.label("image");
            ui.text_edit_singleline(&mut self.document.screenshot_path).labelled_by(label.id);
            if ui.button("Save image").on_hover_text("PNG, PPM, EXR or PFM, by the name's extension, at the render resolution").clicked() {
                self.save_screenshot();
            }
        });
        ui.horizontal(|ui| {
            let label = ui.label("scene");
            ui.text_edit_singleline(&mut self.document.save_path).labelled_by(label.id);
            if ui.button("Save scene as").on_hover_text("TOML with the current camera, lights and materials").clicked() {
                self.save_scene();
            }
        });
    }
}

fn attenuation(ui: &mut Ui, light: usize, a: &mut Attenuation) {
    let name = match a {
        Attenuation::None => "none",
        Attenuation::InverseSquare => "1/d²",
        Attenuation::Polynomial { .. } => "1/(c1 + c2·d + c3·d²)",
    };
    ComboBox::new(("attenuation", light), "attenuation").selected_text(name).show_ui(ui, |ui| {
        if ui.selectable_label(matches!(a, Attenuation::None), "none").clicked() {
            *a = Attenuation::None;
        }
        if ui.selectable_label(matches!(a, Attenuation::InverseSquare), "1/d²").clicked() {
            *a = Attenuation::InverseSquare;
        }
        if ui.selectable_label(matches!(a, Attenuation::Polynomial { .. }), "1/(c1 + c2·d + c3·d²)").clicked()
            && !matches!(a, Attenuation::Polynomial { .. })
        {
            *a = Attenuation::Polynomial { c1: 1.0, c2: 0.0, c3: 0.0 };
        }
    });
    if let Attenuation::Polynomial { c1, c2, c3 } = a {
        ui.horizontal(|ui| {
            for (c, name) in [(&mut *c1, "c1"), (&mut *c2, "c2"), (&mut *c3, "c3")] {
                ui.add(egui::DragValue::new(c).speed(0.01).range(0.0..=f32::MAX).prefix(format!("{name} ")));
            }
        });
        // The loader rejects all-zero coefficients (an infinite gain).
        if *c1 + *c2 + *c3 <= 0.0 {
            *c1 = 1.0;
        }
    }
}
