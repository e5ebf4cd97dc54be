//! Camera moves on the scene's own camera model: orbit, pan, zoom, fly, frame
//! all and switching projection. Every move keeps the camera's basis valid
//! (the eye never reaches the look-at point, the view never lines up with up).

use glam::Vec3;
use glint_scene::{Camera, Projection};

/// How close to the up vector (radians) an orbit may turn the view.
const POLE_MARGIN: f32 = 0.01;
/// The nearest the eye comes to the look-at point, relative to `scale`.
const MIN_DISTANCE: f32 = 1e-4;

fn offset(cam: &Camera) -> Vec3 {
    cam.eye - cam.look_at
}

/// Turns the eye about `look_at`: `yaw` radians about the up vector (right
/// hand rule), then `pitch` radians towards it.
pub fn orbit(cam: &mut Camera, yaw: f32, pitch: f32) {
    let up = cam.up.normalize();
    let off = offset(cam);
    let r = off.length();
    let dir = glam::Quat::from_axis_angle(up, yaw) * (off / r);
    let horizontal = (dir - dir.dot(up) * up).normalize_or_zero();
    if horizontal == Vec3::ZERO {
        return;
    }
    let theta = dir.dot(up).clamp(-1.0, 1.0).acos();
    let theta = (theta - pitch).clamp(POLE_MARGIN, std::f32::consts::PI - POLE_MARGIN);
    cam.eye = cam.look_at + r * (theta.cos() * up + theta.sin() * horizontal);
}

/// World units per pixel of an image `height` pixels tall, at the look-at distance.
fn units_per_pixel(cam: &Camera, height: u32) -> f32 {
    let window = match cam.projection {
        Projection::Perspective { fov_y_degrees } => 2.0 * (fov_y_degrees.to_radians() / 2.0).tan() * offset(cam).length(),
        Projection::Orthographic { height } => height,
    };
    window / height.max(1) as f32
}

/// Moves eye and look-at together so the scene follows a drag of (`dx`, `dy`)
/// pixels (y down) on an image `height` pixels tall.
pub fn pan(cam: &mut Camera, dx: f32, dy: f32, height: u32) {
    let Some(b) = cam.basis() else { return };
    let s = units_per_pixel(cam, height);
    let delta = -dx * s * b.u.as_vec3() + dy * s * b.v.as_vec3();
    cam.eye += delta;
    cam.look_at += delta;
}

/// Moves `point` in the plane through it parallel to the image, so it follows
/// a drag of (`dx`, `dy`) pixels on an image `height` pixels tall.
pub fn drag_point(cam: &Camera, point: Vec3, dx: f32, dy: f32, height: u32) -> Vec3 {
    let Some(b) = cam.basis() else { return point };
    let (u, v, w) = (b.u.as_vec3(), b.v.as_vec3(), b.w.as_vec3());
    let window = match cam.projection {
        Projection::Perspective { fov_y_degrees } => {
            let depth = (cam.eye - point).dot(w).max(MIN_DISTANCE);
            2.0 * (fov_y_degrees.to_radians() / 2.0).tan() * depth
        }
        Projection::Orthographic { height } => height,
    };
    let s = window / height.max(1) as f32;
    point + dx * s * u - dy * s * v
}

/// Zooms by `factor` (below 1 comes closer): the eye moves towards the look-at
/// point, or the orthographic window shrinks.
pub fn zoom(cam: &mut Camera, factor: f32, scale: f32) {
    match &mut cam.projection {
        Projection::Perspective { .. } => {
            let off = offset(cam) * factor;
            let min = MIN_DISTANCE * scale.max(f32::MIN_POSITIVE);
            cam.eye = cam.look_at + off.normalize() * off.length().max(min);
        }
        Projection::Orthographic { height } => *height = (*height * factor).max(MIN_DISTANCE * scale),
    }
}

/// Moves eye and look-at together: `forward` along the view, `right` along the
/// image's x axis, `up` along the camera's up vector, in world units.
pub fn fly(cam: &mut Camera, forward: f32, right: f32, up: f32) {
    let Some(b) = cam.basis() else { return };
    let delta = -forward * b.w.as_vec3() + right * b.u.as_vec3() + up * cam.up.normalize();
    cam.eye += delta;
    cam.look_at += delta;
}

/// Aims at the centre of the box (`lo`, `hi`) from the current direction, near
/// enough that the box's bounding sphere just fills an image of `aspect`
/// (width / height).
pub fn frame_all(cam: &mut Camera, lo: Vec3, hi: Vec3, aspect: f32) {
    if !(lo.is_finite() && hi.is_finite()) || lo.cmpgt(hi).any() {
        return;
    }
    let centre = (lo + hi) / 2.0;
    let radius = ((hi - lo).length() / 2.0).max(MIN_DISTANCE);
    let dir = offset(cam).normalize();
    match &mut cam.projection {
        Projection::Perspective { fov_y_degrees } => {
            let t = (fov_y_degrees.to_radians() / 2.0).tan();
            let half_angle = t.atan().min((t * aspect).atan());
            cam.eye = centre + dir * (radius / half_angle.sin());
        }
        Projection::Orthographic { height } => {
            *height = 2.0 * radius * (1.0 / aspect).max(1.0);
            // Orthographic rays start on the eye's plane: keep it outside the sphere.
            cam.eye = centre + dir * (2.0 * radius);
        }
    }
    cam.look_at = centre;
}

