//! Wavefront OBJ meshes with their MTL materials, read through `tobj`.
//!
//! Faces are triangulated (fans), vertex normals make smooth triangles, points
//! and lines are ignored. A mesh is used two ways: as a scene of its own
//! ([`load`], with a camera that frames it) and as an object of a TOML scene
//! (`type = "mesh"`, through [`load_mesh`]).
//!
//! # MTL mapping
//!
//! MTL describes a Phong-like model with mirror and glass switches (`illum`);
//! Glint's [`Material`] is mapped from it as follows (see [`material_from_mtl`]):
//!
//! | Glint | from MTL |
//! |---|---|
//! | O_d (`color`) | `Kd` (0.8 grey when absent) |
//! | k_d | the opacity d (1 for an opaque material, so O_d = Kd as written) |
//! | k_a | a fixed 0.1: `Ka` is not used, since exporters disagree on it (Blender writes `Ka 1 1 1`) |
//! | O_s (`specular_color`), k_s | `Ks` with k_s = 1; k_s = 0 when `Ks` is absent or `illum` is 0 or 1 |
//! | n (`shininess`) | `Ns` (32 when absent) |
//! | specular model | Blinn-Phong (N·H), as in the MTL spec's formulas |
//! | d, k_t | opacity d = `d`, else 1 − `Tr` (`Tr` is the inverse of `d`), else 1; k_t = 1 − d (grey) |
//! | glass | `illum` 4, 6, 7, 9: the transmitted ray refracts with ior = `Ni` (1.5 when absent); if neither `d` nor `Tr` is given, k_t = `Tf` (white when absent). Other illums see through with ior 1 (dissolve does not bend light). |
//! | k_m (`reflect`) | `Ks` for `illum` 3 to 7 (the ray-traced reflection models), else 0 |
//! | `fresnel` | `illum` 5 and 7 |
//!
//! Colours are clamped to be non-negative. A face with no material, or naming a
//! material no MTL file defines, gets [`Material::default`] (named "default").
//! A missing MTL file is a warning, not an error; a malformed one is an error
//! naming the MTL file and line.

use std::cell::RefCell;
use std::path::{Path, PathBuf};

use glam::Vec3;

use crate::quoted;
use crate::shape::polygon_normal;
use crate::{
    Attenuation, Camera, Light, LightKind, LoadError, Location, Material, Object, Projection,
    RenderSettings, Scene, Shape, SpecularModel,
};

/// A loaded OBJ file: triangles grouped by OBJ object/group and material.
#[derive(Debug, Clone, PartialEq)]
pub struct Mesh {
    /// The OBJ file, as given.
    pub path: PathBuf,
    /// The MTL materials, then (when some face needs it) the default material.
    pub materials: Vec<Material>,
    pub parts: Vec<MeshPart>,
    /// Non-fatal problems: missing MTL files, unknown materials, skipped
    /// degenerate triangles.
    pub warnings: Vec<LoadError>,
}

/// The triangles of one OBJ object or group that share a material.
#[derive(Debug, Clone, PartialEq)]
pub struct MeshPart {
    pub name: String,
    /// Index into [`Mesh::materials`].
    pub material: usize,
    /// Only `Shape::Triangle`s.
    pub triangles: Vec<Shape>,
}

impl Mesh {
    pub fn triangle_count(&self) -> usize {
        self.parts.iter().map(|p| p.triangles.len()).sum()
    }

    /// Axis-aligned bounds (min, max) of all triangles, `None` when there are none.
    pub fn bounds(&self) -> Option<(Vec3, Vec3)> {
        self.parts
            .iter()
            .flat_map(|p| &p.triangles)
            .map(Shape::bounds)
            .reduce(|(lo, hi), (l, h)| (lo.min(l), hi.max(h)))
    }
}

/// The image size of a bare OBJ scene.
pub const DEFAULT_WIDTH: u32 = 640;
pub const DEFAULT_HEIGHT: u32 = 480;
/// The vertical field of view of a bare OBJ scene, degrees.
pub const DEFAULT_FOV_Y: f32 = 40.0;

/// The options every OBJ is read with.
// `..Default::default()` covers the fields of tobj's optional features.
#[allow(clippy::needless_update)]
fn load_options() -> tobj::LoadOptions {
    tobj::LoadOptions { triangulate: true, single_index: true, ignore_points: true, ignore_lines: true, ..Default::default() }
}

/// Reads an OBJ file (and the MTL files it names, relative to it) into a mesh.
pub fn load_mesh(path: &Path) -> Result<Mesh, LoadError> {
    parse_mesh(&read_obj(path)?, path)
}

fn read_obj(path: &Path) -> Result<String, LoadError> {
    crate::read_text(path).map_err(|e| match e {
        crate::ReadError::Io(e) => LoadError::new(path, None, format!("cannot read OBJ file: {e}")),
        crate::ReadError::NotText(e) => e,
    })
}

