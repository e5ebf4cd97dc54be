//! Glint's native scene format: TOML, documented in docs/scene-format.md.
//!
//! Every table is a plain struct with `deny_unknown_fields` (no serde enums, which
//! would buffer the input and lose positions), numbers go through newtypes that
//! reject NaN and infinity while the parser still knows where they are, and
//! checks that need the whole table report the table's own line.
//!
//! Two kinds of entries bring in other files, named relative to the scene file:
//!
//! * an object of `type = "mesh"` with `path = "model.obj"` places an OBJ mesh
//!   (its MTL materials, unless `material = "name"` overrides them all) with an
//!   optional transform: `scale = s` or `[sx, sy, sz]`, `rotate = [rx, ry, rz]`
//!   (degrees, about X, then Y, then Z), `translate = [x, y, z]`, applied in that
//!   order; or instead `matrix = [[..4..], [..], [..], [..]]`, a row-major affine
//!   4×4 matrix (last row `[0, 0, 0, 1]`) acting on column vectors. Normals
//!   transform by the inverse transpose. An OBJ named by several objects is read
//!   once and copied, transformed, into each; each OBJ part becomes one object.
//! * `[[include]]` with `path = "part.nff"` (or `spd:NAME[:SIZE]`) merges an NFF file's objects, lights
//!   and materials (after the TOML file's own objects, in include order); its
//!   `v` block (optional in an included file) and background are ignored, the
//!   TOML file's camera and image apply. Its lights keep their NFF intensity
//!   1/√n, n counting the lights of that NFF file.
//!
//! An error in the reference (a missing file, a bad transform) names the TOML
//! line; an error inside the OBJ, MTL or NFF file names that file.

use std::cell::RefCell;
use std::collections::{BTreeMap, HashMap};
use std::fmt;
use std::path::{Path, PathBuf};

use glam::{DMat3, DMat4, DVec3, Vec3};
use serde::de::{self, Deserializer, Visitor};
use serde::Deserialize;
use toml::Spanned;

use crate::scene::MAX_DEPTH_LIMIT;
use crate::icosphere;
use crate::spd;
use crate::shape::{polygon_non_planarity, polygon_normal};
use crate::{nff, obj, toml_errors, ReadError};
use crate::{
    Attenuation, Camera, DepthCue, Light, LightKind, LoadError, Location, Material, Object,
    Projection, RenderSettings, Scene, ShadowMode, Shape, SpecularModel,
};

/// The largest image side Glint accepts.
pub const MAX_IMAGE_SIDE: u32 = 16384;

pub fn load(path: &Path) -> Result<Scene, LoadError> {
    let source = crate::read_text(path).map_err(|e| match e {
        ReadError::Io(e) => LoadError::new(path, None, format!("cannot read scene file: {e}")),
        ReadError::NotText(e) => e,
    })?;
    parse(&source, path)
}

/// Parses TOML scene text; `path` names the file in errors.
pub fn parse(source: &str, path: &Path) -> Result<Scene, LoadError> {
    let file: FileDef = toml::from_str(source).map_err(|e| toml_errors::explain(source, path, &e, &SCHEMA))?;
    Builder { source, path, warnings: RefCell::new(Vec::new()) }.build(file)
}

/// The tables and keys of the format, for errors about unknown keys.
const SCHEMA: toml_errors::Schema = toml_errors::Schema { fields: schema_fields, object_keys };

fn schema_fields(path: &[&str]) -> Option<&'static [&'static str]> {
    use toml_errors::fields_of;
    Some(match path {
        [] => fields_of::<FileDef>(),
        ["image"] => fields_of::<ImageDef>(),
        ["camera"] => fields_of::<CameraDef>(),
        ["ambient"] => fields_of::<AmbientDef>(),
        ["render"] => fields_of::<RenderDef>(),
        ["depth_cue"] => fields_of::<DepthCueDef>(),
        ["light"] => fields_of::<LightDef>(),
        ["material", _] => fields_of::<MaterialDef>(),
        ["object"] => fields_of::<ObjectDef>(),
        ["include"] => fields_of::<IncludeDef>(),
        _ => return None,
    })
}

/// The keys an object of type `kind` takes besides `type` and `material`.
fn object_keys(kind: &str) -> Option<&'static [&'static str]> {
    Some(match kind {
        "sphere" => &["center", "radius"],
        "triangle" => &["vertices", "normals"],
        "polygon" => &["vertices"],
        "cone" | "cylinder" => &["base", "base_radius", "apex", "apex_radius"],
        "mesh" => &["path", "translate", "rotate", "scale", "matrix"],
        "icosphere" => &["center", "radius", "subdivisions", "displacement"],
        _ => return None,
    })
}

/// A field of view of at most π "degrees" was probably written in radians.
pub(crate) fn radians_warning(key: &str, degrees: f32) -> Option<String> {
    (degrees > 0.0 && degrees <= std::f32::consts::PI).then(|| {
        format!("{key}: {degrees}° is a very narrow view; angles are in degrees ({degrees} radians is {:.1})", degrees.to_degrees())
    })
}

/// A warning for a colour with a component above 1. `reflectance`: a colour
/// that must lie in [0, 1] (a material's); otherwise light, which may be
/// brighter than 1 and is warned about only when it looks like 0–255 values.
fn colour_warning(key: &str, c: Vec3, reflectance: bool) -> Option<String> {
    if c.max_element() <= 1.0 {
        return None;
    }
    let whole = c.to_array().iter().all(|v| v.fract() == 0.0 && *v <= 255.0);
    if !reflectance && !whole {
        return None;
    }
    let short = |v: f32| {
        let s = format!("{:.2}", (v * 100.0).round() / 100.0);
        s.trim_end_matches('0').trim_end_matches('.').to_string()
    };
    let shown = |c: Vec3| {
        if c.x == c.y && c.y == c.z {
            short(c.x)
        } else {
            format!("[{}, {}, {}]", short(c.x), short(c.y), short(c.z))
        }
    };
    let brightness = if reflectance { "" } else { " (set the brightness with `intensity`)" };
    Some(if whole {
        format!("{key}: {} looks like 0–255 values, but colours are 0 to 1{brightness}; did you mean {}?", shown(c), shown(c / 255.0))
    } else {
        format!("{key}: {} is above 1, but a material's colours are 0 to 1: it would reflect more light than arrives", shown(c))
    })
}

/// A finite number.
#[derive(Debug, Clone, Copy)]
struct Num(f32);

/// Three finite numbers.
#[derive(Debug, Clone, Copy)]
struct V3(Vec3);

/// A scale: one finite number for all axes, or three.
#[derive(Debug, Clone, Copy)]
struct Scale(Vec3);

/// A colour: three finite non-negative numbers, or one number for a grey.
#[derive(Debug, Clone, Copy)]
struct Rgb(Vec3);

fn finite<E: de::Error>(v: f64) -> Result<f32, E> {
    let f = v as f32;
    if f.is_finite() {
        Ok(f)
    } else if v.is_finite() {
        Err(E::custom(format!("expected a finite number, found {v:e} (beyond the range of 32-bit floats)")))
    } else {
        Err(E::custom(format!("expected a finite number, found {v}")))
    }
}

/// Exactly `N` values: serde's fixed-size arrays would silently drop extra
/// elements (`[0, 0, 0, 1]` read as a point).
fn exactly<'de, D: Deserializer<'de>, T: Deserialize<'de>, const N: usize>(d: D, what: &str) -> Result<[T; N], D::Error> {
    let values = Vec::<T>::deserialize(d)?;
    let found = values.len();
    values.try_into().map_err(|_| de::Error::custom(format!("invalid length {found}, expected {what}")))
}

/// A row-major 4×4 matrix of finite numbers.
#[derive(Debug, Clone, Copy)]
struct Matrix([[f32; 4]; 4]);

impl<'de> Deserialize<'de> for Matrix {
    fn deserialize<D: Deserializer<'de>>(d: D) -> Result<Self, D::Error> {
        let rows: [Vec<f64>; 4] = exactly(d, "4 rows of 4 numbers")?;
        let mut m = [[0.0f32; 4]; 4];
        for (row, values) in m.iter_mut().zip(rows) {
            if values.len() != 4 {
                return Err(de::Error::custom(format!("invalid row length {}, expected 4 rows of 4 numbers", values.len())));
            }
            for (slot, v) in row.iter_mut().zip(values) {
                *slot = finite(v)?;
            }
        }
        Ok(Matrix(m))
    }
}

impl<'de> Deserialize<'de> for Num {
    fn deserialize<D: Deserializer<'de>>(d: D) -> Result<Self, D::Error> {
        finite(f64::deserialize(d)?).map(Num)
    }
}

impl<'de> Deserialize<'de> for V3 {
    fn deserialize<D: Deserializer<'de>>(d: D) -> Result<Self, D::Error> {
        let [x, y, z]: [f64; 3] = exactly(d, "an array of 3 numbers")?;
        Ok(V3(Vec3::new(finite(x)?, finite(y)?, finite(z)?)))
    }
}

