//! Writes a [`Scene`] as Glint TOML that [`crate::toml_scene`] reads back.
//!
//! A scene loaded from TOML (without meshes or includes) reads back equal to
//! itself; a plane with a `size` is written as the polygon it is stored as.
//! Otherwise the written file renders the same scene, with two
//! differences in its structure: every shape becomes one `[[object]]` (a mesh's
//! triangles are written one by one, so object ids count them), and materials
//! are renamed when their names would not keep their order, since the loader
//! orders named materials by name. Paths to OBJ and NFF files are not kept.
//! An `[animation]` is written with every key in full and placed by `frame`.
//!
//! Numbers are written in the shortest form that reads back to the same `f32`.

use std::fmt::Write;

use glam::Vec3;

use crate::animation::{CameraTrack, Interpolation};
use crate::toml_scene::{written_object, Written};
use crate::{Animation, Attenuation, Camera, LightKind, Material, Projection, Scene, ShadowMode, Shape, SpecularModel};

/// A value that the TOML format cannot hold.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[error("cannot write the scene: {0} is not a finite number")]
pub struct WriteError(String);

/// The scene as TOML text.
pub fn to_string(scene: &Scene) -> Result<String, WriteError> {
    let mut w = Writer::default();
    w.scene(scene)?;
    Ok(w.out)
}

#[derive(Default)]
struct Writer {
    out: String,
}

impl Writer {
    fn line(&mut self, text: impl AsRef<str>) {
        self.out.push_str(text.as_ref());
        self.out.push('\n');
    }

    fn num(&mut self, key: &str, v: f32, what: &str) -> Result<(), WriteError> {
        let n = number(v, what)?;
        self.line(format!("{key} = {n}"));
        Ok(())
    }

    fn vec(&mut self, key: &str, v: Vec3, what: &str) -> Result<(), WriteError> {
        let t = vector(v, what)?;
        self.line(format!("{key} = {t}"));
        Ok(())
    }

    fn scene(&mut self, s: &Scene) -> Result<(), WriteError> {
        self.line("# Written by glint.");
        self.line("");
        self.line("[image]");
        self.line(format!("width = {}", s.width));
        self.line(format!("height = {}", s.height));
        self.vec("background", s.background, "the background")?;

        self.line("");
        self.line("[camera]");
        let c = &written_camera(s);
        match c.projection {
            Projection::Perspective { fov_y_degrees } => {
                self.line("type = \"perspective\"");
                self.num("fov", fov_y_degrees, "the camera's fov")?;
            }
            Projection::Orthographic { height } => {
                self.line("type = \"orthographic\"");
                self.num("height", height, "the camera's height")?;
            }
        }
        self.vec("eye", c.eye, "the camera's eye")?;
        self.vec("look_at", c.look_at, "the camera's look_at")?;
        self.vec("up", c.up, "the camera's up")?;

        self.line("");
        self.line("[ambient]");
        self.vec("color", s.ambient, "the ambient colour")?;

        let r = &s.render;
        self.line("");
        self.line("[render]");
        self.line(format!("max_depth = {}", r.max_depth));
        self.num("cutoff", r.cutoff, "the cutoff")?;
        self.line(format!("shadows = {}", r.shadows));
        let mode = match r.shadow_mode {
            ShadowMode::Opaque => "opaque",
            ShadowMode::Tinted => "tinted",
        };
        self.line(format!("shadow_mode = \"{mode}\""));
        self.line(format!("reflections = {}", r.reflections));
        self.line(format!("refractions = {}", r.refractions));

        if let Some(d) = &s.depth_cue {
            self.line("");
            self.line("[depth_cue]");
            self.vec("color", d.color, "the depth cue colour")?;
            self.num("near", d.near, "the depth cue's near")?;
            self.num("far", d.far, "the depth cue's far")?;
            self.num("near_scale", d.near_scale, "the depth cue's near_scale")?;
            self.num("far_scale", d.far_scale, "the depth cue's far_scale")?;
        }

        for (i, l) in s.lights.iter().enumerate() {
            let what = |field: &str| format!("light {}'s {field}", i + 1);
            self.line("");
            self.line("[[light]]");
            match l.kind {
                LightKind::Point { position } => {
                    self.line("type = \"point\"");
                    self.vec("position", position, &what("position"))?;
                }
                LightKind::Directional { direction } => {
                    self.line("type = \"directional\"");
                    self.vec("direction", direction, &what("direction"))?;
                }
            }
            self.vec("color", l.color, &what("colour"))?;
            self.num("intensity", l.intensity, &what("intensity"))?;
            // Only point lights attenuate: a directional light has no distance.
            let attenuation = if matches!(l.kind, LightKind::Point { .. }) { l.attenuation } else { Attenuation::None };
            match attenuation {
                Attenuation::None => {}
                Attenuation::InverseSquare => self.line("attenuation = \"inverse_square\""),
                Attenuation::Polynomial { c1, c2, c3 } => {
                    self.line("attenuation = \"polynomial\"");
                    self.vec("coefficients", Vec3::new(c1, c2, c3), &what("coefficients"))?;
                }
            }
            if !l.enabled {
                self.line("enabled = false");
            }
        }

        let names = material_names(&s.materials);
        for (m, name) in s.materials.iter().zip(&names) {
            if let Some(name) = name {
                self.material(m, name)?;
            }
        }

        for (i, o) in s.objects.iter().enumerate() {
            for shape in &o.shapes {
                self.line("");
                self.line("[[object]]");
                self.shape(shape, &format!("object {}", i + 1))?;
                if let Some(name) = &names[o.material] {
                    self.line(format!("material = {}", quoted(name)));
                }
            }
        }
        if let Some(a) = &s.animation {
            self.animation(a)?;
        }
        Ok(())
    }