/// Parses OBJ text; `path` names the file in errors and locates MTL files.
pub fn parse_mesh(source: &str, path: &Path) -> Result<Mesh, LoadError> {
    let at_line = |line: usize, message: String| LoadError::new(path, Some(Location::line(line)), message);
    // tobj accepts NaN and infinities, divides by a `w` of 1e-40, skips faces
    // of fewer than 3 vertices and reports other problems without a place, so
    // the statements Glint reads are checked here first.
    check_obj(source).map_err(|(line, message)| at_line(line, format!("malformed OBJ: {message}")))?;
    // tobj hands the material loader only the name, so remember where each
    // `mtllib` and `usemtl` stands for the warnings.
    let mut mtllibs = Vec::new();
    let mut usemtls = Vec::new();
    for (i, line) in source.lines().enumerate() {
        let line = line.trim();
        match line.split_whitespace().next() {
            Some("mtllib") => mtllibs.push((i + 1, line["mtllib".len()..].trim().to_string())),
            Some("usemtl") => usemtls.push((i + 1, line["usemtl".len()..].trim().to_string())),
            _ => {}
        }
    }

    let dir = path.parent().unwrap_or(Path::new(""));
    let warnings = RefCell::new(Vec::new());
    let fatal = RefCell::new(None);
    let loader = |name: &Path| -> tobj::MTLLoadResult {
        let full = dir.join(name);
        let line = mtllibs.iter().find(|(_, n)| Path::new(n) == name).map(|(l, _)| Location::line(*l));
        let text = match crate::read_text(&full) {
            Ok(text) => text,
            Err(crate::ReadError::NotText(e)) => {
                fatal.borrow_mut().get_or_insert(e);
                return Err(tobj::LoadError::MaterialParseError);
            }
            Err(crate::ReadError::Io(e)) => {
                warnings.borrow_mut().push(LoadError::new(
                    path,
                    line,
                    format!("cannot read material library `{}` ({e}); its materials are replaced by the default", full.display()),
                ));
                return Err(tobj::LoadError::OpenFileFailed);
            }
        };
        let mtl_error = |line: Option<usize>, message: String| LoadError::new(&full, line.map(Location::line), message);
        let text = match check_mtl(&text) {
            Ok(text) => text,
            Err((line, message)) => {
                fatal.borrow_mut().get_or_insert(mtl_error(Some(line), format!("malformed MTL: {message}")));
                return Err(tobj::LoadError::MaterialParseError);
            }
        };
        tobj::load_mtl_buf(&mut text.as_bytes()).inspect_err(|e| {
            let line = first_failing_line(&text, |prefix| tobj::load_mtl_buf(&mut prefix.as_bytes()).is_err());
            fatal.borrow_mut().get_or_insert(mtl_error(line, format!("malformed MTL: {e}")));
        })
    };
    let result = tobj::load_obj_buf(&mut source.as_bytes(), &load_options(), loader);
    if let Some(e) = fatal.into_inner() {
        return Err(e);
    }
    let (models, mtl) = result.map_err(|e| {
        let line = first_failing_line(source, |prefix| {
            tobj::load_obj_buf(&mut prefix.as_bytes(), &load_options(), |_| Err(tobj::LoadError::OpenFileFailed)).is_err()
        });
        LoadError::new(path, line.map(Location::line), format!("malformed OBJ: {e}"))
    })?;
    let mut warnings = warnings.into_inner();
    let mtl = mtl.unwrap_or_default();
    let mut materials: Vec<Material> = mtl.iter().map(material_from_mtl).collect();

    if warnings.is_empty() {
        let mut named = std::collections::HashSet::new();
        for (line, name) in &usemtls {
            if !mtl.iter().any(|m| &m.name == name) && named.insert(name) {
                warnings.push(at_line(*line, format!("no material library defines `{name}`; using the default material")));
            }
        }
    }

    let default_index = materials.len();
    let mut needs_default = false;
    let mut parts = Vec::new();
    let (mut degenerate, mut flat) = (0usize, 0usize);
    for model in &models {
        let mesh = &model.mesh;
        let material = match mesh.material_id {
            Some(i) if i < default_index => i,
            _ => {
                needs_default = true;
                default_index
            }
        };
        let position = |i: u32| {
            let i = i as usize * 3;
            Vec3::new(mesh.positions[i], mesh.positions[i + 1], mesh.positions[i + 2])
        };
        let has_normals = !mesh.normals.is_empty() && mesh.normals.len() == mesh.positions.len();
        if !mesh.normals.is_empty() && !has_normals {
            warnings.push(LoadError::new(path, None, format!("`{}`: only some vertices have normals; shaded flat", model.name)));
        }
        let normal = |i: u32| {
            let i = i as usize * 3;
            Vec3::new(mesh.normals[i], mesh.normals[i + 1], mesh.normals[i + 2])
        };
        let mut triangles = Vec::with_capacity(mesh.indices.len() / 3);
        for tri in mesh.indices.chunks_exact(3) {
            let vertices = [position(tri[0]), position(tri[1]), position(tri[2])];
            if !vertices.iter().all(|v| v.is_finite()) {
                return Err(LoadError::new(path, None, format!("`{}`: a vertex is not finite (w close to 0?)", model.name)));
            }
            if polygon_normal(&vertices).is_none() {
                degenerate += 1;
                continue;
            }
            let normals = has_normals.then(|| [normal(tri[0]), normal(tri[1]), normal(tri[2])]).and_then(|n| {
                let units = n.map(crate::unit);
                let ok = units.iter().all(Option::is_some);
                if !ok {
                    flat += 1;
                }
                ok.then(|| units.map(|u| u.expect("checked")))
            });
            triangles.push(Shape::Triangle { vertices, normals });
        }
        if !triangles.is_empty() {
            parts.push(MeshPart { name: model.name.clone(), material, triangles });
        }
    }
    if needs_default {
        materials.push(Material::default());
    }
    if degenerate > 0 {
        warnings.push(LoadError::new(path, None, format!("skipped {degenerate} degenerate triangle(s) (no area)")));
    }
    if flat > 0 {
        warnings.push(LoadError::new(path, None, format!("{flat} triangle(s) have a zero vertex normal; shaded flat")));
    }
    if parts.is_empty() {
        warnings.push(LoadError::new(path, None, "the OBJ file has no faces"));
    }
    Ok(Mesh { path: path.to_path_buf(), materials, parts, warnings })
}

