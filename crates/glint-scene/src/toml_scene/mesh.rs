//! The files a TOML scene names: OBJ meshes placed by objects of type
//! `mesh` (read once, transformed into each instance) and NFF files merged by
//! `[[include]]`.

use std::collections::HashMap;
use std::path::{Path, PathBuf};

use glam::{DMat3, DMat4, DVec3, Vec3};
use toml::Spanned;

use super::build::Builder;
use super::defs::{IncludeDef, ObjectDef};
use crate::{nff, obj, spd, LoadError, Material, Object, ReadError, Shape, Light};

/// The OBJ files read so far, by canonical path.
#[derive(Default)]
pub(super) struct Meshes {
    cache: HashMap<PathBuf, CachedMesh>,
    pub(super) warnings: Vec<LoadError>,
}

pub(super) struct CachedMesh {
    mesh: obj::Mesh,
    /// Where the mesh's MTL materials start in the scene's materials, once an
    /// instance without a material override has added them.
    material_offset: Option<usize>,
}

impl Builder<'_> {
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

    pub(super) fn include(
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

    pub(super) fn mesh(
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
}
