//! The `[animation]` table of a TOML scene: the frame count and rate, camera
//! keys (`[[animation.camera]]`) or an orbit, and keyed positions of point
//! lights (`[[animation.light]]`). Every key is checked where it is written,
//! and every frame's camera once the tracks are built, so a scene that loads
//! renders at every frame.

use std::collections::BTreeMap;

use serde::Deserialize;
use toml::Spanned;

use super::build::Builder;
use super::values::{Num, V3};
use crate::animation::{CameraKey, CameraTrack, Interpolation, LightTrack, Orbit, PositionKey, MAX_FRAMES};
use crate::{Animation, Camera, Light, LightKind, LoadError, Location, Projection};

/// The frame rate when `fps` is not given.
const DEFAULT_FPS: f32 = 24.0;

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
pub(super) struct AnimationDef {
    frames: Spanned<i64>,
    fps: Option<Spanned<Num>>,
    interpolation: Option<Spanned<String>>,
    orbit: Option<Spanned<OrbitDef>>,
    #[serde(default)]
    camera: Vec<Spanned<CameraKeyDef>>,
    #[serde(default)]
    light: Vec<Spanned<LightKeyDef>>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
pub(super) struct OrbitDef {
    center: Option<V3>,
    axis: Option<V3>,
    turns: Option<Num>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
pub(super) struct CameraKeyDef {
    frame: Option<Spanned<Num>>,
    time: Option<Spanned<Num>>,
    eye: Option<V3>,
    look_at: Option<V3>,
    up: Option<V3>,
    fov: Option<Spanned<Num>>,
    height: Option<Spanned<Num>>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
pub(super) struct LightKeyDef {
    light: Spanned<i64>,
    frame: Option<Spanned<Num>>,
    time: Option<Spanned<Num>>,
    position: Option<V3>,
}

/// Where a key sits: its frame, and the key (`frame` or `time`) that placed
/// it and that key's offset.
#[derive(Clone, Copy)]
struct Placed {
    frame: f32,
    by: &'static str,
    at: usize,
}

impl Builder<'_> {
    /// The animation of a scene whose still camera is `camera` and whose
    /// `[[light]]` tables gave `lights`.
    pub(super) fn animation(&self, def: &Spanned<AnimationDef>, camera: &Camera, lights: &[Light]) -> Result<Animation, LoadError> {
        let a = def.get_ref();
        let frames = u32::try_from(*a.frames.get_ref())
            .ok()
            .filter(|f| (1..=MAX_FRAMES).contains(f))
            .ok_or_else(|| self.error_at(&a.frames, format!("frames: {} is outside 1..={MAX_FRAMES}", a.frames.get_ref())))?;
        let fps = match &a.fps {
            None => DEFAULT_FPS,
            Some(f) if f.get_ref().0 > 0.0 => f.get_ref().0,
            Some(f) => return Err(self.error_at(f, format!("fps: must be positive, found {}", f.get_ref().0))),
        };
        let interpolation = match &a.interpolation {
            None => Interpolation::default(),
            Some(i) if a.camera.is_empty() && a.light.is_empty() => {
                return Err(self.error_at(i, "interpolation: there are no [[animation.camera]] or [[animation.light]] keys to interpolate"));
            }
            Some(i) => match i.get_ref().as_str() {
                "linear" => Interpolation::Linear,
                "smooth" => Interpolation::Smooth,
                other => {
                    return Err(self.error_at(i, format!("interpolation: unknown interpolation `{other}`, expected `linear` or `smooth`")));
                }
            },
        };
        let timing = (frames, fps);
        let camera_track = match (&a.orbit, a.camera.is_empty()) {
            (Some(o), false) => {
                return Err(self.error_at(o, "orbit: the camera follows an orbit or [[animation.camera]] keys, not both"));
            }
            (Some(o), true) => {
                let def = o.get_ref();
                let center = def.center.ok_or_else(|| self.error_at(o, "orbit: an orbit needs the `center` it turns about"))?.0;
                let axis = crate::unit(def.axis.map_or(glam::Vec3::Y, |a| a.0))
                    .ok_or_else(|| self.error_at(o, "orbit: `axis` must not be zero"))?;
                let turns = def.turns.map_or(1.0, |t| t.0);
                Some(CameraTrack::Orbit(Orbit { start: *camera, center, axis, turns }))
            }
            (None, false) => Some(CameraTrack::Keys(self.camera_keys(&a.camera, camera, timing)?)),
            (None, true) => None,
        };
        let animation =
            Animation { frames, fps, interpolation, camera: camera_track, lights: self.light_tracks(&a.light, lights, timing)? };
        if let Some((frame, problem)) = animation.first_bad_camera() {
            // The key that starts the stretch of the track holding that frame.
            let at = match &animation.camera {
                Some(CameraTrack::Keys(keys)) => {
                    let key = keys.iter().rposition(|k| k.frame <= frame as f32).unwrap_or(0);
                    a.camera[key].span().start
                }
                _ => a.orbit.as_ref().map_or(def.span().start, |o| o.span().start),
            };
            let hint = match animation.interpolation {
                Interpolation::Smooth => " (a smooth track can overshoot its keys: add a key there, or use linear interpolation)",
                Interpolation::Linear => "",
            };
            return Err(self.error_at_offset(at, format!("animation: at frame {frame}, {problem}{hint}")));
        }
        Ok(animation)
    }