/// A problem found by [`check_obj`] or [`check_mtl`]: the 1-based line and
/// what is wrong.
type LineError = (usize, String);

/// A finite 32-bit number (what `tobj` stores), or what is wrong with `word`.
fn finite_value(word: &str, what: &str) -> Result<f32, String> {
    match word.parse::<f32>() {
        Ok(v) if v.is_finite() => Ok(v),
        Ok(_) => Err(format!("{what}: {} is not a finite number", quoted(word))),
        Err(_) => Err(format!("{what}: {} is not a number", quoted(word))),
    }
}

/// Checks the OBJ statements Glint reads (`v`, `vt`, `vn`, `f`, `l`): their
/// value counts, that numbers are finite, that `v`'s `w` leaves the position
/// finite, that a face has at least 3 vertices and that every index names an
/// element defined before it (negative indices count back from the last).
fn check_obj(source: &str) -> Result<(), LineError> {
    let (mut positions, mut texcoords, mut normals) = (0usize, 0usize, 0usize);
    for (i, line) in source.lines().enumerate() {
        let at = |message: String| (i + 1, message);
        let mut words = line.split_whitespace();
        let Some(key) = words.next() else { continue };
        let values: Vec<&str> = words.collect();
        match key {
            "v" => {
                if !matches!(values.len(), 3 | 4 | 6) {
                    return Err(at(format!(
                        "vertex position: `v` takes x y z, then w or r g b; found {} value(s)",
                        values.len()
                    )));
                }
                let numbers = values
                    .iter()
                    .map(|w| finite_value(w, "vertex position"))
                    .collect::<Result<Vec<f32>, _>>()
                    .map_err(at)?;
                if let [x, y, z, w] = numbers[..]
                    && (w == 0.0 || !(Vec3::new(x, y, z) / w).is_finite())
                {
                    let w = quoted(values[3]);
                    return Err(at(format!("vertex position: w = {w} takes the vertex beyond the range of 32-bit floats")));
                }
                positions += 1;
            }
            "vt" => {
                if !matches!(values.len(), 2 | 3) {
                    return Err(at(format!("texture coordinate: `vt` takes u v [w]; found {} value(s)", values.len())));
                }
                values.iter().try_for_each(|w| finite_value(w, "texture coordinate").map(drop)).map_err(at)?;
                texcoords += 1;
            }
            "vn" => {
                if values.len() != 3 {
                    return Err(at(format!("vertex normal: `vn` takes x y z; found {} value(s)", values.len())));
                }
                values.iter().try_for_each(|w| finite_value(w, "vertex normal").map(drop)).map_err(at)?;
                normals += 1;
            }
            "f" | "l" => {
                let (min, what) = if key == "f" { (3, "a face") } else { (2, "a line") };
                if values.len() < min {
                    return Err(at(format!("{what} needs at least {min} vertices, found {}", values.len())));
                }
                for word in &values {
                    check_vertex_reference(word, [positions, texcoords, normals]).map_err(at)?;
                }
            }
            _ => {}
        }
    }
    Ok(())
}