    fn animation(&mut self, a: &Animation) -> Result<(), WriteError> {
        self.line("");
        self.line("[animation]");
        self.line(format!("frames = {}", a.frames));
        self.num("fps", a.fps, "the animation's fps")?;
        let keyed = matches!(a.camera, Some(CameraTrack::Keys(_))) || !a.lights.is_empty();
        if keyed {
            let interpolation = match a.interpolation {
                Interpolation::Linear => "linear",
                Interpolation::Smooth => "smooth",
            };
            self.line(format!("interpolation = \"{interpolation}\""));
        }
        match &a.camera {
            None => {}
            Some(CameraTrack::Orbit(o)) => {
                let what = "the orbit";
                let (center, axis, turns) = (vector(o.center, what)?, vector(o.axis, what)?, number(o.turns, what)?);
                self.line(format!("orbit = {{ center = {center}, axis = {axis}, turns = {turns} }}"));
            }
            Some(CameraTrack::Keys(keys)) => {
                for (i, k) in keys.iter().enumerate() {
                    let what = format!("camera key {}", i + 1);
                    self.line("");
                    self.line("[[animation.camera]]");
                    self.num("frame", k.frame, &what)?;
                    self.vec("eye", k.camera.eye, &what)?;
                    self.vec("look_at", k.camera.look_at, &what)?;
                    self.vec("up", k.camera.up, &what)?;
                    match k.camera.projection {
                        Projection::Perspective { fov_y_degrees } => self.num("fov", fov_y_degrees, &what)?,
                        Projection::Orthographic { height } => self.num("height", height, &what)?,
                    }
                }
            }
        }
        for track in &a.lights {
            for k in &track.keys {
                let what = format!("light {}'s key", track.light);
                self.line("");
                self.line("[[animation.light]]");
                self.line(format!("light = {}", track.light));
                self.num("frame", k.frame, &what)?;
                self.vec("position", k.position, &what)?;
            }
        }
        Ok(())
    }