    fn camera_keys(&self, defs: &[Spanned<CameraKeyDef>], camera: &Camera, timing: (u32, f32)) -> Result<Vec<CameraKey>, LoadError> {
        let mut keys = Vec::with_capacity(defs.len());
        let mut previous = None;
        for key in defs {
            let k = key.get_ref();
            let placed = self.placed(key, &k.frame, &k.time, "animation.camera", timing)?;
            self.in_order(previous, placed, "the camera")?;
            previous = Some(placed);
            // What a key leaves out is the [camera]'s, whose projection it keeps.
            let projection = match (camera.projection, &k.fov, &k.height) {
                (Projection::Perspective { .. }, _, Some(h)) => {
                    return Err(self.error_at(h, "height: the [camera] is perspective: key its `fov`, not a view-plane height"));
                }
                (Projection::Orthographic { .. }, Some(f), _) => {
                    return Err(self.error_at(f, "fov: the [camera] is orthographic: key its view-plane `height`, not a field of view"));
                }
                (Projection::Perspective { fov_y_degrees }, fov, None) => {
                    Projection::Perspective { fov_y_degrees: fov.as_ref().map_or(Ok(fov_y_degrees), |f| self.fov(f))? }
                }
                (Projection::Orthographic { height }, None, h) => {
                    Projection::Orthographic { height: h.as_ref().map_or(Ok(height), |h| self.view_height(h))? }
                }
            };
            let or = |v: Option<V3>, base| v.map_or(base, |v| v.0);
            let camera = Camera { eye: or(k.eye, camera.eye), look_at: or(k.look_at, camera.look_at), up: or(k.up, camera.up), projection };
            keys.push(CameraKey { frame: placed.frame, camera });
        }
        Ok(keys)
    }

    /// The light keys grouped into one track per light, in light order.
    fn light_tracks(&self, defs: &[Spanned<LightKeyDef>], lights: &[Light], timing: (u32, f32)) -> Result<Vec<LightTrack>, LoadError> {
        let mut tracks: BTreeMap<usize, (Vec<PositionKey>, Placed)> = BTreeMap::new();
        for key in defs {
            let k = key.get_ref();
            let n = *k.light.get_ref();
            let light = usize::try_from(n).ok().filter(|&i| i < lights.len()).ok_or_else(|| {
                let have = match lights.len() {
                    0 => "the scene has no [[light]]".to_string(),
                    1 => "the scene has one [[light]], light 0".to_string(),
                    count => format!("the scene's {count} [[light]] tables are lights 0 to {}, in file order", count - 1),
                };
                self.error_at(&k.light, format!("light: no light {n}: {have}"))
            })?;
            if let LightKind::Directional { .. } = lights[light].kind {
                return Err(
                    self.error_at(&k.light, format!("light: light {light} is directional: only a point light's `position` is keyed"))
                );
            }
            let placed = self.placed(key, &k.frame, &k.time, "animation.light", timing)?;
            let position = k.position.ok_or_else(|| self.error_at(key, "animation.light: a key needs the light's `position`"))?.0;
            let whose = format!("light {light}");
            match tracks.get_mut(&light) {
                Some((keys, previous)) => {
                    self.in_order(Some(*previous), placed, &whose)?;
                    keys.push(PositionKey { frame: placed.frame, position });
                    *previous = placed;
                }
                None => {
                    tracks.insert(light, (vec![PositionKey { frame: placed.frame, position }], placed));
                }
            }
        }
        Ok(tracks.into_iter().map(|(light, (keys, _))| LightTrack { light, keys }).collect())
    }