/// Checks one vertex of a face, `v`, `v/vt`, `v//vn` or `v/vt/vn`, against the
/// numbers of positions, texture coordinates and normals defined so far.
fn check_vertex_reference(word: &str, defined: [usize; 3]) -> Result<(), String> {
    let parts: Vec<&str> = word.split('/').collect();
    if parts.len() > 3 || parts[0].is_empty() {
        return Err(format!("{} is not a vertex reference (v, v/vt, v//vn or v/vt/vn)", quoted(word)));
    }
    let names = [("vertex", "vertices"), ("texture coordinate", "texture coordinates"), ("normal", "normals")];
    for ((part, count), (name, names)) in parts.iter().zip(defined).zip(names) {
        if part.is_empty() {
            continue;
        }
        let index: i64 = part
            .parse()
            .map_err(|_| format!("{} is not a vertex reference: {} is not a whole number", quoted(word), quoted(part)))?;
        if index == 0 {
            return Err(format!("{} refers to {name} 0, but OBJ counts from 1", quoted(word)));
        }
        let count = count as i64;
        if index.unsigned_abs() > count.unsigned_abs() {
            let counted = match count {
                0 => format!("no {names} are"),
                1 => format!("only 1 {name} is"),
                n => format!("only {n} {names} are"),
            };
            return Err(format!("{} refers to {name} {index}, but {counted} defined before it", quoted(word)));
        }
    }
    Ok(())
}

/// Checks the MTL statements Glint reads and returns the text `tobj` should
/// parse: colours (`Ka`, `Kd`, `Ks`, `Ke`, `Tf`) take r g b or one grey value
/// (which `tobj` cannot read, so it is written out as three), `Ns`, `Ni`, `d`
/// and `Tr` one number, and every number must be finite.
fn check_mtl(text: &str) -> Result<std::borrow::Cow<'_, str>, LineError> {
    let mut rewritten: Option<String> = None;
    for (i, line) in text.lines().enumerate() {
        let at = |message: String| (i + 1, message);
        let mut words = line.split_whitespace();
        let Some(key) = words.next() else { continue };
        let values: Vec<&str> = words.collect();
        match key {
            "Ka" | "Kd" | "Ks" | "Ke" | "Tf" => {
                if !matches!(values.len(), 1 | 3) {
                    return Err(at(format!("`{key}` takes r g b or one grey value; found {} value(s)", values.len())));
                }
                values.iter().try_for_each(|w| finite_value(w, key).map(drop)).map_err(at)?;
                if values.len() == 1 && key != "Tf" {
                    let out = rewritten.get_or_insert_with(|| {
                        text.lines().take(i).fold(String::with_capacity(text.len() + 16), |mut s, l| {
                            s.push_str(l);
                            s.push('\n');
                            s
                        })
                    });
                    out.push_str(&format!("{key} {0} {0} {0}\n", values[0]));
                    continue;
                }
            }
            "Ns" | "Ni" | "d" | "Tr" => {
                if values.len() != 1 {
                    return Err(at(format!("`{key}` takes one number; found {} value(s)", values.len())));
                }
                finite_value(values[0], key).map_err(at)?;
            }
            _ => {}
        }
        if let Some(out) = rewritten.as_mut() {
            out.push_str(line);
            out.push('\n');
        }
    }
    Ok(rewritten.map_or(std::borrow::Cow::Borrowed(text), std::borrow::Cow::Owned))
}

/// The 1-based line at which `fails` first fails on a prefix of `text` (whole
/// lines), found by bisection: `tobj` reports what went wrong but not where.
fn first_failing_line(text: &str, fails: impl Fn(&str) -> bool) -> Option<usize> {
    let ends: Vec<usize> = text.match_indices('\n').map(|(i, _)| i + 1).chain(std::iter::once(text.len())).collect();
    let prefix = |lines: usize| &text[..ends[lines - 1]];
    let (mut lo, mut hi) = (1, ends.len());
    if !fails(prefix(hi)) {
        return None;
    }
    while lo < hi {
        let mid = (lo + hi) / 2;
        if fails(prefix(mid)) {
            hi = mid;
        } else {
            lo = mid + 1;
        }
    }
    Some(lo)
}

fn rgb(c: [f32; 3]) -> Vec3 {
    Vec3::from(c).max(Vec3::ZERO)
}

/// Parses "r g b" (one number gives a grey); `None` for other forms.
fn parse_rgb(text: &str) -> Option<Vec3> {
    let v: Vec<f32> = text.split_whitespace().map(str::parse).collect::<Result<_, _>>().ok()?;
    match v[..] {
        [g] => Some(Vec3::splat(g)),
        [r, g, b] => Some(Vec3::new(r, g, b)),
        _ => None,
    }
    .filter(|c| c.is_finite())
    .map(|c| c.max(Vec3::ZERO))
}

