//! The object types of a TOML scene and the keys each takes, both ways:
//! building one `[[object]]` (checking its keys, then making its shape or, for
//! an icosphere, its triangles), and the keys a shape is written back with.

use std::collections::BTreeMap;

use glam::Vec3;
use toml::Spanned;

use super::build::Builder;
use super::defs::ObjectDef;
use super::mesh::Meshes;
use super::values::Num;
use crate::icosphere;
use crate::shape::ShapeProblem;
use crate::{LoadError, Material, Object, Shape};

/// Each object type and the keys it takes besides `type` and `material`: what
/// checking an object and the errors about unknown keys both read.
const OBJECT_TYPES: [(&str, &[&str]); 8] = [
    ("sphere", &["center", "radius"]),
    ("triangle", &["vertices", "normals"]),
    ("polygon", &["vertices"]),
    ("plane", &["point", "normal", "size"]),
    ("cone", &["base", "base_radius", "apex", "apex_radius"]),
    ("cylinder", &["base", "base_radius", "apex", "apex_radius"]),
    ("mesh", &["path", "translate", "rotate", "scale", "matrix"]),
    ("icosphere", &["center", "radius", "subdivisions", "displacement"]),
];

/// Every object type, in the order errors list them.
pub fn object_types() -> impl Iterator<Item = &'static str> {
    OBJECT_TYPES.iter().map(|(name, _)| *name)
}

/// The keys an object of type `kind` takes besides `type` and `material`.
pub(super) fn object_keys(kind: &str) -> Option<&'static [&'static str]> {
    OBJECT_TYPES.iter().find(|(name, _)| *name == kind).map(|(_, keys)| *keys)
}

/// A value of an object's key, as `toml_write` writes it.
pub(crate) enum Written<'a> {
    Number(f32),
    Point(Vec3),
    Points(&'a [Vec3]),
}

/// The object type a shape is written as, and the values of its keys, named
/// from `OBJECT_TYPES` in their order (a key with no value is left out).
pub(crate) fn written_object(shape: &Shape) -> (&'static str, Vec<(&'static str, Written<'_>)>) {
    use Written::{Number, Point, Points};
    let (kind, values) = match shape {
        Shape::Sphere { center, radius } => ("sphere", vec![Some(Point(*center)), Some(Number(*radius))]),
        Shape::Triangle { vertices, normals } => ("triangle", vec![Some(Points(vertices)), normals.as_ref().map(|n| Points(n))]),
        Shape::Polygon { vertices } => ("polygon", vec![Some(Points(vertices))]),
        Shape::Cone { base, base_radius, apex, apex_radius } => {
            ("cone", vec![Some(Point(*base)), Some(Number(*base_radius)), Some(Point(*apex)), Some(Number(*apex_radius))])
        }
        // A plane with a `size` is stored, and so written, as its polygon.
        Shape::Plane { point, normal } => ("plane", vec![Some(Point(*point)), Some(Point(*normal))]),
    };
    let keys = object_keys(kind).expect("shapes are written as object types");
    (kind, keys.iter().zip(values).filter_map(|(key, value)| Some((*key, value?))).collect())
}

