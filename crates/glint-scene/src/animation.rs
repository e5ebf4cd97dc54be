//! Animation: the camera and the positions of point lights as functions of
//! the frame number, as a TOML scene's `[animation]` describes them
//! (docs/scene-format.md). Tracks hold absolute values (an orbit keeps the
//! camera it starts from), so posing a scene at frame n depends on n alone,
//! never on the frames posed before.

use glam::{DQuat, DVec3, Vec3};

use crate::{Camera, LightKind, Projection, Scene};

/// The most frames an animation may have (over an hour at 24 frames per second).
pub const MAX_FRAMES: u32 = 100_000;

#[derive(Debug, Clone, PartialEq)]
pub struct Animation {
    /// The animation is frames 0..`frames`.
    pub frames: u32,
    /// Frames per second: how `time` keys are placed, and the rate of a video.
    pub fps: f32,
    /// How every keyed track moves between its keys.
    pub interpolation: Interpolation,
    /// `None`: the camera stays the scene's.
    pub camera: Option<CameraTrack>,
    pub lights: Vec<LightTrack>,
}

#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum Interpolation {
    /// Straight from key to key at constant speed.
    #[default]
    Linear,
    /// A cubic Hermite curve through the keys whose tangent at an inner key
    /// is the Catmull-Rom one, (p₊ − p₋)/(t₊ − t₋), and 0 at the first and
    /// last key: continuous velocity (C1), easing in and out at the ends. With
    /// two keys it is smoothstep.
    Smooth,
}

#[derive(Debug, Clone, PartialEq)]
pub enum CameraTrack {
    /// At least one key, in increasing frame order; all keys have the same
    /// projection. Before the first key and after the last the camera holds.
    Keys(Vec<CameraKey>),
    Orbit(Orbit),
}

#[derive(Debug, Clone, Copy, PartialEq)]
pub struct CameraKey {
    /// Where the key sits; it may fall between frames.
    pub frame: f32,
    pub camera: Camera,
}

/// The camera turned rigidly (eye, look-at point and up together) about an
/// axis: by 360° · `turns` · n / frames at frame n, counter-clockwise seen
/// from the axis' tip, so that a whole number of turns loops without a
/// repeated frame.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Orbit {
    /// The camera at frame 0.
    pub start: Camera,
    /// A point on the axis.
    pub center: Vec3,
    /// The axis' direction, of unit length.
    pub axis: Vec3,
    pub turns: f32,
}

/// Keyed positions of one point light.
#[derive(Debug, Clone, PartialEq)]
pub struct LightTrack {
    /// The light's index in `Scene::lights`.
    pub light: usize,
    /// At least one key, in increasing frame order.
    pub keys: Vec<PositionKey>,
}

#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PositionKey {
    pub frame: f32,
    pub position: Vec3,
}

impl Animation {
    /// The camera at `frame`, or `None` when the camera is not animated.
    pub fn camera_at(&self, frame: u32) -> Option<Camera> {
        Some(match self.camera.as_ref()? {
            CameraTrack::Orbit(orbit) => orbit.at(frame, self.frames),
            CameraTrack::Keys(keys) => {
                let v = sample(
                    keys.len(),
                    |i| f64::from(keys[i].frame),
                    |i| camera_values(&keys[i].camera),
                    f64::from(frame),
                    self.interpolation,
                );
                let f = |i: usize| Vec3::new(v[i] as f32, v[i + 1] as f32, v[i + 2] as f32);
                let extent = v[9] as f32;
                let projection = match keys[0].camera.projection {
                    Projection::Perspective { .. } => Projection::Perspective { fov_y_degrees: extent },
                    Projection::Orthographic { .. } => Projection::Orthographic { height: extent },
                };
                Camera { eye: f(0), look_at: f(3), up: f(6), projection }
            }
        })
    }

    /// The first frame whose camera cannot be rendered (a smooth curve can
    /// overshoot a field of view, an interpolated `up` can turn parallel to the
    /// view), and why.
    pub fn first_bad_camera(&self) -> Option<(u32, String)> {
        (0..self.frames).find_map(|n| {
            let c = self.camera_at(n)?;
            let problem = if !(c.eye.is_finite() && c.look_at.is_finite() && c.up.is_finite()) || crate::view_overflows(&c) {
                Some("the camera leaves the range of 32-bit floats".to_string())
            } else if c.up == Vec3::ZERO {
                Some("`up` is zero".into())
            } else if c.basis().is_none() {
                Some("`up` is parallel to the view direction (or eye equals look_at)".into())
            } else {
                match c.projection {
                    Projection::Perspective { fov_y_degrees: f } if !(f > 0.0 && f < 180.0) => {
                        Some(format!("the fov is {f}, not between 0 and 180 degrees"))
                    }
                    Projection::Orthographic { height } if !(height > 0.0 && height.is_finite()) => {
                        Some(format!("the view-plane height is {height}, not positive"))
                    }
                    _ => None,
                }
            };
            problem.map(|p| (n, p))
        })
    }
}