    fn material(&mut self, m: &Material, name: &str) -> Result<(), WriteError> {
        let what = |field: &str| format!("material `{name}`'s {field}");
        self.line("");
        self.line(format!("[material.{}]", key(name)));
        self.vec("color", m.color, &what("colour"))?;
        self.num("ka", m.ambient, &what("ka"))?;
        self.num("kd", m.diffuse, &what("kd"))?;
        self.num("ks", m.specular, &what("ks"))?;
        self.num("shininess", m.shininess, &what("shininess"))?;
        if let Some(c) = m.specular_color {
            self.vec("specular_color", c, &what("specular colour"))?;
        }
        let model = match m.specular_model {
            SpecularModel::Phong => "phong",
            SpecularModel::BlinnPhong => "blinn",
        };
        self.line(format!("model = \"{model}\""));
        if let Some(f0) = m.metallic_f0 {
            self.vec("metallic", f0, &what("metallic F0"))?;
        }
        self.vec("reflect", m.reflect, &what("reflect"))?;
        self.vec("transmit", m.transmit, &what("transmit"))?;
        self.num("ior", m.ior, &what("ior"))?;
        self.line(format!("fresnel = {}", m.fresnel));
        if let Some(c) = m.checker {
            let (color, size) = (vector(c.color, &what("checker colour"))?, number(c.size, &what("checker size"))?);
            self.line(format!("checker = {{ color = {color}, size = {size} }}"));
        }
        Ok(())
    }

    fn shape(&mut self, shape: &Shape, what: &str) -> Result<(), WriteError> {
        let (kind, values) = written_object(shape);
        self.line(format!("type = \"{kind}\""));
        for (key, value) in values {
            match value {
                Written::Number(v) => self.num(key, v, what)?,
                Written::Point(v) => self.vec(key, v, what)?,
                Written::Points(vs) => self.line(format!("{key} = {}", vectors(vs, what)?)),
            }
        }
        Ok(())
    }
}

/// The `[camera]` to write. An orbit turns its own start camera, which the
/// reader takes from `[camera]`; camera keys need a `[camera]` of their
/// projection. Otherwise the scene's camera, as it was posed or edited.
fn written_camera(s: &Scene) -> Camera {
    let kind = std::mem::discriminant::<Projection>;
    match s.animation.as_ref().and_then(|a| a.camera.as_ref()) {
        Some(CameraTrack::Orbit(o)) => o.start,
        Some(CameraTrack::Keys(keys)) => match keys.first() {
            Some(k) if kind(&k.camera.projection) != kind(&s.camera.projection) => Camera { projection: k.camera.projection, ..s.camera },
            _ => s.camera,
        },
        None => s.camera,
    }
}

/// The name each material is written under; `None` for the loader's implicit
/// default material (index 0, when unchanged), which objects use by naming none.
///
/// The loader numbers named materials in name order after the default, so the
/// names are kept only when they are unique and already in that order; else
/// every material gets a numbered name that sorts in index order.
fn material_names(materials: &[Material]) -> Vec<Option<String>> {
    let default_kept = materials.first().is_some_and(|m| *m == Material::default());
    let named = if default_kept { &materials[1..] } else { materials };
    let in_order = named.windows(2).all(|p| p[0].name < p[1].name);
    let mut names: Vec<Option<String>> = if in_order {
        named.iter().map(|m| Some(m.name.clone())).collect()
    } else {
        let digits = named.len().to_string().len();
        named.iter().enumerate().map(|(i, m)| Some(format!("m{i:0digits$}_{}", m.name))).collect()
    };
    if default_kept {
        names.insert(0, None);
    }
    names
}

/// `v` in the shortest text that reads back (as f64, then f32) to exactly `v`.
fn number(v: f32, what: &str) -> Result<String, WriteError> {
    if !v.is_finite() {
        return Err(WriteError(what.to_string()));
    }
    // Debug keeps a ".0" on whole numbers and uses an exponent for very large
    // or small ones, both valid TOML floats. Reading goes through f64, and
    // rounding twice can land on a neighbour of `v`: then the f64 form is exact.
    let short = format!("{v:?}");
    Ok(if short.parse::<f64>().map(|d| d as f32) == Ok(v) { short } else { format!("{:?}", f64::from(v)) })
}

fn vector(v: Vec3, what: &str) -> Result<String, WriteError> {
    Ok(format!("[{}, {}, {}]", number(v.x, what)?, number(v.y, what)?, number(v.z, what)?))
}

