//! Observer mode: the inspected pixel's ray tree, and the camera that traced
//! it, frozen while the view's camera moves freely as a second camera, the
//! observer. The image shows the scene from the observer; drawn over it in 3-D
//! are the frozen camera's frame, its view window and the trees
//! (`glint_observer`, which `glint probe --observer` draws too).

use egui::{Color32, Painter, Pos2, Rect, Shape, Stroke};
use glam::DVec2;
use glint_gpu::probe::RayTree;
use glint_observer::{clip_to_box, Ink, Observer, Overlay, RayId};
use glint_scene::camera_frame::CameraFrame;
use glint_scene::Camera;

/// The colour of the ray whose node the pointer is over.
pub(crate) const HIGHLIGHT_COLOR: Color32 = Color32::from_rgb(255, 0, 255);
/// How many pixels a row or a column of probed pixels spreads over.
const SPREAD_PIXELS: u32 = 9;

/// Which pixels observer mode follows.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub(crate) enum Spread {
    /// The pinned pixel alone.
    #[default]
    Pixel,
    /// Pixels spread along the pinned pixel's row, as the teaching tools show a scan line.
    Row,
    /// Pixels spread along its column.
    Column,
}

impl Spread {
    /// The pixels to probe in an image of `size`: `pinned` first, then others
    /// evenly spread along its row or column.
    pub fn pixels(self, pinned: (u32, u32), size: (u32, u32)) -> Vec<(u32, u32)> {
        let along = |n: u32| (0..SPREAD_PIXELS.min(n)).map(move |k| ((2 * k + 1) * n / (2 * SPREAD_PIXELS.min(n))).min(n - 1));
        let others: Vec<(u32, u32)> = match self {
            Spread::Pixel => Vec::new(),
            Spread::Row => along(size.0).map(|x| (x, pinned.1)).collect(),
            Spread::Column => along(size.1).map(|y| (pinned.0, y)).collect(),
        };
        std::iter::once(pinned).chain(others.into_iter().filter(|&p| p != pinned)).collect()
    }
}

/// What observer mode froze when it began.
pub(crate) struct Observed {
    /// The camera that traced the trees, given back on leaving.
    pub camera: Camera,
    pub frame: CameraFrame,
    /// The probed pixels and their trees, the pinned pixel first.
    pub trees: Vec<((u32, u32), RayTree)>,
}

/// Paints `overlay` as `observer` sees it into `rect`, the ray `highlighted`
/// in its own colour; with `rays_only`, the rays and their hits alone.
pub(crate) fn paint(painter: &Painter, rect: Rect, observer: &Observer, overlay: &Overlay, highlighted: Option<RayId>, rays_only: bool) {
    let size = DVec2::new(f64::from(observer.width), f64::from(observer.height));
    let to_screen = |p: DVec2| rect.min + egui::vec2((p.x / size.x) as f32, (p.y / size.y) as f32) * rect.size();
    // A little beyond the image, so a clipped line's ends stay out of sight.
    let margin = size * 0.05;
    for segment in &overlay.segments {
        if rays_only && segment.ray.is_none() {
            continue;
        }
        let Some((a, b)) = observer.project_segment(segment.a, segment.b) else { continue };
        let Some((a, b)) = clip_to_box(a, b, -margin, size + margin) else { continue };
        let (a, b) = (to_screen(a), to_screen(b));
        let lit = segment.ray.is_some() && segment.ray == highlighted;
        let color = if lit { HIGHLIGHT_COLOR } else { color(segment.ink) };
        let width = segment.ink.line_width() as f32 * if lit { 2.0 } else { 1.0 };
        let outline = Stroke::new(width + 2.0, Color32::from_black_alpha(160));
        if segment.ink.is_dashed() {
            painter.extend(Shape::dashed_line(&[a, b], outline, 6.0, 4.0));
            painter.extend(Shape::dashed_line(&[a, b], Stroke::new(width, color), 6.0, 4.0));
        } else {
            if segment.ink != Ink::Grid {
                painter.line_segment([a, b], outline);
            }
            painter.line_segment([a, b], Stroke::new(width, color));
        }
        if segment.ink == Ink::ShadowBlocked {
            cross(painter, b, width + 1.0, color);
        }
    }
    for dot in &overlay.dots {
        if rays_only && dot.ink != Ink::Hit {
            continue;
        }
        let Some(at) = observer.project(dot.at) else { continue };
        let at = to_screen(at);
        painter.circle_filled(at, 4.5, Color32::from_black_alpha(180));
        painter.circle_filled(at, 3.5, color(dot.ink));
    }
}

/// Where a blocked shadow ray stops.
fn cross(painter: &Painter, at: Pos2, width: f32, color: Color32) {
    let r = 5.0;
    for d in [egui::vec2(r, r), egui::vec2(r, -r)] {
        painter.line_segment([at - d, at + d], Stroke::new(width, color));
    }
}

fn color(ink: Ink) -> Color32 {
    let [r, g, b] = ink.rgb();
    Color32::from_rgb(r, g, b)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_row_or_column_spreads_evenly_and_starts_with_the_pinned_pixel() {
        assert_eq!(Spread::Pixel.pixels((5, 7), (90, 60)), [(5, 7)]);
        let row = Spread::Row.pixels((5, 7), (90, 60));
        assert_eq!(row[0], (5, 7));
        assert_eq!(row[1..].iter().map(|p| p.0).collect::<Vec<_>>(), [15, 25, 35, 45, 55, 65, 75, 85], "(2k + 1)·90/18, 5 already there");
        assert!(row.iter().all(|p| p.1 == 7));
        let column = Spread::Column.pixels((5, 7), (90, 3));
        assert_eq!(column, [(5, 7), (5, 0), (5, 1), (5, 2)]);
    }
}