/// Glint's material for an MTL material; the mapping is in the module docs.
pub fn material_from_mtl(m: &tobj::Material) -> Material {
    let param = |key: &str| m.unknown_param.get(key).map(String::as_str);
    let given_dissolve = m.dissolve.or_else(|| param("Tr").and_then(|t| t.trim().parse::<f32>().ok()).map(|tr| 1.0 - tr));
    let opacity = given_dissolve.filter(|d| d.is_finite()).unwrap_or(1.0).clamp(0.0, 1.0);
    let illum = m.illumination_model.unwrap_or(2);
    let glass = matches!(illum, 4 | 6 | 7 | 9);
    let mirror = (3..=7).contains(&illum);
    let highlights = illum >= 2;
    let ks = m.specular.map(rgb);
    let transmit = if glass && given_dissolve.is_none() {
        param("Tf").and_then(parse_rgb).unwrap_or(Vec3::ONE)
    } else {
        Vec3::splat(1.0 - opacity)
    };
    let ior = match m.optical_density {
        Some(n) if glass && n > 0.0 => n,
        _ if glass => 1.5,
        _ => 1.0,
    };
    Material {
        name: m.name.clone(),
        ambient: 0.1,
        diffuse: opacity,
        specular: if highlights && ks.is_some() { 1.0 } else { 0.0 },
        shininess: m.shininess.unwrap_or(32.0).clamp(0.0, 1e6),
        color: m.diffuse.map_or(Vec3::splat(0.8), rgb),
        specular_color: ks,
        specular_model: SpecularModel::BlinnPhong,
        metallic_f0: None,
        reflect: if mirror { ks.unwrap_or(Vec3::ZERO) } else { Vec3::ZERO },
        transmit,
        ior,
        fresnel: matches!(illum, 5 | 7),
    }
}

/// Reads an OBJ file as a scene of its own: the mesh with its materials, seen
/// by a perspective camera (fov [`DEFAULT_FOV_Y`]) that looks at the centre of
/// its bounding box from the +y/+z diagonal, far enough back that the box's
/// bounding sphere fits the image (with a 5 % margin); one white point light
/// (intensity 1, no attenuation) above and to the right of the camera; ambient
/// light I_a = 1 (with the MTL materials' k_a = 0.1 that is a tenth of each
/// colour); a dark grey background; [`DEFAULT_WIDTH`] × [`DEFAULT_HEIGHT`] pixels.
pub fn load(path: &Path) -> Result<Scene, LoadError> {
    let source = read_obj(path)?;
    let mesh = parse_mesh(&source, path)?;
    let Some((lo, hi)) = mesh.bounds() else {
        // Named at the end of the file, where the reader gave up looking.
        let last_line = source.lines().count().max(1);
        return Err(LoadError::new(
            path,
            Some(Location::line(last_line)),
            "the OBJ file has no faces to render (none with an area by the end of the file)",
        ));
    };
    let center = (lo + hi) / 2.0;
    let radius = ((hi - lo).length() / 2.0).max(1e-6);
    let aspect = DEFAULT_WIDTH as f32 / DEFAULT_HEIGHT as f32;
    let half_y = (DEFAULT_FOV_Y / 2.0).to_radians();
    let half = half_y.min((half_y.tan() * aspect).atan());
    let distance = 1.05 * radius / half.sin();
    let eye = center + Vec3::new(0.0, 1.0, 1.0).normalize() * distance;
    let camera = Camera { eye, look_at: center, up: Vec3::Y, projection: Projection::Perspective { fov_y_degrees: DEFAULT_FOV_Y } };
    let basis = camera.basis().expect("the view direction is never parallel to +y");
    let light_position = eye + (basis.u + basis.v).as_vec3() * radius;
    Ok(Scene {
        width: DEFAULT_WIDTH,
        height: DEFAULT_HEIGHT,
        background: Vec3::splat(0.1),
        camera,
        ambient: Vec3::ONE,
        lights: vec![Light {
            kind: LightKind::Point { position: light_position },
            color: Vec3::ONE,
            intensity: 1.0,
            attenuation: Attenuation::None,
            enabled: true,
        }],
        materials: mesh.materials,
        objects: mesh.parts.into_iter().map(|p| Object { material: p.material, shapes: p.triangles }).collect(),
        depth_cue: None,
        render: RenderSettings::default(),
        warnings: mesh.warnings,
    })
}

#[cfg(test)]
pub(crate) mod tests {
    use super::*;

    pub const CUBE_OBJ: &str = "\
# a unit cube, one material per pair of opposite faces
mtllib cube.mtl
v 0 0 0
v 1 0 0
v 1 1 0
v 0 1 0
v 0 0 1
v 1 0 1
v 1 1 1
v 0 1 1
o cube
usemtl red
f 1 4 3 2
f 5 6 7 8
usemtl green
f 1 2 6 5
f 4 8 7 3
usemtl blue
f 1 5 8 4
f 2 3 7 6
";