fn vectors(vs: &[Vec3], what: &str) -> Result<String, WriteError> {
    let items: Vec<String> = vs.iter().map(|v| vector(*v, what)).collect::<Result<_, _>>()?;
    Ok(format!("[{}]", items.join(", ")))
}

/// A TOML basic string.
fn quoted(s: &str) -> String {
    let mut out = String::from("\"");
    for c in s.chars() {
        match c {
            '"' => out.push_str("\\\""),
            '\\' => out.push_str("\\\\"),
            c if c.is_control() => {
                let _ = write!(out, "\\u{:04X}", c as u32);
            }
            c => out.push(c),
        }
    }
    out.push('"');
    out
}

/// A TOML key: bare when it can be, quoted otherwise.
fn key(s: &str) -> String {
    if !s.is_empty() && s.chars().all(|c| c.is_ascii_alphanumeric() || c == '_' || c == '-') {
        s.to_string()
    } else {
        quoted(s)
    }
}

#[cfg(test)]
mod tests {
    use std::path::Path;

    use super::*;
    use crate::toml_scene::parse;

    fn round_trip(scene: &Scene) -> Scene {
        let text = to_string(scene).unwrap();
        parse(&text, Path::new("written.toml")).unwrap_or_else(|e| panic!("{e}\n{text}"))
    }

    const EVERYTHING: &str = r#"
[image]
width = 320
height = 200
background = [0.1, 0.2, 0.3]

[camera]
type = "orthographic"
eye = [1.5, 2.25, 7]
look_at = [0, 0.7, 0]
up = [0, 1, 0.1]
height = 6.5

[ambient]
color = [1, 0.9, 0.8]
intensity = 0.3

[render]
max_depth = 9
cutoff = 0.001
shadows = false
shadow_mode = "tinted"
reflections = true
refractions = false

[depth_cue]
color = [0.5, 0.6, 0.7]
near = 2
far = 40.5
near_scale = 0.9
far_scale = 0.1

[[light]]
type = "point"
position = [-5, 7, 6]
color = [1.0, 0.92, 0.8]
intensity = 0.9
attenuation = "inverse_square"

[[light]]
type = "directional"
direction = [0, -1, 0]
intensity = 0.4
enabled = false

[[light]]
type = "point"
position = [3, 3, 3]
attenuation = "polynomial"
coefficients = [1, 0.1, 0.01]

[material.glass]
color = [0.05, 0.05, 0.05]
ka = 0
kd = 0.05
ks = 0.9
shininess = 300
reflect = 0.05
transmit = [0.85, 0.92, 0.95]
ior = 1.5
fresnel = true

[material.gold]
color = [0.75, 0.55, 0.15]
specular_color = [1, 0.9, 0.5]
metallic = [1.0, 0.78, 0.34]
model = "phong"
checker = { color = [0.2, 0.1, 0.05], size = 0.75 }

[material."odd \"name\""]
color = 0.3

[[object]]
type = "sphere"
center = [-1.4, 1.0, 0]
radius = 1.0
material = "glass"

[[object]]
type = "triangle"
vertices = [[0, 0, 0], [1, 0, 0], [0, 1, 0]]
normals = [[0, 0, 1], [0.6, 0, 0.8], [0, 0.6, 0.8]]
material = "gold"

[[object]]
type = "polygon"
vertices = [[-9, 0, -9], [9, 0, -9], [9, 0, 9], [-9, 0, 9]]

[[object]]
type = "cylinder"
base = [2.6, 0, -1.0]
apex = [2.6, 1.4, -1.0]
base_radius = 0.35
material = "odd \"name\""

[[object]]
type = "cone"
base = [-3.0, 0, -2.0]
base_radius = 0.6
apex = [-3.0, 1.6, -2.0]
apex_radius = 0.0

[[object]]
type = "plane"
point = [0, -1, 0.5]
normal = [1, 2, 3]
material = "gold"

[[object]]
type = "plane"
point = [0, 2, -5]
normal = [0, 0.6, 0.8]
size = [4, 2.5]
"#;

