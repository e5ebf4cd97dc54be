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

mod check;
#[cfg(test)]
pub(crate) mod tests;

use check::{check_mtl, check_obj, first_failing_line};

use crate::shape::ShapeProblem;
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
            .filter_map(Shape::bounds)
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
    tobj::LoadOptions { triangulate: false, single_index: true, ignore_points: true, ignore_lines: true, ..Default::default() }
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
    let face_lines = check_obj(source).map_err(|(line, message)| at_line(line, format!("malformed OBJ: {message}")))?;
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
    let mut flat = 0usize;
    // Faces skipped as degenerate, and polygons kept though not planar: one
    // warning each, at the first such face, so a large mesh does not flood.
    let mut degenerate = FaceWarning::default();
    let mut non_planar = FaceWarning::default();
    let mut face_index = 0;
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
        // tobj leaves `face_arities` empty when every face is a triangle.
        let arities: Vec<usize> = if mesh.face_arities.is_empty() {
            vec![3; mesh.indices.len() / 3]
        } else {
            mesh.face_arities.iter().map(|&n| n as usize).collect()
        };
        let mut triangles = Vec::with_capacity(mesh.indices.len() / 3);
        let mut first = 0;
        for arity in arities {
            let face = &mesh.indices[first..first + arity];
            first += arity;
            let line = face_lines.get(face_index).copied();
            face_index += 1;
            let vertices: Vec<Vec3> = face.iter().map(|&i| position(i)).collect();
            if !vertices.iter().all(|v| v.is_finite()) {
                return Err(LoadError::new(path, None, format!("`{}`: a vertex is not finite (w close to 0?)", model.name)));
            }
            // A face is a polygon of the scene model, built and checked by the
            // same constructor as everywhere, then stored as a fan of triangles.
            let checked = match vertices[..] {
                [a, b, c] => Shape::triangle([a, b, c], None).map(|_| None),
                _ => Shape::polygon(vertices).map(|(_, non_planar)| non_planar),
            };
            match checked {
                Ok(None) => {}
                Ok(Some(warning)) => non_planar.add(line, warning),
                Err(ShapeProblem::Degenerate(warning)) => {
                    degenerate.add(line, warning);
                    continue;
                }
                Err(ShapeProblem::Overflows) => {
                    return Err(LoadError::new(path, line.map(Location::line), format!("`{}`: the face reaches beyond the range of 32-bit floats", model.name)));
                }
            }
            for k in 1..arity - 1 {
                let corners = [face[0], face[k], face[k + 1]];
                let normals = has_normals.then(|| corners.map(normal)).and_then(|n| {
                    let units = n.map(crate::unit);
                    let ok = units.iter().all(Option::is_some);
                    if !ok {
                        flat += 1;
                    }
                    ok.then(|| units.map(|u| u.expect("checked")))
                });
                match Shape::triangle(corners.map(position), normals) {
                    Ok(triangle) => triangles.push(triangle),
                    // A fan over a convex face with collinear neighbours has slivers of no area.
                    Err(ShapeProblem::Degenerate(_)) => {}
                    Err(ShapeProblem::Overflows) => {
                        return Err(LoadError::new(path, line.map(Location::line), format!("`{}`: the face reaches beyond the range of 32-bit floats", model.name)));
                    }
                }
            }
        }
        if !triangles.is_empty() {
            parts.push(MeshPart { name: model.name.clone(), material, triangles });
        }
    }
    if needs_default {
        materials.push(Material::default());
    }
    warnings.extend(degenerate.into_warning(path, "degenerate"));
    warnings.extend(non_planar.into_warning(path, "non-planar"));
    if flat > 0 {
        warnings.push(LoadError::new(path, None, format!("{flat} triangle(s) have a zero vertex normal; shaded flat")));
    }
    if parts.is_empty() {
        warnings.push(LoadError::new(path, None, "the OBJ file has no faces"));
    }
    Ok(Mesh { path: path.to_path_buf(), materials, parts, warnings })
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

/// Faces with the same problem: the first one's line and message, and how many.
#[derive(Default)]
struct FaceWarning {
    first: Option<(Option<usize>, String)>,
    count: usize,
}

impl FaceWarning {
    fn add(&mut self, line: Option<usize>, message: String) {
        self.first.get_or_insert((line, message));
        self.count += 1;
    }

    /// The warning, naming the first face's line; `kind` words the count of the others.
    fn into_warning(self, path: &Path, kind: &str) -> Option<LoadError> {
        let (line, message) = self.first?;
        let others = match self.count - 1 {
            0 => String::new(),
            1 => format!(" (and 1 more {kind} face)"),
            n => format!(" (and {n} more {kind} faces)"),
        };
        Some(LoadError::new(path, line.map(Location::line), format!("{message}{others}")))
    }
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
        checker: None,
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
        animation: None,
        warnings: mesh.warnings,
    })
}