impl Orbit {
    /// The camera at `frame` of an animation of `frames` frames.
    pub fn at(&self, frame: u32, frames: u32) -> Camera {
        let angle = std::f64::consts::TAU * f64::from(self.turns) * f64::from(frame) / f64::from(frames.max(1));
        let turn = DQuat::from_axis_angle(self.axis.as_dvec3().normalize_or_zero(), angle);
        let center = self.center.as_dvec3();
        let point = |p: Vec3| (center + turn * (p.as_dvec3() - center)).as_vec3();
        Camera {
            eye: point(self.start.eye),
            look_at: point(self.start.look_at),
            up: (turn * self.start.up.as_dvec3()).as_vec3(),
            ..self.start
        }
    }
}

impl LightTrack {
    /// The light's position at `frame`.
    pub fn position_at(&self, frame: u32, interpolation: Interpolation) -> Vec3 {
        let keys = &self.keys;
        let p = |i: usize| keys[i].position.as_dvec3().to_array();
        DVec3::from_array(sample(keys.len(), |i| f64::from(keys[i].frame), p, f64::from(frame), interpolation)).as_vec3()
    }
}

impl Scene {
    /// Poses the camera and the keyed point lights at `frame`. Without an
    /// animation, nothing changes.
    pub fn set_frame(&mut self, frame: u32) {
        let Some(animation) = &self.animation else { return };
        if let Some(camera) = animation.camera_at(frame) {
            self.camera = camera;
        }
        for track in &animation.lights {
            if let Some(LightKind::Point { position }) = self.lights.get_mut(track.light).map(|l| &mut l.kind) {
                *position = track.position_at(frame, animation.interpolation);
            }
        }
    }
}

/// A camera as the ten numbers a key interpolates: eye, look_at, up, and the
/// field of view or view-plane height.
fn camera_values(c: &Camera) -> [f64; 10] {
    let extent = match c.projection {
        Projection::Perspective { fov_y_degrees } => fov_y_degrees,
        Projection::Orthographic { height } => height,
    };
    let mut v = [0.0; 10];
    for (i, p) in [c.eye, c.look_at, c.up].iter().enumerate() {
        v[3 * i..3 * i + 3].copy_from_slice(&p.as_dvec3().to_array());
    }
    v[9] = f64::from(extent);
    v
}