    /// The frame a key is placed at, by `frame` or by `time` in seconds,
    /// inside the animation's frames.
    fn placed<T>(
        &self,
        key: &Spanned<T>,
        frame: &Option<Spanned<Num>>,
        time: &Option<Spanned<Num>>,
        table: &str,
        (frames, fps): (u32, f32),
    ) -> Result<Placed, LoadError> {
        let last = frames - 1;
        match (frame, time) {
            (Some(_), Some(t)) => Err(self.error_at(t, "time: a key is placed by `frame` or by `time`, not both")),
            (None, None) => Err(self.error_at(key, format!("{table}: a key needs `frame` (a frame number) or `time` (in seconds)"))),
            (Some(f), None) => {
                let frame = f.get_ref().0;
                if !(0.0..=last as f32).contains(&frame) {
                    return Err(self.error_at(f, format!("frame: {frame} is outside the animation's frames 0..={last}")));
                }
                Ok(Placed { frame, by: "frame", at: f.span().start })
            }
            (None, Some(t)) => {
                let seconds = t.get_ref().0;
                let frame = (f64::from(seconds) * f64::from(fps)) as f32;
                if !(0.0..=last as f32).contains(&frame) {
                    return Err(self.error_at(
                        t,
                        format!("time: {seconds} s is frame {frame} at {fps} fps, outside the animation's frames 0..={last}"),
                    ));
                }
                Ok(Placed { frame, by: "time", at: t.span().start })
            }
        }
    }

    /// Keys of one track come in increasing frame order, one per frame.
    fn in_order(&self, previous: Option<Placed>, key: Placed, whose: &str) -> Result<(), LoadError> {
        let Some(previous) = previous else { return Ok(()) };
        let line = Location::of_offset(self.source, previous.at).line;
        let problem = if key.frame == previous.frame {
            format!("a second key for {whose} at frame {} (the first is on line {line})", key.frame)
        } else if key.frame < previous.frame {
            format!("the keys for {whose} go in frame order, but frame {} follows frame {} (line {line})", key.frame, previous.frame)
        } else {
            return Ok(());
        };
        Err(self.error_at_offset(key.at, format!("{}: {problem}", key.by)))
    }
}

#[cfg(test)]
mod tests {
    use std::path::Path;

    use glam::Vec3;

    use crate::animation::{CameraTrack, Interpolation};
    use crate::{LightKind, Projection, Scene};

    /// A scene with a point light (0) and a directional light (1); what a
    /// test appends starts on line 17.
    const BASE: &str = r#"[image]
width = 32
height = 24

[camera]
eye = [0, 0, 5]
look_at = [0, 0, 0]
fov = 40

[[light]]
type = "point"
position = [0, 3, 4]

[[light]]
type = "directional"
direction = [0, -1, 0]
"#;

    fn parse(extra: &str) -> Result<Scene, String> {
        crate::toml_scene::parse(&format!("{BASE}{extra}"), Path::new("a.toml")).map_err(|e| e.to_string())
    }

    #[test]
    fn an_orbit_starts_from_the_camera() {
        let s = parse("[animation]\nframes = 48\norbit = { center = [0, 1, 0] }\n").unwrap();
        let a = s.animation.as_ref().unwrap();
        assert_eq!((a.frames, a.fps, a.interpolation), (48, 24.0, Interpolation::Linear));
        let Some(CameraTrack::Orbit(o)) = a.camera else { panic!("an orbit: {a:?}") };
        assert_eq!((o.start, o.center, o.axis, o.turns), (s.camera, Vec3::Y, Vec3::Y, 1.0));
        // The table form reads the same.
        let table = parse("[animation]\nframes = 48\n[animation.orbit]\ncenter = [0, 1, 0]\naxis = [0, 2, 0]\nturns = 1\n").unwrap();
        assert_eq!(table.animation, s.animation);
    }

    #[test]
    fn camera_keys_take_what_they_leave_out_from_the_camera() {
        let s = parse(
            r#"[animation]
frames = 50
fps = 25
interpolation = "smooth"

[[animation.camera]]
frame = 0
eye = [0, 1, 9]

[[animation.camera]]
time = 1.5
look_at = [1, 0, 0]
fov = 30
"#,
        )
        .unwrap();
        let a = s.animation.unwrap();
        assert_eq!(a.interpolation, Interpolation::Smooth);
        let Some(CameraTrack::Keys(keys)) = a.camera else { panic!("keys") };
        assert_eq!(keys.len(), 2);
        assert_eq!((keys[0].frame, keys[0].camera.eye, keys[0].camera.look_at), (0.0, Vec3::new(0.0, 1.0, 9.0), Vec3::ZERO));
        assert_eq!(keys[1].frame, 37.5, "1.5 s at 25 fps");
        assert_eq!(keys[1].camera.eye, s.camera.eye);
        assert_eq!(keys[1].camera.projection, Projection::Perspective { fov_y_degrees: 30.0 });
        assert_eq!(keys[0].camera.projection, s.camera.projection);
    }