    #[test]
    fn every_feature_round_trips() {
        let scene = parse(EVERYTHING, Path::new("everything.toml")).unwrap();
        assert_eq!(round_trip(&scene), scene);
    }

    const ORBIT: &str = "\n[animation]\nframes = 36\nfps = 30\norbit = { center = [0, 1, 0], axis = [0, 1, 0.5], turns = -0.5 }\n";

    const KEYS: &str = r#"
[animation]
frames = 20
interpolation = "smooth"

[[animation.camera]]
time = 0.125
height = 5

[[animation.camera]]
frame = 7.5
eye = [4, 2, 6]
up = [0.1, 1, 0]

[[animation.light]]
light = 2
frame = 0
position = [1, 2, 3]

[[animation.light]]
light = 0
frame = 19
position = [-1, 2, 3]

[[animation.light]]
light = 2
frame = 10
position = [3, 2, 1]
"#;

    #[test]
    fn animations_round_trip_also_when_posed() {
        for animation in [ORBIT, KEYS] {
            let scene = parse(&format!("{EVERYTHING}{animation}"), Path::new("animated.toml")).unwrap();
            assert_eq!(round_trip(&scene), scene);
            // A scene posed at a frame is written with the animation it moves by.
            let mut posed = scene.clone();
            posed.set_frame(13);
            let back = round_trip(&posed);
            assert_eq!(back.animation, scene.animation);
            let mut again = back.clone();
            again.set_frame(13);
            assert_eq!((again.camera, &again.lights), (posed.camera, &posed.lights));
        }
    }

    #[test]
    fn the_showcase_round_trips() {
        let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../scenes/showcase.toml");
        let scene = crate::load(&path).unwrap();
        assert_eq!(round_trip(&scene), scene);
    }

    #[test]
    fn a_perspective_camera_round_trips() {
        let text = EVERYTHING.replace("type = \"orthographic\"", "type = \"perspective\"").replace("height = 6.5", "fov = 38.5");
        let scene = parse(&text, Path::new("p.toml")).unwrap();
        assert_eq!(round_trip(&scene).camera, scene.camera);
    }

    #[test]
    fn numbers_read_back_exactly() {
        for v in [0.1f32, 1.0 / 3.0, 1e-30, 3.4e38, -0.0, 16777217.0, f32::MIN_POSITIVE, 0.85] {
            let text = number(v, "v").unwrap();
            let back = text.parse::<f64>().unwrap() as f32;
            assert_eq!(back.to_bits(), v.to_bits(), "{v} → {text}");
        }
        assert_eq!(number(0.85, "v").unwrap(), "0.85");
        assert!(number(f32::NAN, "light 1's intensity").unwrap_err().to_string().contains("light 1's intensity"));
    }

    /// An edited default material and names out of order still give the same
    /// material on every object.
    #[test]
    fn edited_and_unordered_materials_keep_each_object_s_material() {
        let mut scene = parse(EVERYTHING, Path::new("everything.toml")).unwrap();
        scene.materials[0].color = Vec3::new(0.9, 0.1, 0.1);
        scene.materials.swap(1, 2);
        for o in &mut scene.objects {
            o.material = match o.material {
                1 => 2,
                2 => 1,
                m => m,
            };
        }
        let back = round_trip(&scene);
        assert_eq!(back.objects.len(), scene.objects.len());
        for (a, b) in scene.objects.iter().zip(&back.objects) {
            let (ma, mb) = (&scene.materials[a.material], &back.materials[b.material]);
            assert_eq!(Material { name: String::new(), ..ma.clone() }, Material { name: String::new(), ..mb.clone() });
            assert_eq!(a.shapes, b.shapes);
        }
    }

    #[test]
    fn mesh_objects_are_written_shape_by_shape() {
        let mut scene = parse(EVERYTHING, Path::new("everything.toml")).unwrap();
        let extra = scene.objects[1].shapes[0].clone();
        scene.objects[1].shapes.push(extra);
        let back = round_trip(&scene);
        assert_eq!(back.objects.len(), scene.objects.len() + 1);
        assert_eq!(back.primitive_count(), scene.primitive_count());
    }
}