/// The value at frame `t` of a track of `count` keys (at least one), key i at
/// `time(i)` (increasing) with `value(i)`. Computed in f64, so a frame on a key
/// gives the key's own value.
fn sample<const N: usize>(
    count: usize,
    time: impl Fn(usize) -> f64,
    value: impl Fn(usize) -> [f64; N],
    t: f64,
    interpolation: Interpolation,
) -> [f64; N] {
    // The key that starts the segment holding `t`; before the first and after
    // the last key the track holds.
    let i = (0..count).rev().find(|&i| time(i) <= t).unwrap_or(0);
    if i + 1 >= count || t <= time(0) {
        return value(i);
    }
    let (t0, t1) = (time(i), time(i + 1));
    let (h, s) = (t1 - t0, (t - t0) / (t1 - t0));
    let (p0, p1) = (value(i), value(i + 1));
    let mut out = [0.0; N];
    match interpolation {
        Interpolation::Linear => {
            for c in 0..N {
                out[c] = p0[c] + s * (p1[c] - p0[c]);
            }
        }
        Interpolation::Smooth => {
            let tangent = |k: usize| -> [f64; N] {
                let mut m = [0.0; N];
                if k > 0 && k + 1 < count {
                    let (before, after) = (value(k - 1), value(k + 1));
                    for c in 0..N {
                        m[c] = (after[c] - before[c]) / (time(k + 1) - time(k - 1));
                    }
                }
                m
            };
            let (m0, m1) = (tangent(i), tangent(i + 1));
            let (s2, s3) = (s * s, s * s * s);
            let (h00, h10, h01, h11) = (2.0 * s3 - 3.0 * s2 + 1.0, s3 - 2.0 * s2 + s, 3.0 * s2 - 2.0 * s3, s3 - s2);
            for c in 0..N {
                out[c] = h00 * p0[c] + h10 * h * m0[c] + h01 * p1[c] + h11 * h * m1[c];
            }
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    fn keys(points: &[(f32, f32)]) -> LightTrack {
        LightTrack { light: 0, keys: points.iter().map(|&(frame, x)| PositionKey { frame, position: Vec3::new(x, 2.0 * x, -x) }).collect() }
    }

    /// The x of the track between frames, for derivatives.
    fn x_at(track: &LightTrack, t: f64, interpolation: Interpolation) -> f64 {
        let k = &track.keys;
        sample(k.len(), |i| f64::from(k[i].frame), |i| [f64::from(k[i].position.x)], t, interpolation)[0]
    }

    #[test]
    fn keys_are_hit_exactly_and_held_outside() {
        let track = keys(&[(2.0, 0.1), (5.0, 0.7), (9.0, -0.3)]);
        for interpolation in [Interpolation::Linear, Interpolation::Smooth] {
            for (frame, x) in [(2, 0.1f32), (5, 0.7), (9, -0.3), (0, 0.1), (40, -0.3)] {
                assert_eq!(track.position_at(frame, interpolation), Vec3::new(x, 2.0 * x, -x), "{interpolation:?} frame {frame}");
            }
        }
    }

    #[test]
    fn linear_midpoints_are_the_mean_of_the_keys() {
        let track = keys(&[(0.0, 1.0), (4.0, 3.0)]);
        assert_eq!(track.position_at(2, Interpolation::Linear), Vec3::new(2.0, 4.0, -2.0));
        assert_eq!(track.position_at(1, Interpolation::Linear).x, 1.5);
    }

    #[test]
    fn smooth_with_two_keys_is_smoothstep() {
        let track = keys(&[(0.0, 0.0), (10.0, 1.0)]);
        for n in 0..=10 {
            let s = f64::from(n) / 10.0;
            let want = s * s * (3.0 - 2.0 * s);
            assert!((f64::from(track.position_at(n, Interpolation::Smooth).x) - want).abs() < 1e-7, "frame {n}");
        }
    }

    #[test]
    fn smooth_has_continuous_velocity_at_inner_keys() {
        let track = keys(&[(0.0, 0.0), (4.0, 2.0), (10.0, 1.0), (12.0, 5.0)]);
        for key in [4.0, 10.0] {
            let d = 0.001;
            let before = (x_at(&track, key, Interpolation::Smooth) - x_at(&track, key - d, Interpolation::Smooth)) / d;
            let after = (x_at(&track, key + d, Interpolation::Smooth) - x_at(&track, key, Interpolation::Smooth)) / d;
            assert!((before - after).abs() < 1e-2, "at {key}: {before} then {after}");
            // Linear has a kink there.
            let lb = (x_at(&track, key, Interpolation::Linear) - x_at(&track, key - d, Interpolation::Linear)) / d;
            let la = (x_at(&track, key + d, Interpolation::Linear) - x_at(&track, key, Interpolation::Linear)) / d;
            assert!((lb - la).abs() > 0.1);
        }
        // And the tangent there is Catmull-Rom's: (p₊ − p₋)/(t₊ − t₋).
        let d = 0.001;
        let slope = (x_at(&track, 4.0 + d, Interpolation::Smooth) - x_at(&track, 4.0 - d, Interpolation::Smooth)) / (2.0 * d);
        assert!((slope - 0.1).abs() < 1e-3, "{slope}");
    }

    fn orbit(turns: f32) -> Orbit {
        let start = Camera {
            eye: Vec3::new(3.0, 2.0, 4.0),
            look_at: Vec3::new(1.0, 0.5, 0.0),
            up: Vec3::Y,
            projection: Projection::Perspective { fov_y_degrees: 40.0 },
        };
        Orbit { start, center: Vec3::new(1.0, 0.0, 0.0), axis: Vec3::Y, turns }
    }

    #[test]
    fn an_orbit_keeps_its_radius_and_loops() {
        let o = orbit(1.0);
        let radius = |c: Camera| (c.eye - o.center).reject_from(o.axis).length();
        let r0 = radius(o.start);
        for n in 0..48 {
            let c = o.at(n, 48);
            assert!((radius(c) - r0).abs() < 1e-5, "frame {n}");
            assert!((c.eye.y - o.start.eye.y).abs() < 1e-6, "stays at its height");
            assert!((c.eye.distance(c.look_at) - o.start.eye.distance(o.start.look_at)).abs() < 1e-5, "rigid");
        }
        assert_eq!(o.at(0, 48), o.start);
        assert!(o.at(48, 48).eye.distance(o.start.eye) < 1e-5, "a whole turn comes back");
        // A quarter turn counter-clockwise about +y takes +z to +x.
        let quarter = o.at(12, 48);
        let (from, to) = (o.start.eye - o.center, quarter.eye - o.center);
        assert!((to - Vec3::new(from.z, from.y, -from.x)).length() < 1e-5, "{to}");
    }
}