    #[test]
    fn light_keys_make_one_track_per_light() {
        let s = parse(
            r#"[[light]]
type = "point"
position = [1, 1, 1]

[animation]
frames = 10

[[animation.light]]
light = 2
frame = 0
position = [0, 0, 0]

[[animation.light]]
light = 0
frame = 3
position = [1, 0, 0]

[[animation.light]]
light = 2
frame = 9
position = [9, 0, 0]
"#,
        )
        .unwrap();
        let tracks = &s.animation.as_ref().unwrap().lights;
        assert_eq!(tracks.iter().map(|t| (t.light, t.keys.len())).collect::<Vec<_>>(), [(0, 1), (2, 2)]);
        let mut posed = s.clone();
        posed.set_frame(3);
        assert_eq!(posed.lights[2].kind, LightKind::Point { position: Vec3::new(3.0, 0.0, 0.0) });
        assert_eq!(posed.lights[0].kind, LightKind::Point { position: Vec3::X });
        assert_eq!(posed.lights[1], s.lights[1], "a light without keys stays");
    }

    #[test]
    fn bad_animations_are_errors_where_they_are_written() {
        let key = |body: &str| format!("[animation]\nframes = 48\n\n[[animation.camera]]\n{body}\n");
        let cases: Vec<(String, &str)> = vec![
            ("[animation]\nframes = 0\n".into(), "a.toml:18:10: frames: 0 is outside 1..=100000"),
            (
                "[animation]\nframes = 24.0\n".into(),
                "a.toml:18:10: frames: expected a whole number, found 24.0 (write 24, without the decimal point)",
            ),
            ("[animation]\nframes = 4\nfps = 0\n".into(), "a.toml:19:7: fps: must be positive, found 0"),
            (
                "[animation]\nframes = 4\ninterpolation = \"smooth\"\n".into(),
                "a.toml:19:17: interpolation: there are no [[animation.camera]] or [[animation.light]] keys to interpolate",
            ),
            (
                "[animation]\nframes = 48\ninterpolation = \"cubic\"\n[[animation.camera]]\nframe = 0\n".into(),
                "a.toml:19:17: interpolation: unknown interpolation `cubic`, expected `linear` or `smooth`",
            ),
            (key("frame = 48"), "a.toml:21:9: frame: 48 is outside the animation's frames 0..=47"),
            (key("time = 2"), "a.toml:21:8: time: 2 s is frame 48 at 24 fps, outside the animation's frames 0..=47"),
            (key("frame = 1\ntime = 0"), "a.toml:22:8: time: a key is placed by `frame` or by `time`, not both"),
            (key("eye = [1, 2, 3]"), "a.toml:20:1: animation.camera: a key needs `frame` (a frame number) or `time` (in seconds)"),
            (
                key("frame = 5\n[[animation.camera]]\nframe = 2"),
                "a.toml:23:9: frame: the keys for the camera go in frame order, but frame 2 follows frame 5 (line 21)",
            ),
            (
                key("frame = 6\n[[animation.camera]]\ntime = 0.25"),
                "a.toml:23:8: time: a second key for the camera at frame 6 (the first is on line 21)",
            ),
            (key("frame = 0\nheight = 3"), "a.toml:22:10: height: the [camera] is perspective: key its `fov`, not a view-plane height"),
            (key("frame = 0\nfov = 180"), "a.toml:22:7: fov: 180 is not between 0 and 180 degrees"),
            (key("frame = 0\neyes = [0, 0, 1]"), "a.toml:22:1: unknown key `eyes` in [[animation.camera]]; did you mean `eye`?"),
            (
                key("frame = 0\nposition = [0, 0, 1]"),
                "a.toml:22:1: unknown key `position` in [[animation.camera]]: `position` belongs in [[animation.light]]",
            ),
            (
                key("frame = 0\neye = [0, 5, 0]\nlook_at = [0, 0, 0]"),
                "a.toml:20:1: animation: at frame 0, `up` is parallel to the view direction (or eye equals look_at)",
            ),
            (
                key("frame = 0\nfov = 170\n[[animation.camera]]\nframe = 10\nfov = 179\n[[animation.camera]]\nframe = 20\nfov = 10")
                    .replace("frames = 48\n", "frames = 48\ninterpolation = \"smooth\"\n"),
                "a.toml:21:1: animation: at frame 4, the fov is 180.848, not between 0 and 180 degrees (a smooth track can overshoot \
                 its keys: add a key there, or use linear interpolation)",
            ),
            (
                "[animation]\nframes = 8\norbit = { center = [0, 0, 0] }\n[[animation.camera]]\nframe = 0\n".into(),
                "a.toml:19:9: orbit: the camera follows an orbit or [[animation.camera]] keys, not both",
            ),
            (
                "[animation]\nframes = 8\norbit = { center = [0, 0, 0], axis = [0, 0, 0] }\n".into(),
                "a.toml:19:9: orbit: `axis` must not be zero",
            ),
            (
                "[animation]\nframes = 8\n[animation.orbit]\nturns = 2\n".into(),
                "a.toml:19:1: orbit: an orbit needs the `center` it turns about",
            ),
            (
                "[animation]\nframes = 8\n[animation.camera]\nframe = 0\n".into(),
                "a.toml:19:12: [animation.camera] is a single table: write [[animation.camera]] (an array of tables) for each key",
            ),
            (
                "[[animation]]\nframes = 8\n".into(),
                "a.toml:17:3: [[animation]] is an array of tables, but a scene has one animation: write [animation]",
            ),
            (
                "[animation]\nframes = 8\n[[animation.light]]\nlight = 2\nframe = 0\nposition = [0, 0, 0]\n".into(),
                "a.toml:20:9: light: no light 2: the scene's 2 [[light]] tables are lights 0 to 1, in file order",
            ),
            (
                "[animation]\nframes = 8\n[[animation.light]]\nlight = 1\nframe = 0\nposition = [0, 0, 0]\n".into(),
                "a.toml:20:9: light: light 1 is directional: only a point light's `position` is keyed",
            ),
            (
                "[animation]\nframes = 8\n[[animation.light]]\nlight = 0\nframe = 0\n".into(),
                "a.toml:19:1: animation.light: a key needs the light's `position`",
            ),
            ("frames = 8\n".into(), "a.toml:17:1: unknown key `frames` in a directional light: `frames` belongs in [animation]"),
        ];
        for (extra, want) in cases {
            let got = parse(&extra).err().unwrap_or_else(|| panic!("loaded:\n{extra}"));
            assert_eq!(got, want, "{extra}");
        }
    }