impl Builder<'_> {
    pub(super) fn object(
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
            Some(m) => Some(*names.get(m.get_ref().as_str()).ok_or_else(|| {
                let hint = crate::suggest::nearest(m.get_ref(), names.keys().copied()).map_or(String::new(), |n| format!("; did you mean `{n}`?"));
                self.error_at(m, format!("material: no material named `{}`{hint}", m.get_ref()))
            })?),
        };
        let material = named.unwrap_or(0);
        let kind = def.kind.get_ref().as_str();
        let Some(allowed) = object_keys(kind) else {
            let types: Vec<&str> = object_types().collect();
            let (last, others) = types.split_last().expect("there are object types");
            return Err(self.error_at(&def.kind, format!("type: unknown object type `{kind}`, expected {} or {last}", others.join(", "))));
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
            ("point", def.point.is_some()),
            ("normal", def.normal.is_some()),
            ("size", def.size.is_some()),
        ];
        if let Some((key, _)) = present.iter().find(|(k, p)| *p && !allowed.contains(k)) {
            return Err(self.error_at(object, format!("object: `{key}` does not apply to a {kind}")));
        }
        if kind == "mesh" {
            return self.mesh(object, named, materials, meshes, objects);
        }
        let missing = |key: &str| self.error_at(object, format!("object: a {kind} needs `{key}`"));
        let non_negative = |v: &Option<Spanned<Num>>, key: &str| -> Result<(f32, usize), LoadError> {
            let s = v.as_ref().ok_or_else(|| missing(key))?;
            if s.get_ref().0 >= 0.0 {
                Ok((s.get_ref().0, s.span().start))
            } else {
                Err(self.error_at(s, format!("{key}: must not be negative, found {}", s.get_ref().0)))
            }
        };
        if kind == "icosphere" {
            let center = def.center.ok_or_else(|| missing("center"))?.0;
            let (radius, radius_at) = non_negative(&def.radius, "radius")?;
            let s = def.subdivisions.as_ref().ok_or_else(|| missing("subdivisions"))?;
            let subdivisions = u32::try_from(*s.get_ref())
                .ok()
                .filter(|n| *n <= icosphere::MAX_SUBDIVISIONS)
                .ok_or_else(|| self.error_at(s, format!("subdivisions: {} is outside 0..={}", s.get_ref(), icosphere::MAX_SUBDIVISIONS)))?;
            let displacement = self.ranged(&def.displacement, "displacement", 0.0, 0.0, 0.5)?;
            if radius == 0.0 {
                // Degenerate like a sphere of radius 0: the same policy (crate::shape).
                self.warn_at_offset(radius_at, "icosphere of radius 0 skipped");
                return Ok(());
            }
            let shapes = icosphere::icosphere(center, radius, subdivisions, displacement);
            if !shapes.iter().all(Shape::is_finite) {
                return Err(self.error_at(object, "object: the icosphere reaches beyond the range of 32-bit floats"));
            }
            objects.push(Object { material, shapes });
            return Ok(());
        }
        // The shape, or why it is none, and where a warning about it points.
        let (built, at) = match kind {
            "sphere" => {
                let center = def.center.ok_or_else(|| missing("center"))?.0;
                let (radius, at) = non_negative(&def.radius, "radius")?;
                (Shape::sphere(center, radius), at)
            }
            "triangle" | "polygon" => {
                let vs = def.vertices.as_ref().ok_or_else(|| missing("vertices"))?;
                let vertices: Vec<Vec3> = vs.get_ref().iter().map(|v| v.0).collect();
                let expected = if kind == "triangle" { vertices.len() == 3 } else { vertices.len() >= 3 };
                if !expected {
                    let need = if kind == "triangle" { "exactly 3" } else { "at least 3" };
                    return Err(self.error_at(vs, format!("vertices: a {kind} needs {need} vertices, found {}", vertices.len())));
                }
                let built = if kind == "polygon" {
                    Shape::polygon(vertices).map(|(shape, non_planar)| {
                        if let Some(warning) = non_planar {
                            self.warn_at(vs, warning);
                        }
                        shape
                    })
                } else {
                    let normals = match &def.normals {
                        None => None,
                        Some(ns) if ns.get_ref().len() == 3 && ns.get_ref().iter().all(|n| crate::unit(n.0).is_some()) => {
                            Some([0, 1, 2].map(|i| crate::unit(ns.get_ref()[i].0).expect("checked")))
                        }
                        Some(ns) => return Err(self.error_at(ns, "normals: a triangle needs 3 non-zero normals")),
                    };
                    Shape::triangle([vertices[0], vertices[1], vertices[2]], normals)
                };
                (built, vs.span().start)
            }
            "plane" => {
                let point = def.point.ok_or_else(|| missing("point"))?.0;
                let n = def.normal.as_ref().ok_or_else(|| missing("normal"))?;
                let normal = crate::unit(n.get_ref().0).ok_or_else(|| self.error_at(n, "normal: must not be zero"))?;
                match &def.size {
                    None => (Shape::plane(point, normal), object.span().start),
                    Some(size) => {
                        let sides = size.get_ref().0;
                        if let Some(side) = sides.iter().find(|s| **s < 0.0) {
                            return Err(self.error_at(size, format!("size: must not be negative, found {side}")));
                        }
                        (Shape::rectangle(point, normal, sides), size.span().start)
                    }
                }
            }
            _ => {
                let base = def.base.ok_or_else(|| missing("base"))?.0;
                let apex = def.apex.ok_or_else(|| missing("apex"))?.0;
                let (base_radius, _) = non_negative(&def.base_radius, "base_radius")?;
                let apex_radius = if kind == "cylinder" && def.apex_radius.is_none() {
                    base_radius
                } else {
                    non_negative(&def.apex_radius, "apex_radius")?.0
                };
                (Shape::cone(base, base_radius, apex, apex_radius), object.span().start)
            }
        };
        let shape = match built {
            Ok(shape) => shape,
            Err(ShapeProblem::Degenerate(warning)) => {
                self.warn_at_offset(at, warning);
                return Ok(());
            }
            Err(ShapeProblem::Overflows) => {
                return Err(self.error_at(object, format!("object: the {kind} reaches beyond the range of 32-bit floats")));
            }
        };
        objects.push(Object { material, shapes: vec![shape] });
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use std::collections::BTreeSet;

    use super::{ObjectDef, OBJECT_TYPES};

    /// The types take, between them, exactly the keys an object can hold.
    #[test]
    fn the_types_take_exactly_the_keys_an_object_holds() {
        let taken: BTreeSet<&str> = OBJECT_TYPES.iter().flat_map(|(_, keys)| keys.iter().copied()).chain(["type", "material"]).collect();
        let held: BTreeSet<&str> = crate::toml_errors::fields_of::<ObjectDef>().iter().copied().collect();
        assert_eq!(taken, held);
    }
}