/// Switches to an orthographic camera showing at the look-at distance what the
/// perspective one shows, or back to a perspective one of `fov` degrees, moving
/// the eye so the look-at plane keeps its framing.
pub fn set_orthographic(cam: &mut Camera, orthographic: bool, fov: f32) {
    let d = offset(cam).length();
    match (cam.projection, orthographic) {
        (Projection::Perspective { fov_y_degrees }, true) => {
            let height = 2.0 * d * (fov_y_degrees.to_radians() / 2.0).tan();
            cam.projection = Projection::Orthographic { height };
        }
        (Projection::Orthographic { height }, false) => {
            let distance = height / 2.0 / (fov.to_radians() / 2.0).tan();
            cam.eye = cam.look_at + offset(cam) / d * distance;
            cam.projection = Projection::Perspective { fov_y_degrees: fov };
        }
        _ => {}
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn camera() -> Camera {
        Camera {
            eye: Vec3::new(0.0, 2.0, 8.0),
            look_at: Vec3::new(0.0, 1.0, 0.0),
            up: Vec3::Y,
            projection: Projection::Perspective { fov_y_degrees: 40.0 },
        }
    }

    fn close(a: Vec3, b: Vec3) -> bool {
        (a - b).length() < 1e-4
    }

    #[test]
    fn orbit_keeps_distance_and_target_and_stops_at_the_pole() {
        let mut c = camera();
        let d = offset(&c).length();
        orbit(&mut c, 0.7, 0.2);
        assert!((offset(&c).length() - d).abs() < 1e-4);
        assert_eq!(c.look_at, Vec3::new(0.0, 1.0, 0.0));
        orbit(&mut c, 0.0, 10.0);
        assert!(c.basis().is_some(), "never straight down the up vector");
        assert!(offset(&c).normalize().dot(Vec3::Y) > 0.99);
        orbit(&mut c, 0.0, -20.0);
        assert!(c.basis().is_some());
    }

    #[test]
    fn a_positive_yaw_turns_counter_clockwise_seen_from_above() {
        let mut c = camera();
        orbit(&mut c, std::f32::consts::FRAC_PI_2, 0.0);
        assert!(close(c.eye, Vec3::new(8.0, 2.0, 0.0)), "{}", c.eye);
    }

    #[test]
    fn pan_moves_the_scene_with_the_pointer() {
        let mut c = camera();
        let before = c.look_at;
        pan(&mut c, 100.0, 0.0, 400);
        let moved = c.look_at - before;
        assert!(moved.x < 0.0 && moved.y.abs() < 1e-6, "the camera moves left when the scene is dragged right");
        // The point under the pointer moves exactly as far as the pointer did.
        let (x, _) = c.project(400, 400, before.as_dvec3()).unwrap();
        assert!((x - 300.0).abs() < 1e-2, "{x}");
    }

    #[test]
    fn a_dragged_point_stays_under_the_pointer() {
        for projection in [Projection::Perspective { fov_y_degrees: 40.0 }, Projection::Orthographic { height: 5.0 }] {
            let c = Camera { projection, ..camera() };
            let p = Vec3::new(1.0, 3.0, -2.0);
            let (x0, y0) = c.project(640, 400, p.as_dvec3()).unwrap();
            let q = drag_point(&c, p, 30.0, -12.0, 400);
            let (x1, y1) = c.project(640, 400, q.as_dvec3()).unwrap();
            assert!((x1 - x0 - 30.0).abs() < 1e-2 && (y1 - y0 + 12.0).abs() < 1e-2, "{projection:?}: {x1} {y1}");
        }
    }

    #[test]
    fn zoom_never_reaches_the_target() {
        let mut c = camera();
        for _ in 0..1000 {
            zoom(&mut c, 0.5, 10.0);
        }
        assert!(c.basis().is_some());
        let mut o = Camera { projection: Projection::Orthographic { height: 4.0 }, ..camera() };
        zoom(&mut o, 0.5, 10.0);
        assert_eq!(o.projection, Projection::Orthographic { height: 2.0 });
    }

    #[test]
    fn fly_moves_along_the_view() {
        let mut c = camera();
        let dir = (c.look_at - c.eye).normalize();
        let eye = c.eye;
        fly(&mut c, 2.0, 0.0, 0.0);
        assert!(close(c.eye, eye + 2.0 * dir));
        fly(&mut c, 0.0, 0.0, 1.0);
        assert!(close(c.eye, eye + 2.0 * dir + Vec3::Y));
    }

    #[test]
    fn frame_all_fits_the_bounding_sphere() {
        let (lo, hi) = (Vec3::new(-1.0, 0.0, -1.0), Vec3::new(1.0, 2.0, 1.0));
        for aspect in [0.5, 1.6] {
            let mut c = camera();
            frame_all(&mut c, lo, hi, aspect);
            assert!(close(c.look_at, Vec3::new(0.0, 1.0, 0.0)));
            // Every corner of the box projects inside the image.
            let (w, h) = ((400.0 * aspect) as u32, 400);
            for i in 0..8 {
                let corner = Vec3::new(
                    if i & 1 == 0 { lo.x } else { hi.x },
                    if i & 2 == 0 { lo.y } else { hi.y },
                    if i & 4 == 0 { lo.z } else { hi.z },
                );
                let (x, y) = c.project(w, h, corner.as_dvec3()).unwrap();
                assert!((0.0..=f64::from(w)).contains(&x) && (0.0..=f64::from(h)).contains(&y), "{aspect}: {x} {y}");
            }
        }
    }

    #[test]
    fn switching_projection_keeps_the_framing() {
        let mut c = camera();
        let d = offset(&c).length();
        set_orthographic(&mut c, true, 40.0);
        let Projection::Orthographic { height } = c.projection else { panic!() };
        assert!((height - 2.0 * d * 20f32.to_radians().tan()).abs() < 1e-4);
        set_orthographic(&mut c, false, 40.0);
        assert_eq!(c.projection, Projection::Perspective { fov_y_degrees: 40.0 });
        assert!((offset(&c).length() - d).abs() < 1e-3);
    }
}