/// Reads one number (for all three components) or three numbers, all finite.
struct SplatOrTriple(&'static str);

impl<'de> Visitor<'de> for SplatOrTriple {
    type Value = Vec3;
    fn expecting(&self, f: &mut fmt::Formatter) -> fmt::Result {
        f.write_str(self.0)
    }
    fn visit_f64<E: de::Error>(self, v: f64) -> Result<Vec3, E> {
        Ok(Vec3::splat(finite(v)?))
    }
    fn visit_i64<E: de::Error>(self, v: i64) -> Result<Vec3, E> {
        self.visit_f64(v as f64)
    }
    fn visit_seq<A: de::SeqAccess<'de>>(self, mut seq: A) -> Result<Vec3, A::Error> {
        let mut c = [0.0f32; 3];
        for (i, slot) in c.iter_mut().enumerate() {
            let v: f64 = seq.next_element()?.ok_or_else(|| de::Error::invalid_length(i, &self))?;
            *slot = finite(v)?;
        }
        if seq.next_element::<de::IgnoredAny>()?.is_some() {
            return Err(de::Error::invalid_length(4, &self));
        }
        Ok(Vec3::from(c))
    }
}

impl<'de> Deserialize<'de> for Scale {
    fn deserialize<D: Deserializer<'de>>(d: D) -> Result<Self, D::Error> {
        d.deserialize_any(SplatOrTriple("a scale: a number or [sx, sy, sz]")).map(Scale)
    }
}