    #[test]
    fn an_orthographic_camera_keys_its_height() {
        let ortho = BASE.replace("fov = 40", "type = \"orthographic\"\nheight = 4");
        let parse = |extra: &str| crate::toml_scene::parse(&format!("{ortho}{extra}"), Path::new("o.toml")).map_err(|e| e.to_string());
        let s = parse("[animation]\nframes = 4\n[[animation.camera]]\nframe = 3\nheight = 8\n").unwrap();
        let Some(CameraTrack::Keys(keys)) = &s.animation.as_ref().unwrap().camera else { panic!("keys") };
        assert_eq!(keys[0].camera.projection, Projection::Orthographic { height: 8.0 });
        let e = parse("[animation]\nframes = 4\n[[animation.camera]]\nframe = 3\nfov = 8\n").unwrap_err();
        assert_eq!(e, "o.toml:22:7: fov: the [camera] is orthographic: key its view-plane `height`, not a field of view");
    }

    #[test]
    fn posing_depends_on_the_frame_alone() {
        let mut scene = super::super::parse(
            "[image]\nwidth = 8\nheight = 8\n[camera]\neye = [0, 0, 5]\nlook_at = [0, 0, 0]\nfov = 40\n[[light]]\ntype = \"point\"\nposition = [0, 3, 0]\n[animation]\nframes = 10\norbit = { center = [0, 0, 0] }\n[[animation.light]]\nlight = 0\nframe = 0\nposition = [1, 1, 1]\n[[animation.light]]\nlight = 0\nframe = 9\nposition = [5, 1, 1]\n",
            Path::new("a.toml"),
        )
        .unwrap();
        let mut alone = scene.clone();
        alone.set_frame(7);
        for n in [3, 9, 0, 7] {
            scene.set_frame(n);
        }
        assert_eq!(scene, alone);
        let LightKind::Point { position } = scene.lights[0].kind else { panic!("a point light") };
        assert!((position - Vec3::new(1.0 + 4.0 * 7.0 / 9.0, 1.0, 1.0)).length() < 1e-6, "{position}");
    }
}