    pub const CUBE_MTL: &str = "\
newmtl red
Ka 1 1 1
Kd 0.8 0.1 0.1
Ks 0.5 0.5 0.5
Ns 50
illum 2

newmtl green
Kd 0.1 0.8 0.1
Ks 0.9 0.9 0.9
Ns 200
illum 3

newmtl blue
Kd 0.1 0.1 0.8
Ks 0.2 0.2 0.2
Ni 1.33
d 0.25
illum 7
";

    pub fn write(dir: &Path, name: &str, text: &str) -> PathBuf {
        let p = dir.join(name);
        std::fs::write(&p, text).unwrap();
        p
    }

    fn triangles(s: &Scene) -> Vec<&Shape> {
        s.objects.iter().flat_map(|o| &o.shapes).collect()
    }

    #[test]
    fn cube_with_mtl() {
        let dir = tempfile::tempdir().unwrap();
        write(dir.path(), "cube.mtl", CUBE_MTL);
        let scene = load(&write(dir.path(), "cube.obj", CUBE_OBJ)).unwrap();
        assert!(scene.warnings.is_empty(), "{:?}", scene.warnings);
        assert_eq!(triangles(&scene).len(), 12);
        assert_eq!(scene.materials.len(), 3, "no default needed");
        let colors: Vec<Vec3> = scene.objects.iter().map(|o| scene.materials[o.material].color).collect();
        assert_eq!(colors, [Vec3::new(0.8, 0.1, 0.1), Vec3::new(0.1, 0.8, 0.1), Vec3::new(0.1, 0.1, 0.8)]);
        for o in &scene.objects {
            assert_eq!(o.shapes.len(), 4);
            assert!(o.shapes.iter().all(|s| matches!(s, Shape::Triangle { normals: None, .. })));
        }

        let red = &scene.materials[0];
        assert_eq!((red.name.as_str(), red.ambient, red.diffuse, red.specular, red.shininess), ("red", 0.1, 1.0, 1.0, 50.0));
        assert_eq!(red.specular_color, Some(Vec3::splat(0.5)));
        assert_eq!(red.specular_model, SpecularModel::BlinnPhong);
        assert_eq!((red.reflect, red.transmit, red.ior, red.fresnel), (Vec3::ZERO, Vec3::ZERO, 1.0, false));
        let green = &scene.materials[1];
        assert_eq!(green.reflect, Vec3::splat(0.9), "illum 3 mirrors with Ks");
        let blue = &scene.materials[2];
        assert_eq!(blue.transmit, Vec3::splat(0.75));
        assert_eq!((blue.diffuse, blue.ior, blue.fresnel), (0.25, 1.33, true));
        assert_eq!(blue.reflect, Vec3::splat(0.2));

        // The default camera sees the whole cube.
        assert_eq!((scene.width, scene.height), (DEFAULT_WIDTH, DEFAULT_HEIGHT));
        assert_eq!(scene.camera.look_at, Vec3::splat(0.5));
        for corner in [Vec3::ZERO, Vec3::ONE, Vec3::X, Vec3::new(1.0, 1.0, 0.0), Vec3::new(0.0, 0.0, 1.0)] {
            let (x, y) = scene.camera.project(scene.width, scene.height, corner.as_dvec3()).unwrap();
            assert!((0.0..640.0).contains(&x) && (0.0..480.0).contains(&y), "{corner}: {x} {y}");
        }
        assert_eq!(scene.lights.len(), 1);
    }

    #[test]
    fn tr_is_the_inverse_of_d_and_glass_uses_tf() {
        let mut m = tobj::Material { name: "g".into(), illumination_model: Some(2), ..Default::default() };
        m.unknown_param.insert("Tr".into(), "0.3".into());
        let g = material_from_mtl(&m);
        assert!((g.transmit - Vec3::splat(0.3)).length() < 1e-6 && (g.diffuse - 0.7).abs() < 1e-6);
        assert_eq!(g.ior, 1.0, "dissolve alone does not refract");
        assert_eq!(g.specular, 0.0, "no Ks, no highlights");

        let mut m = tobj::Material { name: "glass".into(), illumination_model: Some(6), optical_density: None, ..Default::default() };
        m.unknown_param.insert("Tf".into(), "0.9 0.95 1".into());
        let g = material_from_mtl(&m);
        assert_eq!((g.transmit, g.ior, g.diffuse), (Vec3::new(0.9, 0.95, 1.0), 1.5, 1.0));
    }

    #[test]
    fn missing_mtl_is_a_warning() {
        let dir = tempfile::tempdir().unwrap();
        let scene = load(&write(dir.path(), "cube.obj", CUBE_OBJ)).unwrap();
        assert_eq!(triangles(&scene).len(), 12);
        assert_eq!(scene.materials.len(), 1);
        assert_eq!(scene.materials[0], Material::default());
        assert_eq!(scene.warnings.len(), 1, "{:?}", scene.warnings);
        let w = scene.warnings[0].to_string();
        assert!(w.contains("cube.obj:2: ") && w.contains("cube.mtl"), "{w}");
    }