impl<'de> Deserialize<'de> for Rgb {
    fn deserialize<D: Deserializer<'de>>(d: D) -> Result<Self, D::Error> {
        let c = d.deserialize_any(SplatOrTriple("a colour: [r, g, b] or a single number"))?;
        if c.min_element() < 0.0 {
            return Err(de::Error::custom("colour components must not be negative"));
        }
        Ok(Rgb(c))
    }
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct FileDef {
    image: Spanned<ImageDef>,
    camera: Spanned<CameraDef>,
    ambient: Option<AmbientDef>,
    render: Option<Spanned<RenderDef>>,
    depth_cue: Option<Spanned<DepthCueDef>>,
    #[serde(default)]
    light: Vec<Spanned<LightDef>>,
    #[serde(default)]
    material: BTreeMap<String, Spanned<MaterialDef>>,
    #[serde(default)]
    object: Vec<Spanned<ObjectDef>>,
    #[serde(default)]
    include: Vec<Spanned<IncludeDef>>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct IncludeDef {
    path: Spanned<String>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct ImageDef {
    width: Spanned<i64>,
    height: Spanned<i64>,
    background: Option<Spanned<Rgb>>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct CameraDef {
    #[serde(rename = "type")]
    kind: Option<Spanned<String>>,
    eye: V3,
    look_at: V3,
    up: Option<V3>,
    fov: Option<Spanned<Num>>,
    height: Option<Spanned<Num>>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct AmbientDef {
    color: Option<Spanned<Rgb>>,
    intensity: Option<Spanned<Num>>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct RenderDef {
    max_depth: Option<Spanned<i64>>,
    cutoff: Option<Spanned<Num>>,
    shadows: Option<bool>,
    shadow_mode: Option<Spanned<String>>,
    reflections: Option<bool>,
    refractions: Option<bool>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct DepthCueDef {
    color: Spanned<Rgb>,
    near: Num,
    far: Num,
    near_scale: Option<Spanned<Num>>,
    far_scale: Spanned<Num>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct LightDef {
    #[serde(rename = "type")]
    kind: Spanned<String>,
    position: Option<V3>,
    direction: Option<V3>,
    color: Option<Spanned<Rgb>>,
    intensity: Option<Spanned<Num>>,
    attenuation: Option<Spanned<String>>,
    coefficients: Option<Spanned<V3>>,
    enabled: Option<bool>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct MaterialDef {
    color: Spanned<Rgb>,
    ka: Option<Spanned<Num>>,
    kd: Option<Spanned<Num>>,
    ks: Option<Spanned<Num>>,
    shininess: Option<Spanned<Num>>,
    specular_color: Option<Spanned<Rgb>>,
    model: Option<Spanned<String>>,
    metallic: Option<Spanned<Rgb>>,
    reflect: Option<Spanned<Rgb>>,
    transmit: Option<Spanned<Rgb>>,
    ior: Option<Spanned<Num>>,
    fresnel: Option<bool>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct ObjectDef {
    #[serde(rename = "type")]
    kind: Spanned<String>,
    material: Option<Spanned<String>>,
    center: Option<V3>,
    radius: Option<Spanned<Num>>,
    vertices: Option<Spanned<Vec<V3>>>,
    normals: Option<Spanned<Vec<V3>>>,
    base: Option<V3>,
    base_radius: Option<Spanned<Num>>,
    apex: Option<V3>,
    apex_radius: Option<Spanned<Num>>,
    path: Option<Spanned<String>>,
    translate: Option<V3>,
    rotate: Option<V3>,
    scale: Option<Spanned<Scale>>,
    matrix: Option<Spanned<Matrix>>,
    subdivisions: Option<Spanned<i64>>,
    displacement: Option<Spanned<Num>>,
}

/// The OBJ files read so far, by canonical path.
#[derive(Default)]
struct Meshes {
    cache: HashMap<PathBuf, CachedMesh>,
    warnings: Vec<LoadError>,
}

struct CachedMesh {
    mesh: obj::Mesh,
    /// Where the mesh's MTL materials start in the scene's materials, once an
    /// instance without a material override has added them.
    material_offset: Option<usize>,
}

struct Builder<'a> {
    source: &'a str,
    path: &'a Path,
    /// Problems in this file that do not stop loading, with their offsets.
    warnings: RefCell<Vec<(usize, LoadError)>>,
}

impl Builder<'_> {
    fn error_at<T>(&self, spanned: &Spanned<T>, message: impl Into<String>) -> LoadError {
        LoadError::new(self.path, Some(Location::of_offset(self.source, spanned.span().start)), message)
    }

    fn warn_at<T>(&self, spanned: &Spanned<T>, message: impl Into<String>) {
        self.warnings.borrow_mut().push((spanned.span().start, self.error_at(spanned, message)));
    }

    /// A colour's value, with a warning when it is out of its usual range
    /// (see [`colour_warning`]).
    fn colour(&self, c: &Spanned<Rgb>, key: &str, reflectance: bool) -> Vec3 {
        let value = c.get_ref().0;
        if let Some(warning) = colour_warning(key, value, reflectance) {
            self.warn_at(c, warning);
        }
        value
    }

    fn optional_colour(&self, c: &Option<Spanned<Rgb>>, key: &str, reflectance: bool) -> Option<Vec3> {
        c.as_ref().map(|c| self.colour(c, key, reflectance))
    }

    /// A number that must lie in `range`, reported at its own position.
    fn ranged(&self, v: &Option<Spanned<Num>>, key: &str, default: f32, lo: f32, hi: f32) -> Result<f32, LoadError> {
        match v {
            None => Ok(default),
            Some(s) if (lo..=hi).contains(&s.get_ref().0) => Ok(s.get_ref().0),
            Some(s) => Err(self.error_at(s, format!("{key}: {} is outside {lo}..={hi}", s.get_ref().0))),
        }
    }

    fn build(&self, file: FileDef) -> Result<Scene, LoadError> {
        let (width, height, background) = self.image(&file.image)?;
        let camera = self.camera(&file.camera)?;
        let ambient = match &file.ambient {
            None => Vec3::ZERO,
            Some(a) => {
                let ambient = self.optional_colour(&a.color, "color", false).unwrap_or(Vec3::ONE) * self.ranged(&a.intensity, "intensity", 1.0, 0.0, f32::MAX)?;
                self.no_overflow(&a.intensity, ambient)?
            }
        };
        let render = match &file.render {
            None => RenderSettings::default(),
            Some(r) => self.render(r.get_ref())?,
        };
        let depth_cue = file.depth_cue.as_ref().map(|d| self.depth_cue(d)).transpose()?;
        let mut lights: Vec<Light> = file.light.iter().map(|l| self.light(l)).collect::<Result<_, _>>()?;

        let mut materials = vec![Material::default()];
        let mut names = BTreeMap::new();
        for (name, def) in &file.material {
            names.insert(name.as_str(), materials.len());
            materials.push(self.material(name, def.get_ref())?);
        }
        let mut meshes = Meshes::default();
        let mut objects = Vec::with_capacity(file.object.len());
        for o in &file.object {
            self.object(o, &names, &mut materials, &mut meshes, &mut objects)?;
        }
        // This file's own warnings in file order, then those of the files it names.
        let mut warnings: Vec<(usize, LoadError)> = self.warnings.take();
        warnings.sort_by_key(|(offset, _)| *offset);
        let mut warnings: Vec<LoadError> = warnings.into_iter().map(|(_, w)| w).chain(meshes.warnings).collect();
        for include in &file.include {
            self.include(include, &mut materials, &mut objects, &mut lights, &mut warnings)?;
        }

        Ok(Scene { width, height, background, camera, ambient, lights, materials, objects, depth_cue, render, warnings })
    }

    /// The text of a file the scene names at `rel`: a file that cannot be read
    /// is an error at the reference, one that is not text an error in that file.
    fn read_referenced(&self, rel: &Spanned<String>, path: &Path) -> Result<String, LoadError> {
        crate::read_text(path).map_err(|e| match e {
            ReadError::Io(e) => self.error_at(rel, format!("path: cannot read `{}`: {e}", path.display())),
            ReadError::NotText(e) => e,
        })
    }

    /// A path written in the scene file, relative to the scene file.
    fn relative(&self, path: &str) -> PathBuf {
        self.path.parent().map_or_else(|| PathBuf::from(path), |dir| dir.join(path))
    }

    fn include(
        &self,
        include: &Spanned<IncludeDef>,
        materials: &mut Vec<Material>,
        objects: &mut Vec<Object>,
        lights: &mut Vec<Light>,
        warnings: &mut Vec<LoadError>,
    ) -> Result<(), LoadError> {
        let rel = &include.get_ref().path;
        let (source, path) = if let Some(spec) = spd::spec_of(Path::new(rel.get_ref())) {
            let generated = spd::generate(Path::new(rel.get_ref()), spec).map_err(|e| self.error_at(rel, format!("path: {}", e.message)))?;
            (generated, PathBuf::from(rel.get_ref()))
        } else {
            let path = self.relative(rel.get_ref());
            if !path.extension().is_some_and(|e| e.eq_ignore_ascii_case("nff")) {
                return Err(self.error_at(rel, "path: only .nff files or spd:NAME can be included (place an .obj with an object of type \"mesh\")"));
            }
            (self.read_referenced(rel, &path)?, path)
        };
        let contents = nff::parse_contents(&source, &path, &nff::NffOptions::default())?;
        let offset = materials.len();
        materials.extend(contents.materials);
        objects.extend(contents.objects.into_iter().map(|o| Object { material: o.material + offset, shapes: o.shapes }));
        lights.extend(contents.lights);
        warnings.extend(contents.warnings);
        Ok(())
    }

    /// The transform of a mesh object: S, then R_x, R_y, R_z, then T; or `matrix`.
    fn transform(&self, object: &Spanned<ObjectDef>) -> Result<DMat4, LoadError> {
        let def = object.get_ref();
        if let Some(m) = &def.matrix {
            if def.translate.is_some() || def.rotate.is_some() || def.scale.is_some() {
                return Err(self.error_at(m, "matrix: cannot be combined with translate, rotate or scale"));
            }
            let rows = m.get_ref().0.map(|row| row.map(f64::from));
            // from_cols_array_2d reads each inner array as a column.
            let matrix = DMat4::from_cols_array_2d(&rows).transpose();
            if (matrix.row(3) - glam::DVec4::W).abs().max_element() > 1e-9 {
                return Err(self.error_at(m, "matrix: the last row must be [0, 0, 0, 1] (an affine transform)"));
            }
            let linear = DMat3::from_mat4(matrix);
            let size = linear.to_cols_array().iter().fold(0.0f64, |a, v| a.max(v.abs()));
            if linear.determinant().abs() <= 1e-12 * size.powi(3) {
                return Err(self.error_at(m, "matrix: singular (it flattens the mesh)"));
            }
            return Ok(matrix);
        }
        let scale = match &def.scale {
            None => DVec3::ONE,
            Some(s) if s.get_ref().0.abs().min_element() > 0.0 => s.get_ref().0.as_dvec3(),
            Some(s) => return Err(self.error_at(s, "scale: must not be zero")),
        };
        let r = def.rotate.map_or(DVec3::ZERO, |r| r.0.as_dvec3());
        let t = def.translate.map_or(DVec3::ZERO, |t| t.0.as_dvec3());
        Ok(DMat4::from_translation(t)
            * DMat4::from_rotation_z(r.z.to_radians())
            * DMat4::from_rotation_y(r.y.to_radians())
            * DMat4::from_rotation_x(r.x.to_radians())
            * DMat4::from_scale(scale))
    }

    fn mesh(
        &self,
        object: &Spanned<ObjectDef>,
        material: Option<usize>,
        materials: &mut Vec<Material>,
        meshes: &mut Meshes,
        objects: &mut Vec<Object>,
    ) -> Result<(), LoadError> {
        let def = object.get_ref();
        let rel = def.path.as_ref().ok_or_else(|| self.error_at(object, "object: a mesh needs `path`"))?;
        let transform = self.transform(object)?;
        let path = self.relative(rel.get_ref());
        if !path.extension().is_some_and(|e| e.eq_ignore_ascii_case("obj")) {
            return Err(self.error_at(rel, "path: a mesh is read from an .obj file (bring in an .nff file with [[include]])"));
        }
        let key = std::fs::canonicalize(&path)
            .map_err(|e| self.error_at(rel, format!("path: cannot open `{}`: {e}", path.display())))?;
        if !meshes.cache.contains_key(&key) {
            let source = self.read_referenced(rel, &path)?;
            let mesh = obj::parse_mesh(&source, &path)?;
            meshes.warnings.extend(mesh.warnings.iter().cloned());
            meshes.cache.insert(key.clone(), CachedMesh { mesh, material_offset: None });
        }
        let cached = meshes.cache.get_mut(&key).expect("just inserted");
        let offset = match (material, cached.material_offset) {
            (Some(_), _) => 0,
            (None, Some(offset)) => offset,
            (None, None) => {
                let offset = materials.len();
                materials.extend(cached.mesh.materials.iter().cloned());
                cached.material_offset = Some(offset);
                offset
            }
        };
        let normal_matrix = DMat3::from_mat4(transform).inverse().transpose();
        let point = |p: Vec3| transform.transform_point3(p.as_dvec3()).as_vec3();
        let normal = |n: Vec3| (normal_matrix * n.as_dvec3()).normalize().as_vec3();
        // A mirroring transform reverses the winding; swapping two vertices keeps
        // each face's normal on the side its vertex normals (and the file) say.
        let mirrored = DMat3::from_mat4(transform).determinant() < 0.0;
        for part in &cached.mesh.parts {
            let mut shapes = Vec::with_capacity(part.triangles.len());
            for t in &part.triangles {
                let Shape::Triangle { vertices, normals } = t else {
                    unreachable!("meshes hold only triangles, found {t:?}");
                };
                let mut vertices = vertices.map(point);
                let mut normals = *normals;
                if mirrored {
                    vertices.swap(1, 2);
                    if let Some(n) = &mut normals {
                        n.swap(1, 2);
                    }
                }
                if !vertices.iter().all(|v| v.is_finite()) {
                    return Err(self.error_at(object, "object: the transform takes the mesh beyond the range of 32-bit floats"));
                }
                // A normal the transform cannot carry (it underflows) leaves the triangle flat.
                let normals = normals.map(|n| n.map(normal)).filter(|n| n.iter().all(|v| v.is_finite()));
                shapes.push(Shape::Triangle { vertices, normals });
            }
            objects.push(Object { material: material.unwrap_or(offset + part.material), shapes });
        }
        Ok(())
    }

    fn image(&self, image: &Spanned<ImageDef>) -> Result<(u32, u32, Vec3), LoadError> {
        let def = image.get_ref();
        let side = |v: &Spanned<i64>, key: &str| {
            u32::try_from(*v.get_ref())
                .ok()
                .filter(|s| (1..=MAX_IMAGE_SIDE).contains(s))
                .ok_or_else(|| self.error_at(v, format!("{key}: {} is outside 1..={MAX_IMAGE_SIDE}", v.get_ref())))
        };
        let background = self.optional_colour(&def.background, "background", false).unwrap_or(Vec3::ZERO);
        Ok((side(&def.width, "width")?, side(&def.height, "height")?, background))
    }

    fn camera(&self, camera: &Spanned<CameraDef>) -> Result<Camera, LoadError> {
        let def = camera.get_ref();
        let kind = def.kind.as_ref().map_or("perspective", |k| k.get_ref().as_str());
        let projection = match kind {
            "perspective" => {
                if let Some(h) = &def.height {
                    return Err(self.error_at(h, "height: only an orthographic camera has a view-plane height"));
                }
                let fov = def.fov.as_ref().ok_or_else(|| self.error_at(camera, "camera: missing field `fov`"))?;
                let fov_y_degrees = fov.get_ref().0;
                if !(fov_y_degrees > 0.0 && fov_y_degrees < 180.0) {
                    return Err(self.error_at(fov, format!("fov: {fov_y_degrees} is not between 0 and 180 degrees")));
                }
                if let Some(warning) = radians_warning("fov", fov_y_degrees) {
                    self.warn_at(fov, warning);
                }
                Projection::Perspective { fov_y_degrees }
            }
            "orthographic" => {
                if let Some(f) = &def.fov {
                    return Err(self.error_at(f, "fov: an orthographic camera has a view-plane `height`, not a field of view"));
                }
                let h = def.height.as_ref().ok_or_else(|| self.error_at(camera, "camera: missing field `height`"))?;
                if h.get_ref().0 <= 0.0 {
                    return Err(self.error_at(h, "height: must be positive"));
                }
                Projection::Orthographic { height: h.get_ref().0 }
            }
            other => {
                let k = def.kind.as_ref().expect("a non-default kind was written");
                return Err(self.error_at(k, format!("type: unknown camera type `{other}`, expected `perspective` or `orthographic`")));
            }
        };
        let camera_value = Camera { eye: def.eye.0, look_at: def.look_at.0, up: def.up.map_or(Vec3::Y, |u| u.0), projection };
        if crate::view_overflows(&camera_value) {
            return Err(self.error_at(camera, "camera: eye and look_at are too far apart (the view direction overflows 32-bit floats)"));
        }
        if camera_value.basis().is_none() {
            return Err(self.error_at(camera, "camera: `up` is parallel to the view direction (or eye equals look_at)"));
        }
        Ok(camera_value)
    }

    fn render(&self, def: &RenderDef) -> Result<RenderSettings, LoadError> {
        let d = RenderSettings::default();
        let max_depth = match &def.max_depth {
            None => d.max_depth,
            Some(v) => u32::try_from(*v.get_ref())
                .ok()
                .filter(|m| (1..=MAX_DEPTH_LIMIT).contains(m))
                .ok_or_else(|| self.error_at(v, format!("max_depth: {} is outside 1..={MAX_DEPTH_LIMIT}", v.get_ref())))?,
        };
        let shadow_mode = match def.shadow_mode.as_ref() {
            None => d.shadow_mode,
            Some(m) => match m.get_ref().as_str() {
                "opaque" => ShadowMode::Opaque,
                "tinted" => ShadowMode::Tinted,
                other => return Err(self.error_at(m, format!("shadow_mode: unknown mode `{other}`, expected `opaque` or `tinted`"))),
            },
        };
        Ok(RenderSettings {
            max_depth,
            cutoff: self.ranged(&def.cutoff, "cutoff", d.cutoff, 0.0, 1.0)?,
            shadows: def.shadows.unwrap_or(d.shadows),
            shadow_mode,
            reflections: def.reflections.unwrap_or(d.reflections),
            refractions: def.refractions.unwrap_or(d.refractions),
        })
    }

    fn depth_cue(&self, cue: &Spanned<DepthCueDef>) -> Result<DepthCue, LoadError> {
        let def = cue.get_ref();
        if def.far.0 <= def.near.0 {
            return Err(self.error_at(cue, "depth_cue: `far` must be greater than `near`"));
        }
        Ok(DepthCue {
            color: self.colour(&def.color, "color", false),
            near: def.near.0,
            far: def.far.0,
            near_scale: self.ranged(&def.near_scale, "near_scale", 1.0, 0.0, 1.0)?,
            far_scale: self.ranged(&Some(def.far_scale.clone()), "far_scale", 0.0, 0.0, 1.0)?,
        })
    }

    fn light(&self, light: &Spanned<LightDef>) -> Result<Light, LoadError> {
        let def = light.get_ref();
        let kind = match def.kind.get_ref().as_str() {
            "point" => {
                if def.direction.is_some() {
                    return Err(self.error_at(light, "light: a point light has a `position`, not a `direction`"));
                }
                let p = def.position.ok_or_else(|| self.error_at(light, "light: missing field `position`"))?;
                LightKind::Point { position: p.0 }
            }
            "directional" => {
                if def.position.is_some() {
                    return Err(self.error_at(light, "light: a directional light has a `direction`, not a `position`"));
                }
                let d = def.direction.ok_or_else(|| self.error_at(light, "light: missing field `direction`"))?;
                let direction = crate::unit(d.0).ok_or_else(|| self.error_at(light, "direction: must not be zero"))?;
                LightKind::Directional { direction }
            }
            other => return Err(self.error_at(&def.kind, format!("type: unknown light type `{other}`, expected `point` or `directional`"))),
        };
        let attenuation = match def.attenuation.as_ref().map(|a| a.get_ref().as_str()) {
            None | Some("none") => Attenuation::None,
            Some("inverse_square") => Attenuation::InverseSquare,
            Some("polynomial") => {
                let c = def.coefficients.as_ref().ok_or_else(|| {
                    self.error_at(light, "light: polynomial attenuation needs `coefficients = [c1, c2, c3]`")
                })?;
                let v = c.get_ref().0;
                if v.min_element() < 0.0 || v.max_element() <= 0.0 {
                    return Err(self.error_at(c, "coefficients: must be non-negative and not all zero"));
                }
                Attenuation::Polynomial { c1: v.x, c2: v.y, c3: v.z }
            }
            Some(other) => {
                let a = def.attenuation.as_ref().expect("matched Some");
                return Err(self.error_at(a, format!("attenuation: unknown form `{other}`, expected `none`, `inverse_square` or `polynomial`")));
            }
        };
        if let (LightKind::Directional { .. }, Some(a)) = (kind, &def.attenuation) {
            return Err(self.error_at(a, "attenuation: a directional light has no distance to attenuate over"));
        }
        if let (Some(c), Attenuation::None | Attenuation::InverseSquare) = (&def.coefficients, attenuation) {
            return Err(self.error_at(c, "coefficients: only polynomial attenuation takes coefficients"));
        }
        let color = self.optional_colour(&def.color, "color", false).unwrap_or(Vec3::ONE);
        let intensity = self.ranged(&def.intensity, "intensity", 1.0, 0.0, f32::MAX)?;
        self.no_overflow(&def.intensity, color * intensity)?;
        Ok(Light { kind, color, intensity, attenuation, enabled: def.enabled.unwrap_or(true) })
    }

    /// `light` (a colour times `intensity`) when it is finite: the product of
    /// two finite numbers can overflow 32-bit floats.
    fn no_overflow(&self, intensity: &Option<Spanned<Num>>, light: Vec3) -> Result<Vec3, LoadError> {
        match intensity {
            Some(i) if !light.is_finite() => {
                Err(self.error_at(i, "intensity: the colour times the intensity overflows 32-bit floats"))
            }
            _ => Ok(light),
        }
    }

    fn material(&self, name: &str, def: &MaterialDef) -> Result<Material, LoadError> {
        let d = Material::default();
        let specular_model = match def.model.as_ref() {
            None => d.specular_model,
            Some(m) => match m.get_ref().as_str() {
                "phong" => SpecularModel::Phong,
                "blinn" => SpecularModel::BlinnPhong,
                other => return Err(self.error_at(m, format!("model: unknown specular model `{other}`, expected `phong` or `blinn`"))),
            },
        };
        Ok(Material {
            name: name.to_string(),
            ambient: self.ranged(&def.ka, "ka", d.ambient, 0.0, f32::MAX)?,
            diffuse: self.ranged(&def.kd, "kd", d.diffuse, 0.0, f32::MAX)?,
            specular: self.ranged(&def.ks, "ks", d.specular, 0.0, f32::MAX)?,
            shininess: self.ranged(&def.shininess, "shininess", d.shininess, 0.0, 1e6)?,
            color: self.colour(&def.color, "color", true),
            specular_color: self.optional_colour(&def.specular_color, "specular_color", true),
            specular_model,
            metallic_f0: self.optional_colour(&def.metallic, "metallic", true),
            reflect: self.optional_colour(&def.reflect, "reflect", true).unwrap_or(Vec3::ZERO),
            transmit: self.optional_colour(&def.transmit, "transmit", true).unwrap_or(Vec3::ZERO),
            ior: self.ranged(&def.ior, "ior", 1.0, 0.01, 100.0)?,
            fresnel: def.fresnel.unwrap_or(false),
        })
    }

    fn object(
        &self,
        object: &Spanned<ObjectDef>,
        names: &BTreeMap<&str, usize>,
        materials: &mut Vec<Material>,
        meshes: &mut Meshes,
        objects: &mut Vec<Object>,
    ) -> Result<(), LoadError> {
        let def = object.get_ref();
        let named = match &def.material {
            None => None,
            Some(m) => Some(
                *names
                    .get(m.get_ref().as_str())
                    .ok_or_else(|| self.error_at(m, format!("material: no material named `{}`", m.get_ref())))?,
            ),
        };
        let material = named.unwrap_or(0);
        let kind = def.kind.get_ref().as_str();
        let Some(allowed) = object_keys(kind) else {
            return Err(self.error_at(
                &def.kind,
                format!("type: unknown object type `{kind}`, expected sphere, triangle, polygon, cone, cylinder, mesh or icosphere"),
            ));
        };
        let present = [
            ("center", def.center.is_some()),
            ("radius", def.radius.is_some()),
            ("vertices", def.vertices.is_some()),
            ("normals", def.normals.is_some()),
            ("base", def.base.is_some()),
            ("base_radius", def.base_radius.is_some()),
            ("apex", def.apex.is_some()),
            ("apex_radius", def.apex_radius.is_some()),
            ("path", def.path.is_some()),
            ("translate", def.translate.is_some()),
            ("rotate", def.rotate.is_some()),
            ("scale", def.scale.is_some()),
            ("matrix", def.matrix.is_some()),
            ("subdivisions", def.subdivisions.is_some()),
            ("displacement", def.displacement.is_some()),
        ];
        if let Some((key, _)) = present.iter().find(|(k, p)| *p && !allowed.contains(k)) {
            return Err(self.error_at(object, format!("object: `{key}` does not apply to a {kind}")));
        }
        if kind == "mesh" {
            return self.mesh(object, named, materials, meshes, objects);
        }
        let missing = |key: &str| self.error_at(object, format!("object: a {kind} needs `{key}`"));
        let positive = |v: &Option<Spanned<Num>>, key: &str| -> Result<f32, LoadError> {
            let s = v.as_ref().ok_or_else(|| missing(key))?;
            if s.get_ref().0 > 0.0 {
                Ok(s.get_ref().0)
            } else {
                Err(self.error_at(s, format!("{key}: must be positive, found {}", s.get_ref().0)))
            }
        };
        if kind == "icosphere" {
            let center = def.center.ok_or_else(|| missing("center"))?.0;
            let radius = positive(&def.radius, "radius")?;
            let s = def.subdivisions.as_ref().ok_or_else(|| missing("subdivisions"))?;
            let subdivisions = u32::try_from(*s.get_ref())
                .ok()
                .filter(|n| *n <= icosphere::MAX_SUBDIVISIONS)
                .ok_or_else(|| self.error_at(s, format!("subdivisions: {} is outside 0..={}", s.get_ref(), icosphere::MAX_SUBDIVISIONS)))?;
            let displacement = self.ranged(&def.displacement, "displacement", 0.0, 0.0, 0.5)?;
            let shapes = icosphere::icosphere(center, radius, subdivisions, displacement);
            if !shapes.iter().all(crate::bounds_are_finite) {
                return Err(self.error_at(object, "object: the icosphere reaches beyond the range of 32-bit floats"));
            }
            objects.push(Object { material, shapes });
            return Ok(());
        }
        let shape = match kind {
            "sphere" => Shape::Sphere { center: def.center.ok_or_else(|| missing("center"))?.0, radius: positive(&def.radius, "radius")? },
            "triangle" | "polygon" => {
                let vs = def.vertices.as_ref().ok_or_else(|| missing("vertices"))?;
                let vertices: Vec<Vec3> = vs.get_ref().iter().map(|v| v.0).collect();
                let expected = if kind == "triangle" { vertices.len() == 3 } else { vertices.len() >= 3 };
                if !expected {
                    let need = if kind == "triangle" { "exactly 3" } else { "at least 3" };
                    return Err(self.error_at(vs, format!("vertices: a {kind} needs {need} vertices, found {}", vertices.len())));
                }
                let normal = polygon_normal(&vertices)
                    .ok_or_else(|| self.error_at(vs, format!("vertices: the {kind} has no area (its vertices are collinear)")))?;
                if kind == "polygon" {
                    if polygon_non_planarity(&vertices, normal) > 1e-4 {
                        return Err(self.error_at(vs, "vertices: the polygon's vertices are not coplanar"));
                    }
                    Shape::Polygon { vertices }
                } else {
                    let normals = match &def.normals {
                        None => None,
                        Some(ns) if ns.get_ref().len() == 3 && ns.get_ref().iter().all(|n| crate::unit(n.0).is_some()) => {
                            Some([0, 1, 2].map(|i| crate::unit(ns.get_ref()[i].0).expect("checked")))
                        }
                        Some(ns) => return Err(self.error_at(ns, "normals: a triangle needs 3 non-zero normals")),
                    };
                    Shape::Triangle { vertices: [vertices[0], vertices[1], vertices[2]], normals }
                }
            }
            _ => {
                let base = def.base.ok_or_else(|| missing("base"))?.0;
                let apex = def.apex.ok_or_else(|| missing("apex"))?.0;
                if (apex - base).length() == 0.0 {
                    return Err(self.error_at(object, "object: `base` and `apex` must differ"));
                }
                let base_radius = positive(&def.base_radius, "base_radius")?;
                let apex_radius = if kind == "cylinder" && def.apex_radius.is_none() {
                    base_radius
                } else {
                    let r = def.apex_radius.as_ref().ok_or_else(|| missing("apex_radius"))?;
                    if r.get_ref().0 < 0.0 {
                        return Err(self.error_at(r, "apex_radius: must not be negative"));
                    }
                    r.get_ref().0
                };
                Shape::Cone { base, base_radius, apex, apex_radius }
            }
        };
        if !crate::bounds_are_finite(&shape) {
            return Err(self.error_at(object, format!("object: the {kind} reaches beyond the range of 32-bit floats")));
        }
        objects.push(Object { material, shapes: vec![shape] });
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    const MINIMAL: &str = r#"
[image]
width = 32
height = 24

[camera]
eye = [0, 0, 5]
look_at = [0, 0, 0]
fov = 40
"#;

    fn parse_str(extra: &str) -> Result<Scene, LoadError> {
        parse(&format!("{MINIMAL}{extra}"), Path::new("test.toml"))
    }

    fn error(extra: &str) -> String {
        parse_str(extra).unwrap_err().to_string()
    }

    #[test]
    fn minimal_scene_has_defaults() {
        let s = parse_str("").unwrap();
        assert_eq!((s.width, s.height), (32, 24));
        assert_eq!(s.camera.projection, Projection::Perspective { fov_y_degrees: 40.0 });
        assert_eq!(s.camera.up, Vec3::Y);
        assert_eq!(s.materials.len(), 1);
        assert_eq!(s.render, RenderSettings::default());
    }

    #[test]
    fn every_section_parses() {
        let s = parse_str(
            r#"
[ambient]
color = [1, 0.5, 0.25]
intensity = 0.2

[render]
max_depth = 3
cutoff = 0.01
shadow_mode = "tinted"

[depth_cue]
color = [0.5, 0.5, 0.5]
near = 1
far = 11
far_scale = 0.25

[[light]]
type = "point"
position = [1, 2, 3]
color = [1, 1, 0]
intensity = 2
attenuation = "polynomial"
coefficients = [1, 0.1, 0.01]

[[light]]
type = "directional"
direction = [0, -2, 0]

[material.glass]
color = 1
ks = 0.5
model = "phong"
transmit = [0.9, 0.9, 0.9]
ior = 1.5
fresnel = true

[[object]]
type = "sphere"
center = [0, 0, 0]
radius = 1
material = "glass"

[[object]]
type = "polygon"
vertices = [[0, 0, 0], [2, 0, 0], [2, 1, 0], [1, 1, 0], [1, 2, 0], [0, 2, 0]]

[[object]]
type = "cylinder"
base = [0, 0, 0]
apex = [0, 1, 0]
base_radius = 0.5
"#,
        )
        .unwrap();
        assert_eq!(s.ambient, Vec3::new(0.2, 0.1, 0.05));
        assert_eq!(s.render.max_depth, 3);
        assert_eq!(s.render.shadow_mode, ShadowMode::Tinted);
        assert_eq!(s.depth_cue.unwrap().near_scale, 1.0);
        assert_eq!(s.lights[0].attenuation, Attenuation::Polynomial { c1: 1.0, c2: 0.1, c3: 0.01 });
        assert_eq!(s.lights[1].kind, LightKind::Directional { direction: Vec3::NEG_Y });
        assert_eq!(s.materials[1].specular_model, SpecularModel::Phong);
        assert_eq!(s.objects[0].material, 1);
        assert!(matches!(s.objects[2].shapes[0], Shape::Cone { apex_radius: 0.5, .. }));
    }

    #[test]
    fn orthographic_camera() {
        let s = parse(
            "[image]\nwidth = 4\nheight = 4\n[camera]\ntype = \"orthographic\"\neye = [0,0,5]\nlook_at = [0,0,0]\nheight = 3\n",
            Path::new("o.toml"),
        )
        .unwrap();
        assert_eq!(s.camera.projection, Projection::Orthographic { height: 3.0 });
    }

    #[test]
    fn unknown_key_names_file_line_and_key() {
        let e = error("[[object]]\ntype = \"sphere\"\ncenter = [0, 0, 0]\nradus = 1\n");
        assert!(e.starts_with("test.toml:13:"), "{e}");
        assert!(e.contains("radus"), "{e}");
    }

    #[test]
    fn wrong_type_names_line_and_key() {
        let e = error("[[object]]\ntype = \"sphere\"\ncenter = [0, 0, 0]\nradius = \"big\"\n");
        assert!(e.starts_with("test.toml:13:"), "{e}");
        assert!(e.contains("radius"), "{e}");
    }

    #[test]
    fn nan_is_rejected_where_it_stands() {
        let e = error("[[object]]\ntype = \"sphere\"\ncenter = [0, nan, 0]\nradius = 1\n");
        assert!(e.starts_with("test.toml:12:"), "{e}");
        assert!(e.contains("finite"), "{e}");
    }

    #[test]
    fn missing_field_names_the_table_and_field() {
        let e = error("[[object]]\ntype = \"sphere\"\ncenter = [0, 0, 0]\n");
        assert!(e.starts_with("test.toml:1"), "{e}");
        assert!(e.contains("`radius`"), "{e}");
        let e = parse("[image]\nwidth = 3\nheight = 3\n", Path::new("t.toml")).unwrap_err().to_string();
        assert!(e.contains("camera"), "{e}");
    }

    #[test]
    fn semantic_errors_point_at_the_value() {
        for (extra, line, needle) in [
            ("[[object]]\ntype = \"sphere\"\ncenter = [0, 0, 0]\nradius = -1\n", 13, "positive"),
            ("[[object]]\ntype = \"sphere\"\ncenter = [0, 0, 0]\nradius = 1\nmaterial = \"nope\"\n", 14, "nope"),
            ("[[object]]\ntype = \"polygon\"\nvertices = [[0,0,0],[1,0,0]]\n", 12, "at least 3"),
            ("[[object]]\ntype = \"triangle\"\nvertices = [[0,0,0],[1,0,0],[2,0,0]]\n", 12, "no area"),
            ("[[object]]\ntype = \"polygon\"\nvertices = [[0,0,0],[1,0,0],[1,1,0],[0,1,1]]\n", 12, "coplanar"),
            ("[render]\nmax_depth = 1000\n", 11, "max_depth"),
            ("[[light]]\ntype = \"spotlight\"\nposition = [0,0,0]\n", 11, "spotlight"),
            ("[[light]]\ntype = \"directional\"\ndirection = [0,-1,0]\nattenuation = \"inverse_square\"\n", 13, "directional"),
        ] {
            let e = error(extra);
            assert!(e.starts_with(&format!("test.toml:{line}:")), "{e}");
            assert!(e.contains(needle), "{e}");
        }
    }

    #[test]
    fn points_need_exactly_three_numbers() {
        for (center, needle) in [("[0, 0, 0, 1]", "array of 3 numbers, found 4 values"), ("[0, 0]", "found 2 values"), ("[0, 0, 1e39]", "32-bit")] {
            let e = error(&format!("[[object]]\ntype = \"sphere\"\ncenter = {center}\nradius = 1\n"));
            assert!(e.starts_with("test.toml:12:10:") && e.contains(needle), "{center}: {e}");
        }
        let e = error("[[object]]\ntype = \"polygon\"\nvertices = [[0, 0, 0], [1, 0, 0], [0, 1, 0, 7]]\n");
        assert!(e.starts_with("test.toml:12:") && e.contains("found 4 values"), "{e}");
    }

    #[test]
    fn geometry_and_views_that_overflow_f32_are_errors() {
        let e = error("[[object]]\ntype = \"sphere\"\ncenter = [3e38, 0, 0]\nradius = 3e38\n");
        assert!(e.starts_with("test.toml:10:1:") && e.contains("32-bit floats"), "{e}");
        let e = error("[[object]]\ntype = \"cylinder\"\nbase = [3e38, 0, 0]\napex = [3e38, 1, 0]\nbase_radius = 3e38\n");
        assert!(e.starts_with("test.toml:10:1:") && e.contains("32-bit floats"), "{e}");
        let src = MINIMAL.replace("eye = [0, 0, 5]", "eye = [0, 0, 3e38]").replace("look_at = [0, 0, 0]", "look_at = [0, 0, -3e38]");
        let e = parse(&src, Path::new("p.toml")).unwrap_err().to_string();
        assert!(e.starts_with("p.toml:6:1:") && e.contains("too far apart"), "{e}");
    }

    #[test]
    fn directions_and_normals_of_any_finite_size_normalise() {
        let s = parse_str(
            "[[light]]\ntype = \"directional\"\ndirection = [3e38, 0, 0]\n[[object]]\ntype = \"triangle\"\n\
             vertices = [[0, 0, 0], [1, 0, 0], [0, 1, 0]]\nnormals = [[0, 0, 3e38], [0, 0, 1e-30], [0, 0, 1]]\n",
        )
        .unwrap();
        assert_eq!(s.lights[0].kind, LightKind::Directional { direction: Vec3::X });
        assert!(matches!(&s.objects[0].shapes[0], Shape::Triangle { normals: Some(n), .. } if *n == [Vec3::Z; 3]));
    }

    #[test]
    fn light_that_overflows_f32_is_an_error() {
        let e = error("[[light]]\ntype = \"point\"\nposition = [0, 0, 0]\ncolor = [3e38, 0, 0]\nintensity = 10\n");
        assert!(e.starts_with("test.toml:14:13:") && e.contains("overflows"), "{e}");
        let e = error("[ambient]\ncolor = 3e38\nintensity = 3e38\n");
        assert!(e.starts_with("test.toml:12:13:") && e.contains("overflows"), "{e}");
    }

    #[test]
    fn type_errors_are_in_plain_words() {
        for (extra, want) in [
            ("[[object]]\ntype = \"sphere\"\ncenter = [0, 0, 0]\nradius = \"big\"\n", "test.toml:13:10: radius: expected a number, found the string \"big\""),
            ("[render]\nmax_depth = 3.0\n", "test.toml:11:13: max_depth: expected a whole number, found 3.0 (write 3, without the decimal point)"),
            ("[render]\nshadows = 1\n", "test.toml:11:11: shadows: expected `true` or `false`, found 1"),
            ("[[object]]\ntype = 3\n", "test.toml:11:8: type: expected a string in quotes, found 3"),
            ("[[object]]\ntype = \"sphere\"\ncenter = 1\nradius = 1\n", "test.toml:12:10: center: expected an array, found 1"),
        ] {
            let e = error(extra);
            assert_eq!(e, want);
            assert!(!e.contains("f64") && !e.contains("i64") && !e.contains("invalid type"), "{e}");
        }
    }

    #[test]
    fn a_table_of_the_wrong_kind_is_explained() {
        let e = error("[object]\ntype = \"sphere\"\ncenter = [0, 0, 0]\nradius = 1\n");
        assert_eq!(e, "test.toml:10:2: [object] is a single table: write [[object]] (an array of tables) for each object");
        let e = error("[light]\ntype = \"point\"\nposition = [0, 0, 0]\n");
        assert!(e.starts_with("test.toml:10:") && e.contains("write [[light]]"), "{e}");
        let src = MINIMAL.replace("[camera]", "[[camera]]");
        let e = parse(&src, Path::new("t.toml")).unwrap_err().to_string();
        assert!(e.starts_with("t.toml:6:") && e.contains("a scene has one camera: write [camera]"), "{e}");
        let e = error("[material]\ncolor = [1, 0, 0]\n");
        assert!(e.starts_with("test.toml:11:1:") && e.contains("write [material.NAME]"), "{e}");
        let e = error("[[material]]\ncolor = [1, 0, 0]\n");
        assert!(e.starts_with("test.toml:10:") && e.contains("[material.red]"), "{e}");
    }

    #[test]
    fn an_unclosed_array_is_reported_where_it_opens() {
        let e = error("[[object]]\ntype = \"sphere\"\ncenter = [0, 0, 0\nradius = 1\n");
        assert_eq!(e, "test.toml:12:10: center: this array is not closed: a `]` is missing");
        // At the end of the file too.
        let e = error("[[object]]\ntype = \"sphere\"\ncenter = [0, 0,\n");
        assert!(e.starts_with("test.toml:12:10:") && e.contains("not closed"), "{e}");
        // A comma missing inside a multi-line array is a missing comma, where it is.
        let e = error("[[object]]\ntype = \"polygon\"\nvertices = [\n  [0, 0, 0]\n  [1, 0, 0],\n  [0, 1, 0],\n]\n");
        assert!(e.starts_with("test.toml:14:") && e.contains("missing comma"), "{e}");
        let e = error("[[object]]\ntype = \"sphere\"\ncenter = [0 0 0]\nradius = 1\n");
        assert_eq!(e, "test.toml:12:10: center: the values of an array are separated by commas: write [0, 0, 0]");
    }

    #[test]
    fn unknown_keys_name_the_first_in_the_file_and_the_nearest_valid_key() {
        // `zenter` comes before `radus` in the file, though not in the alphabet.
        let e = error("[[object]]\ntype = \"sphere\"\nzenter = [0, 0, 0]\nradus = 1\n");
        assert_eq!(e, "test.toml:12:1: unknown key `zenter` in a sphere object; did you mean `center`?");
        let e = error("[[object]]\ntype = \"sphere\"\ncenter = [0, 0, 0]\nradus = 1\n");
        assert_eq!(e, "test.toml:13:1: unknown key `radus` in a sphere object; did you mean `radius`?");
        // The keys of that type of object only, not all seventeen.
        let e = error("[[object]]\ntype = \"sphere\"\ncenter = [0, 0, 0]\nradius = 1\nwobble = 2\n");
        assert_eq!(e, "test.toml:14:1: unknown key `wobble` in a sphere object, which takes `type`, `material`, `center`, `radius`");
        // Across tables: [image] comes first in the file, [camera] in the alphabet.
        let src = MINIMAL.replace("height = 24", "heigth = 24").replace("fov = 40", "fov = 40\nfvo = 3");
        let e = parse(&src, Path::new("t.toml")).unwrap_err().to_string();
        assert_eq!(e, "t.toml:4:1: unknown key `heigth` in [image]; did you mean `height`?");
        for (extra, want) in [
            ("[[objects]]\ntype = \"sphere\"\n", "test.toml:10:3: unknown table [[objects]]; did you mean [[object]]?"),
            ("[render]\nspp = 4\n", "test.toml:11:1: unknown key `spp` in [render]: `spp` is a command-line option (glint render --spp …), not a scene key"),
            (
                "[[object]]\ntype = \"sphere\"\ncenter = [0, 0, 0]\nradius = 1\ncolor = [1, 0, 0]\n",
                "test.toml:14:1: unknown key `color` in a sphere object: `color` belongs to a material; define it in [material.NAME] and give the object `material = \"NAME\"`",
            ),
            ("[ambient]\nfov = 3\n", "test.toml:11:1: unknown key `fov` in [ambient]: `fov` belongs in [camera]"),
            ("[[light]]\ntype = \"point\"\npostion = [0, 0, 0]\n", "test.toml:12:1: unknown key `postion` in a point light; did you mean `position`?"),
            ("[material.red]\ncolour = 1\n", "test.toml:11:1: unknown key `colour` in [material.red]; did you mean `color`?"),
        ] {
            assert_eq!(error(extra), want);
        }
    }

    fn warnings(src: &str) -> Vec<String> {
        parse(src, Path::new("w.toml")).unwrap().warnings.iter().map(ToString::to_string).collect()
    }

    #[test]
    fn colours_written_0_to_255_and_radian_angles_warn() {
        let w = warnings(&format!("{MINIMAL}[material.red]\ncolor = [230, 50, 25]\n"));
        assert_eq!(w, ["w.toml:11:9: color: [230, 50, 25] looks like 0–255 values, but colours are 0 to 1; did you mean [0.9, 0.2, 0.1]?"]);
        let w = warnings(&format!("{MINIMAL}[material.white]\ncolor = 1.5\nreflect = [0.5, 0.5, 2]\n"));
        assert_eq!(w.len(), 2, "{w:?}");
        assert!(w[0].starts_with("w.toml:11:9: color: 1.5 is above 1"), "{w:?}");
        assert!(w[1].starts_with("w.toml:12:11: reflect: [0.5, 0.5, 2] is above 1"), "{w:?}");
        // Light may be brighter than 1; only 0–255 values are suspicious there.
        let light = |c: &str| format!("{MINIMAL}[[light]]\ntype = \"point\"\nposition = [0, 0, 0]\ncolor = {c}\n");
        assert!(warnings(&light("[1.0, 0.9, 2.5]")).is_empty());
        let w = warnings(&light("[255, 255, 255]"));
        assert_eq!(w, ["w.toml:13:9: color: 255 looks like 0–255 values, but colours are 0 to 1 (set the brightness with `intensity`); did you mean 1?"]);
        let w = warnings(&MINIMAL.replace("fov = 40", "fov = 0.5"));
        assert_eq!(w, ["w.toml:9:7: fov: 0.5° is a very narrow view; angles are in degrees (0.5 radians is 28.6)"]);
        assert!(warnings(MINIMAL).is_empty());
        assert!(warnings(&MINIMAL.replace("fov = 40", "fov = 3.5")).is_empty());
        // In file order, whatever the order of checking.
        let src = format!("{}[material.a]\ncolor = [0, 0, 9]\n", MINIMAL.replace("[image]", "[image]\nbackground = [200, 200, 200]").replace("fov = 40", "fov = 1"));
        let lines: Vec<String> = warnings(&src).iter().map(|w| w.split(':').nth(1).unwrap().to_string()).collect();
        assert_eq!(lines, ["3", "10", "12"]);
    }

    #[test]
    fn up_parallel_to_view_is_an_error() {
        let src = MINIMAL.replace("fov = 40", "fov = 40\nup = [0, 0, 1]");
        let e = parse(&src, Path::new("p.toml")).unwrap_err().to_string();
        assert!(e.contains("parallel"), "{e}");
    }

    #[test]
    fn absurd_image_size_is_an_error() {
        let src = MINIMAL.replace("width = 32", "width = 100000");
        let e = parse(&src, Path::new("p.toml")).unwrap_err().to_string();
        assert!(e.starts_with("p.toml:3:"), "{e}");
        let src = MINIMAL.replace("width = 32", "width = 0");
        assert!(parse(&src, Path::new("p.toml")).is_err());
    }

    mod files {
        use super::*;
        use crate::obj::tests::{write, CUBE_MTL, CUBE_OBJ};

        fn scene_file(dir: &Path, extra: &str) -> Result<Scene, LoadError> {
            crate::load(&write(dir, "scene.toml", &format!("{MINIMAL}{extra}")))
        }

        fn bounds(shapes: &[Shape]) -> (Vec3, Vec3) {
            shapes.iter().map(Shape::bounds).reduce(|(a, b), (c, d)| (a.min(c), b.max(d))).unwrap()
        }

        fn close(a: Vec3, b: Vec3) -> bool {
            (a - b).abs().max_element() < 1e-5
        }

        #[test]
        fn mirroring_transforms_keep_faces_and_vertex_normals_on_one_side() {
            let dir = tempfile::tempdir().unwrap();
            write(dir.path(), "tri.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nvn 0 0 1\nvn 0 0 1\nvn 0 0 1\nf 1//1 2//2 3//3\n");
            for transform in ["scale = [-1, 1, 1]", "scale = [1, 1, 1]", "matrix = [[1, 0, 0, 0], [0, 1, 0, 0], [0, 0, -1, 0], [0, 0, 0, 1]]"] {
                let s = scene_file(dir.path(), &format!("[[object]]\ntype = \"mesh\"\npath = \"tri.obj\"\n{transform}\n")).unwrap();
                let Shape::Triangle { vertices: [a, b, c], normals: Some(n) } = &s.objects[0].shapes[0] else { panic!() };
                let face = (*b - *a).cross(*c - *a);
                assert!(n.iter().all(|n| face.dot(*n) > 0.0), "{transform}: face {face} against normals {n:?}");
            }
        }

        #[test]
        fn mesh_instances_with_transforms() {
            let dir = tempfile::tempdir().unwrap();
            write(dir.path(), "cube.obj", CUBE_OBJ);
            write(dir.path(), "cube.mtl", CUBE_MTL);
            let s = scene_file(
                dir.path(),
                r#"
[material.gold]
color = [1, 0.8, 0.2]

[[object]]
type = "mesh"
path = "cube.obj"
scale = 2
rotate = [0, 90, 0]
translate = [10, 0, 0]

[[object]]
type = "mesh"
path = "./cube.obj"
material = "gold"
matrix = [[1, 0, 0, 0], [0, 1, 0, 5], [0, 0, 1, 0], [0, 0, 0, 1]]

[[object]]
type = "mesh"
path = "cube.obj"
"#,
            )
            .unwrap();
            assert!(s.warnings.is_empty(), "{:?}", s.warnings);
            // Each instance is three objects (one per material) of four triangles.
            assert_eq!(s.objects.len(), 9);
            assert_eq!(s.primitive_count(), 36);
            // default, gold, then the MTL's three, added once.
            let names: Vec<&str> = s.materials.iter().map(|m| m.name.as_str()).collect();
            assert_eq!(names, ["default", "gold", "red", "green", "blue"]);
            let ids: Vec<usize> = s.objects.iter().map(|o| o.material).collect();
            assert_eq!(ids, [2, 3, 4, 1, 1, 1, 2, 3, 4]);

            let first: Vec<Shape> = s.objects[..3].iter().flat_map(|o| o.shapes.clone()).collect();
            let (lo, hi) = bounds(&first);
            assert!(close(lo, Vec3::new(10.0, 0.0, -2.0)) && close(hi, Vec3::new(12.0, 2.0, 0.0)), "{lo} {hi}");
            let second: Vec<Shape> = s.objects[3..6].iter().flat_map(|o| o.shapes.clone()).collect();
            let (lo, hi) = bounds(&second);
            assert!(close(lo, Vec3::new(0.0, 5.0, 0.0)) && close(hi, Vec3::new(1.0, 6.0, 1.0)), "{lo} {hi}");
            let third: Vec<Shape> = s.objects[6..].iter().flat_map(|o| o.shapes.clone()).collect();
            assert!(close(bounds(&third).1, Vec3::ONE));
        }

        #[test]
        fn normals_use_the_inverse_transpose() {
            let dir = tempfile::tempdir().unwrap();
            // A triangle in the plane x + y = 1 with its true normal.
            write(dir.path(), "slope.obj", "v 1 0 0\nv 0 1 0\nv 1 0 1\nvn 1 1 0\nf 1//1 2//1 3//1\n");
            let s = scene_file(dir.path(), "[[object]]\ntype = \"mesh\"\npath = \"slope.obj\"\nscale = [2, 1, 1]\n").unwrap();
            let Shape::Triangle { vertices, normals: Some(n) } = &s.objects[0].shapes[0] else { panic!() };
            assert_eq!(vertices[0], Vec3::new(2.0, 0.0, 0.0));
            // The plane is now x/2 + y = 1, normal ∝ (1/2, 1, 0).
            let want = Vec3::new(0.5, 1.0, 0.0).normalize();
            assert!(n.iter().all(|v| close(*v, want)), "{n:?}");
            let face = (vertices[1] - vertices[0]).cross(vertices[2] - vertices[0]).normalize();
            assert!(face.dot(want).abs() > 0.99999);
        }

        #[test]
        fn a_mesh_read_twice_warns_once() {
            let dir = tempfile::tempdir().unwrap();
            write(dir.path(), "cube.obj", CUBE_OBJ);
            let mesh = "[[object]]\ntype = \"mesh\"\npath = \"cube.obj\"\n";
            let s = scene_file(dir.path(), &format!("{mesh}{mesh}translate = [3, 0, 0]\n")).unwrap();
            assert_eq!(s.warnings.len(), 1, "{:?}", s.warnings);
            assert!(s.warnings[0].to_string().contains("cube.mtl"));
            assert_eq!(s.materials.len(), 2, "the TOML default, then the OBJ's default once");
            assert!(s.objects.iter().all(|o| o.material == 1));
            assert_eq!(s.primitive_count(), 24);
        }

        #[test]
        fn mesh_errors() {
            let dir = tempfile::tempdir().unwrap();
            write(dir.path(), "cube.obj", CUBE_OBJ);
            write(dir.path(), "bad.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 9\n");
            for (extra, at, needle) in [
                ("[[object]]\ntype = \"mesh\"\npath = \"missing.obj\"\n", "scene.toml:12:", "cannot open"),
                ("[[object]]\ntype = \"mesh\"\npath = \"bad.obj\"\n", "bad.obj:4: ", "malformed OBJ"),
                ("[[object]]\ntype = \"mesh\"\n", "scene.toml:10:", "needs `path`"),
                (
                    "[[object]]\ntype = \"mesh\"\npath = \"cube.obj\"\ntranslate = [1, 0, 0]\nmatrix = [[1,0,0,0],[0,1,0,0],[0,0,1,0],[0,0,0,1]]\n",
                    "scene.toml:14:",
                    "cannot be combined",
                ),
                ("[[object]]\ntype = \"mesh\"\npath = \"cube.obj\"\nmatrix = [[1,0,0,0],[0,1,0,0],[0,0,1,0],[0,0,1,1]]\n", "scene.toml:13:", "last row"),
                ("[[object]]\ntype = \"mesh\"\npath = \"cube.obj\"\nmatrix = [[1,0,0,0],[0,1,0,0],[0,0,0,0],[0,0,0,1]]\n", "scene.toml:13:", "singular"),
                ("[[object]]\ntype = \"mesh\"\npath = \"cube.obj\"\nmatrix = [[1,0,0],[0,1,0],[0,0,1]]\n", "scene.toml:13:", "matrix"),
                ("[[object]]\ntype = \"mesh\"\npath = \"cube.obj\"\nscale = [1, 0, 1]\n", "scene.toml:13:", "zero"),
                ("[[object]]\ntype = \"mesh\"\npath = \"cube.obj\"\nrotate = [1, 0]\n", "scene.toml:13:", "rotate"),
                ("[[object]]\ntype = \"mesh\"\npath = \"cube.obj\"\nmaterial = \"nope\"\n", "scene.toml:13:", "nope"),
                ("[[object]]\ntype = \"sphere\"\ncenter = [0, 0, 0]\nradius = 1\ntranslate = [1, 0, 0]\n", "scene.toml:10:", "`translate` does not apply"),
                ("[[object]]\ntype = \"mesh\"\npath = \"cube.obj\"\nradius = 1\n", "scene.toml:10:", "`radius` does not apply"),
            ] {
                let e = scene_file(dir.path(), extra).unwrap_err().to_string();
                assert!(e.contains(at) && e.contains(needle), "{extra}: {e}");
            }
        }

        #[test]
        fn unreadable_references_name_the_right_file() {
            let dir = tempfile::tempdir().unwrap();
            std::fs::create_dir(dir.path().join("folder.obj")).unwrap();
            write(dir.path(), "part.nff", "s 0 0 0 1\n");
            std::fs::write(dir.path().join("binary.obj"), b"v 0 0 0\nv 1 \xff 0\n").unwrap();
            std::fs::write(dir.path().join("binary.nff"), b"s 0 0 0 1\n\x80").unwrap();
            write(dir.path(), "cube.obj", CUBE_OBJ);
            for (extra, at, needle) in [
                // A directory canonicalises but cannot be read: the TOML line says so.
                ("[[object]]\ntype = \"mesh\"\npath = \"folder.obj\"\n", "scene.toml:12:8:", "cannot read"),
                ("[[object]]\ntype = \"mesh\"\npath = \"binary.obj\"\n", "binary.obj:2:5:", "not a text file"),
                ("[[include]]\npath = \"binary.nff\"\n", "binary.nff:2:1:", "not a text file"),
                // An NFF read as an OBJ would fail on its first line, naming the wrong problem.
                ("[[object]]\ntype = \"mesh\"\npath = \"part.nff\"\n", "scene.toml:12:8:", "[[include]]"),
                (
                    "[[object]]\ntype = \"mesh\"\npath = \"cube.obj\"\nmatrix = [[1,0,0,0],[0,1,0,0],[0,0,1,0,5],[0,0,0,1]]\n",
                    "scene.toml:13:",
                    "row length 5",
                ),
                ("[[object]]\ntype = \"mesh\"\npath = \"cube.obj\"\nscale = 1e38\ntranslate = [0, 0, 3e38]\n", "scene.toml:10:1:", "32-bit floats"),
            ] {
                let e = scene_file(dir.path(), extra).unwrap_err().to_string();
                assert!(e.contains(at) && e.contains(needle), "{extra}: {e}");
            }
        }

        #[test]
        fn include_merges_an_nff() {
            let dir = tempfile::tempdir().unwrap();
            // No `v` block: an included NFF may be geometry only.
            write(dir.path(), "part.nff", "b 1 0 0\nl 1 2 3\nl 4 5 6 0 1 0\nf 0 1 0 1 0 0 0 1\ns 0 0 0 1\np 3\n0 0 0\n1 0 0\n0 1 0\n");
            let s = scene_file(
                dir.path(),
                r#"
[[light]]
type = "point"
position = [0, 9, 0]

[material.red]
color = [1, 0, 0]

[[object]]
type = "sphere"
center = [5, 0, 0]
radius = 1
material = "red"

[[include]]
path = "part.nff"
"#,
            )
            .unwrap();
            assert_eq!(s.background, Vec3::ZERO, "the TOML file's image settings apply");
            assert_eq!(s.objects.len(), 3);
            assert_eq!(s.objects[0].material, 1);
            assert_eq!(s.materials.len(), 3);
            assert!(s.objects[1..].iter().all(|o| s.materials[o.material].color == Vec3::Y));
            assert_eq!(s.objects[1].shapes[0], Shape::Sphere { center: Vec3::ZERO, radius: 1.0 });
            assert_eq!(s.lights.len(), 3);
            assert_eq!(s.lights[2].color, Vec3::Y);
            assert!((s.lights[1].intensity - 2f32.sqrt() / 4.0).abs() < 1e-7, "SPD's √n / (2n) for the file's 2 lights");
            assert_eq!(s.camera.eye, Vec3::new(0.0, 0.0, 5.0));

            // A generated SPD database is included like a file.
            let s = scene_file(dir.path(), "[[include]]\npath = \"spd:tetra:1\"\n").unwrap();
            assert_eq!((s.objects.len(), s.lights.len()), (4, 1));
        }

        #[test]
        fn include_errors() {
            let dir = tempfile::tempdir().unwrap();
            write(dir.path(), "bad.nff", "s 0 0 0 1\ns 0 0\n");
            write(dir.path(), "cube.obj", CUBE_OBJ);
            for (extra, at, needle) in [
                ("[[include]]\npath = \"nope.nff\"\n", "scene.toml:11:", "cannot read"),
                ("[[include]]\npath = \"cube.obj\"\n", "scene.toml:11:", "only .nff"),
                ("[[include]]\npath = \"bad.nff\"\n", "bad.nff:2:1:", "end of file"),
                ("[[include]]\npath = \"bad.nff\"\ndepth = 2\n", "scene.toml:12:", "depth"),
                ("[[include]]\npath = \"spd:tetras\"\n", "scene.toml:11:", "no SPD database named `tetras`"),
                ("[[include]]\npath = \"spd:tetra:99\"\n", "scene.toml:11:", "a whole number from 1 to 10"),
            ] {
                let e = scene_file(dir.path(), extra).unwrap_err().to_string();
                assert!(e.contains(at) && e.contains(needle), "{extra}: {e}");
            }
        }
    }
}
