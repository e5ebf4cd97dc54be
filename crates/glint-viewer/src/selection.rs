//! What is selected: an object, whose material the side panel edits and whose
//! outline the image shows, and a light, whose marker is ringed and whose
//! section stays open. Clicking the image selects; dragging a point light's
//! marker moves the light.

use egui::{Color32, Pos2, Rect, Stroke, StrokeKind};
use glam::Vec3;
use glint_scene::{LightKind, Scene};

use crate::one_line;
use crate::document::LoadedScene;
use crate::image::TracedImage;

/// How near (in points) a click must land to a light's marker to grab it.
const LIGHT_GRAB_RADIUS: f32 = 10.0;

#[derive(Default)]
pub(crate) struct Selection {
    pub object: Option<usize>,
    pub light: Option<usize>,
    /// The light whose marker is being dragged in the image.
    dragged_light: Option<usize>,
}

impl Selection {
    /// A newly opened `scene` starts with nothing selected; a reloaded one keeps
    /// what it still has.
    pub fn for_scene(&mut self, scene: &Scene, reload: bool) {
        if !reload {
            self.object = None;
            self.light = None;
        }
        self.object = self.object.filter(|&i| i < scene.objects.len());
        self.light = self.light.filter(|&i| i < scene.lights.len());
    }

    /// A drag starts: with `light`, the one whose marker it grabbed, selected.
    pub fn start_drag(&mut self, light: Option<usize>) {
        self.dragged_light = light;
        if light.is_some() {
            self.light = light;
        }
    }

    pub fn stop_drag(&mut self) {
        self.dragged_light = None;
    }

    pub fn dragged_light(&self) -> Option<usize> {
        self.dragged_light
    }

    /// A click at `pos` selects the light marker there, or else the object
    /// under the pointer; a failed read-back goes to `error`.
    pub fn click(&mut self, image: &TracedImage, doc: &LoadedScene, pos: Pos2, error: &mut Option<String>) {
        match light_at(image, &doc.scene, pos) {
            Some(i) => self.light = Some(i),
            None => match image.object_at(doc, pos) {
                Some(Ok(id)) => self.object = id.map(|i| i as usize),
                Some(Err(e)) => *error = Some(one_line(e)),
                None => {}
            },
        }
    }

    /// The selected object's outline (none for an infinite plane) and the
    /// point lights' markers.
    pub fn draw(&self, painter: &egui::Painter, image: &TracedImage, scene: &Scene) {
        let bounds = self.object.and_then(|i| scene.objects.get(i)).and_then(|object| {
            object.shapes.iter().filter_map(glint_scene::Shape::bounds).reduce(|(lo, hi), (a, b)| (lo.min(a), hi.max(b)))
        });
        if let Some((lo, hi)) = bounds {
            let corners: Option<Vec<Pos2>> = (0..8)
                .map(|i| {
                    let pick = |bit: u32, a: f32, b: f32| if i & bit == 0 { a } else { b };
                    image.to_screen(&scene.camera, Vec3::new(pick(1, lo.x, hi.x), pick(2, lo.y, hi.y), pick(4, lo.z, hi.z)))
                })
                .collect();
            if let Some(corners) = corners {
                let outline = Rect::from_points(&corners);
                painter.rect_stroke(outline, 2.0, Stroke::new(2.0, Color32::from_rgb(255, 200, 40)), StrokeKind::Outside);
            }
        }
        for (i, light) in scene.lights.iter().enumerate() {
            let LightKind::Point { position } = light.kind else { continue };
            let Some(at) = image.to_screen(&scene.camera, position) else { continue };
            let c = light.color.clamp(Vec3::ZERO, Vec3::ONE) * 255.0;
            let fill = if light.enabled { Color32::from_rgb(c.x as u8, c.y as u8, c.z as u8) } else { Color32::from_gray(60) };
            painter.circle_filled(at, 6.0, fill);
            painter.circle_stroke(at, 6.0, Stroke::new(1.5, Color32::BLACK));
            if self.light == Some(i) {
                painter.circle_stroke(at, 10.0, Stroke::new(2.0, Color32::WHITE));
            }
        }
    }
}

/// The point light whose marker is within reach of `pos`.
pub fn light_at(image: &TracedImage, scene: &Scene, pos: Pos2) -> Option<usize> {
    scene
        .lights
        .iter()
        .enumerate()
        .filter_map(|(i, l)| match l.kind {
            LightKind::Point { position } => Some((i, image.to_screen(&scene.camera, position)?.distance(pos))),
            LightKind::Directional { .. } => None,
        })
        .filter(|(_, d)| *d <= LIGHT_GRAB_RADIUS)
        .min_by(|a, b| a.1.total_cmp(&b.1))
        .map(|(i, _)| i)
}