    #[test]
    fn unknown_material_is_a_warning() {
        let dir = tempfile::tempdir().unwrap();
        write(dir.path(), "cube.mtl", CUBE_MTL);
        let obj = CUBE_OBJ.replace("usemtl blue", "usemtl purple");
        let scene = load(&write(dir.path(), "cube.obj", &obj)).unwrap();
        assert_eq!(scene.materials.len(), 4);
        assert_eq!(scene.warnings.len(), 1);
        assert!(scene.warnings[0].to_string().contains("cube.obj:18: ") && scene.warnings[0].message.contains("purple"));
        assert_eq!(scene.objects[2].material, 3);
    }

    #[test]
    fn normals_make_smooth_triangles() {
        let dir = tempfile::tempdir().unwrap();
        let obj = "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nvn 0 0 2\nvn 0 0 1\nvn 0 1 1\nvn 1 0 1\nf 1//1 2//2 3//3 4//4\n";
        let scene = load(&write(dir.path(), "quad.obj", obj)).unwrap();
        let tris = triangles(&scene);
        assert_eq!(tris.len(), 2);
        let Shape::Triangle { vertices, normals: Some(n) } = tris[0] else { panic!("{:?}", tris[0]) };
        assert_eq!(vertices[1], Vec3::X);
        assert_eq!(n[0], Vec3::Z);
        assert!((n[2] - Vec3::new(0.0, 1.0, 1.0).normalize()).length() < 1e-6);
        assert_eq!(scene.materials.len(), 1, "no MTL: the default");
        assert!(scene.warnings.is_empty(), "{:?}", scene.warnings);
    }

    #[test]
    fn errors_name_file_and_line() {
        let dir = tempfile::tempdir().unwrap();
        let e = load(&dir.path().join("nope.obj")).unwrap_err().to_string();
        assert!(e.contains("nope.obj: cannot read"), "{e}");
        for (obj, line, needle) in [
            ("v 0 0 0\nv 1 0 0\nv 0 x 0\nf 1 2 3\n", 3, "position"),
            ("v 0 0 0\nv 1 0 0\nv 0 1 0\n\nf 1 2 7\n", 5, "malformed OBJ"),
            ("v 0 0 0\nv nan 0 0\nv 0 1 0\nf 1 2 3\n", 2, "finite"),
        ] {
            let e = load(&write(dir.path(), "bad.obj", obj)).unwrap_err().to_string();
            assert!(e.contains(&format!("bad.obj:{line}: ")) && e.contains(needle), "{e}");
        }
        write(dir.path(), "bad.mtl", "newmtl a\nKd 1 1 1\nNs many\n");
        let e = load(&write(dir.path(), "m.obj", "mtllib bad.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n")).unwrap_err().to_string();
        assert!(e.contains("bad.mtl:3: ") && e.contains("malformed MTL"), "{e}");
        let e = load(&write(dir.path(), "empty.obj", "v 0 0 0\n")).unwrap_err().to_string();
        assert!(e.contains("no faces"), "{e}");
    }

    #[test]
    fn statements_are_checked_before_tobj_sees_them() {
        let dir = tempfile::tempdir().unwrap();
        const TRI: &str = "v 0 0 0\nv 1 0 0\nv 0 1 0\n";
        for (body, line, needle) in [
            ("v 1 0\n", 4, "found 2 value(s)"),
            ("v 1 0 0 1 1\n", 4, "found 5 value(s)"),
            ("v 1 0 0 0\n", 4, "w = `0`"),
            ("v 1 0 0 1e-40\n", 4, "range of 32-bit floats"),
            ("v 1e39 0 0\n", 4, "`1e39` is not a finite number"),
            ("vn 0 1\n", 4, "`vn` takes x y z"),
            ("vt 0.5 0.5 0.5 0.5\n", 4, "`vt` takes u v [w]"),
            ("f 1 2\n", 4, "at least 3 vertices, found 2"),
            ("l 1\n", 4, "at least 2 vertices"),
            ("f 0 1 2\n", 4, "OBJ counts from 1"),
            ("f 1 2 4\n", 4, "only 3 vertices are defined"),
            ("f -1 -2 -4\n", 4, "refers to vertex -4"),
            ("f 1 2 -9223372036854775808\n", 4, "refers to vertex -9223372036854775808"),
            ("f 1 2 99999999999999999999\n", 4, "not a whole number"),
            ("f 1/1 2/1 3/1\n", 4, "no texture coordinates are defined"),
            ("vn 0 0 1\nf 1//1 2//1 3//2\n", 5, "only 1 normal is defined"),
            ("f 1 2 3/1/1/1\n", 4, "not a vertex reference"),
            ("f 1 2 /3\n", 4, "not a vertex reference"),
        ] {
            let e = load(&write(dir.path(), "bad.obj", &format!("{TRI}{body}"))).unwrap_err().to_string();
            assert!(e.contains(&format!("bad.obj:{line}: malformed OBJ: ")) && e.contains(needle), "{body:?}: {e}");
        }
        // Valid forms still load: w, relative indices, texture coordinates, vertex colours.
        let ok = "v 0 0 0 2\nv 2 0 0 2\nv 0 1 0\nvt 0 0\nvt 1 0 0\nvn 0 0 1\nf -3/1/1 -2/2/1 -1//1\n";
        let s = load(&write(dir.path(), "ok.obj", ok)).unwrap();
        assert_eq!(triangles(&s).len(), 1);
        let Shape::Triangle { vertices, .. } = triangles(&s)[0] else { panic!() };
        assert_eq!(vertices[1], Vec3::X, "w divides");
        let colours = "v 0 0 0 1 0 0\nv 1 0 0 0 1 0\nv 0 1 0 0 0 1\nf 1 2 3\n";
        assert_eq!(triangles(&load(&write(dir.path(), "rgb.obj", colours)).unwrap()).len(), 1);
    }

    #[test]
    fn mtl_colours_take_three_values_or_one_grey() {
        let dir = tempfile::tempdir().unwrap();
        let obj = "mtllib m.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nusemtl a\nf 1 2 3\n";
        // One value is a grey (tobj 4 itself panics on it).
        write(dir.path(), "m.mtl", "newmtl a\nKd 0.5\nKs 0.25\nNs 10\n");
        let s = load(&write(dir.path(), "m.obj", obj)).unwrap();
        assert_eq!(s.materials[0].color, Vec3::splat(0.5));
        assert_eq!(s.materials[0].specular_color, Some(Vec3::splat(0.25)));
        assert_eq!(s.materials[0].shininess, 10.0);
        for (mtl, line, needle) in [
            ("newmtl a\nKd 1 0\n", 2, "found 2 value(s)"),
            ("newmtl a\nKs\n", 2, "found 0 value(s)"),
            ("newmtl a\nKd 1 1 1\nNs 1e39\n", 3, "`1e39` is not a finite number"),
            ("newmtl a\nd -halo 0.5\n", 2, "`d` takes one number"),
            ("newmtl a\nTf 1 nan 1\n", 2, "not a finite number"),
        ] {
            write(dir.path(), "m.mtl", mtl);
            let e = load(&write(dir.path(), "m.obj", obj)).unwrap_err().to_string();
            assert!(e.contains(&format!("m.mtl:{line}: malformed MTL: ")) && e.contains(needle), "{mtl:?}: {e}");
        }
        std::fs::write(dir.path().join("m.mtl"), b"newmtl a\nKd 1 1 1\n\xfe\n").unwrap();
        let e = load(&write(dir.path(), "m.obj", obj)).unwrap_err().to_string();
        assert!(e.contains("m.mtl:3:1: not a text file"), "{e}");
    }

    #[test]
    fn nothing_to_render_names_the_end_of_the_file() {
        let dir = tempfile::tempdir().unwrap();
        let e = load(&write(dir.path(), "flat.obj", "v 0 0 0\nv 1 1 1\nv 2 2 2\nf 1 2 3\n")).unwrap_err().to_string();
        assert!(e.contains("flat.obj:4: ") && e.contains("no faces"), "{e}");
        let e = load(&write(dir.path(), "empty.obj", "")).unwrap_err().to_string();
        assert!(e.contains("empty.obj:1: ") && e.contains("no faces"), "{e}");
    }

    #[test]
    fn huge_and_tiny_normals_normalise() {
        let dir = tempfile::tempdir().unwrap();
        let obj = "v 0 0 0\nv 1 0 0\nv 0 1 0\nvn 0 0 3e38\nvn 0 0 1e-30\nvn 0 0 0\nf 1//1 2//2 3//1\nf 1//1 2//3 3//1\n";
        let s = load(&write(dir.path(), "n.obj", obj)).unwrap();
        let tris = triangles(&s);
        assert!(matches!(tris[0], Shape::Triangle { normals: Some(n), .. } if *n == [Vec3::Z; 3]), "{tris:?}");
        assert!(matches!(tris[1], Shape::Triangle { normals: None, .. }), "a zero normal shades flat: {tris:?}");
        assert_eq!(s.warnings.len(), 1, "{:?}", s.warnings);
    }

    #[test]
    fn degenerate_faces_are_skipped_with_a_warning() {
        let dir = tempfile::tempdir().unwrap();
        let scene = load(&write(dir.path(), "d.obj", "v 0 0 0\nv 1 0 0\nv 2 0 0\nv 0 1 0\nf 1 2 3\nf 1 2 4\n")).unwrap();
        assert_eq!(triangles(&scene).len(), 1);
        assert!(scene.warnings[0].message.contains("1 degenerate"), "{:?}", scene.warnings);
    }
}
