//! What the kernels rely on and do not check: the embedded kernels run without
//! bounds checks, so every index they follow and every count they loop to is
//! checked here, on the host, before anything is uploaded. A violation is an
//! error naming the problem, never a panic and never an out-of-bounds access.

use crate::bvh::{Bvh, MAX_DEPTH as BVH_STACK};
use crate::{Scene, Shape, MAX_DEPTH_LIMIT, MAX_LIGHTS, MAX_MATERIALS};

/// A scene the kernels cannot be given.
#[derive(Debug, Clone, PartialEq, Eq, thiserror::Error)]
pub enum Invalid {
    #[error("object {object} uses material {material}, but the scene has {count} materials")]
    MaterialIndex { object: usize, material: usize, count: usize },
    #[error("object {object}: a polygon needs at least 3 vertices, not {count}")]
    PolygonVertices { object: usize, count: usize },
    #[error("object {object}: a plane's normal must be a unit vector")]
    PlaneNormal { object: usize },
    #[error("material {material}: a checker's tiles must have a positive, finite size")]
    CheckerSize { material: usize },
    #[error("the scene has {count} {what}; the kernels index at most {max}")]
    TooMany { what: &'static str, count: usize, max: usize },
    #[error("a maximum ray depth of {0} does not fit the kernel's ray stack (1 to {MAX_DEPTH_LIMIT})")]
    MaxDepth(u32),
    #[error("the BVH is {0} levels deep; traversal's stack holds {BVH_STACK}")]
    TooDeep(usize),
}

impl Scene {
    /// Checks every invariant of the scene itself that the kernels assume.
    pub fn validate(&self) -> Result<(), Invalid> {
        if !(1..=MAX_DEPTH_LIMIT).contains(&self.render.max_depth) {
            return Err(Invalid::MaxDepth(self.render.max_depth));
        }
        if self.materials.len() > MAX_MATERIALS as usize {
            return Err(Invalid::TooMany { what: "materials", count: self.materials.len(), max: MAX_MATERIALS as usize });
        }
        for (material, m) in self.materials.iter().enumerate() {
            if m.checker.is_some_and(|c| !(c.size > 0.0 && c.size.is_finite())) {
                return Err(Invalid::CheckerSize { material });
            }
        }
        // Every light, on or off: the viewer turns them on in place.
        if self.lights.len() > MAX_LIGHTS as usize {
            return Err(Invalid::TooMany { what: "lights", count: self.lights.len(), max: MAX_LIGHTS as usize });
        }
        let object_limit = u32::MAX as usize;
        if self.objects.len() > object_limit {
            return Err(Invalid::TooMany { what: "objects", count: self.objects.len(), max: object_limit });
        }
        let mut primitives = 0usize;
        let mut points = 0usize;
        for (object, o) in self.objects.iter().enumerate() {
            if o.material >= self.materials.len() {
                return Err(Invalid::MaterialIndex { object, material: o.material, count: self.materials.len() });
            }
            primitives += o.shapes.len();
            for shape in &o.shapes {
                match shape {
                    Shape::Polygon { vertices } if vertices.len() < 3 => {
                        return Err(Invalid::PolygonVertices { object, count: vertices.len() });
                    }
                    Shape::Polygon { vertices } => points += vertices.len(),
                    // The kernels shade with it as it is.
                    Shape::Plane { normal, .. } if !normal.is_finite() || (normal.length() - 1.0).abs() >= 1e-3 => {
                        return Err(Invalid::PlaneNormal { object });
                    }
                    Shape::Triangle { normals: Some(_), .. } => points += 3,
                    _ => {}
                }
            }
        }
        // Leaves address primitives and primitives address points with u32s.
        let index_limit = u32::MAX as usize;
        if primitives > index_limit {
            return Err(Invalid::TooMany { what: "primitives", count: primitives, max: index_limit });
        }
        if points > index_limit {
            return Err(Invalid::TooMany { what: "polygon vertices and vertex normals", count: points, max: index_limit });
        }
        Ok(())
    }
}

impl Bvh {
    /// Checks that the tree fits the kernel's traversal stack, which the
    /// builder's depth bound sizes (glint-encoding checks its record count).
    pub fn validate(&self) -> Result<(), Invalid> {
        if self.depth() > BVH_STACK {
            return Err(Invalid::TooDeep(self.depth()));
        }
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::{Camera, Material, Object, Projection, RenderSettings};
    use glam::Vec3;

    fn scene(objects: Vec<Object>, materials: usize) -> Scene {
        Scene {
            width: 8,
            height: 8,
            background: Vec3::ZERO,
            camera: Camera { eye: Vec3::Z, look_at: Vec3::ZERO, up: Vec3::Y, projection: Projection::Perspective { fov_y_degrees: 40.0 } },
            ambient: Vec3::ZERO,
            lights: Vec::new(),
            materials: vec![Material::default(); materials],
            objects,
            depth_cue: None,
            render: RenderSettings::default(),
            animation: None,
            warnings: Vec::new(),
        }
    }

    fn sphere(material: usize) -> Object {
        Object { material, shapes: vec![Shape::Sphere { center: Vec3::ZERO, radius: 1.0 }] }
    }

    #[test]
    fn each_broken_invariant_is_an_error() {
        assert_eq!(scene(vec![sphere(0)], 1).validate(), Ok(()));
        assert_eq!(scene(Vec::new(), 0).validate(), Ok(()), "an empty scene is fine: packing pads its arrays");
        assert_eq!(
            scene(vec![sphere(0), sphere(2)], 2).validate(),
            Err(Invalid::MaterialIndex { object: 1, material: 2, count: 2 })
        );
        let two_vertices = Object { material: 0, shapes: vec![Shape::Polygon { vertices: vec![Vec3::ZERO, Vec3::X] }] };
        assert_eq!(scene(vec![two_vertices], 1).validate(), Err(Invalid::PolygonVertices { object: 0, count: 2 }));
        let plane = |normal| Object { material: 0, shapes: vec![Shape::Plane { point: Vec3::ZERO, normal }] };
        assert_eq!(scene(vec![plane(Vec3::Y), sphere(0)], 1).validate(), Ok(()));
        assert_eq!(scene(vec![plane(Vec3::ZERO)], 1).validate(), Err(Invalid::PlaneNormal { object: 0 }));
        let mut checkered = scene(vec![sphere(0)], 2);
        checkered.materials[1].checker = Some(crate::Checker { color: Vec3::ONE, size: 0.0 });
        assert_eq!(checkered.validate(), Err(Invalid::CheckerSize { material: 1 }));
        for depth in [0, MAX_DEPTH_LIMIT + 1] {
            let mut s = scene(vec![sphere(0)], 1);
            s.render.max_depth = depth;
            assert_eq!(s.validate(), Err(Invalid::MaxDepth(depth)));
        }
        let light = crate::Light {
            kind: crate::LightKind::Point { position: Vec3::Y },
            color: Vec3::ONE,
            intensity: 1.0,
            attenuation: crate::Attenuation::None,
            enabled: false,
        };
        let mut lit = scene(vec![sphere(0)], 1);
        lit.lights = vec![light; MAX_LIGHTS as usize];
        assert_eq!(lit.validate(), Ok(()));
        lit.lights.push(light);
        let too_many = Invalid::TooMany { what: "lights", count: MAX_LIGHTS as usize + 1, max: MAX_LIGHTS as usize };
        assert_eq!(lit.validate(), Err(too_many), "lights count whether on or off");
        let mut painted = scene(vec![sphere(0)], MAX_MATERIALS as usize);
        assert_eq!(painted.validate(), Ok(()));
        painted.materials.push(crate::Material::default());
        let too_many = Invalid::TooMany { what: "materials", count: MAX_MATERIALS as usize + 1, max: MAX_MATERIALS as usize };
        assert_eq!(painted.validate(), Err(too_many));
        let message = Invalid::MaterialIndex { object: 1, material: 2, count: 2 }.to_string();
        assert_eq!(message, "object 1 uses material 2, but the scene has 2 materials");
    }

    #[test]
    fn a_tree_deeper_than_the_stack_is_an_error_not_a_panic() {
        // A chain: every interior node's second child is the next interior node.
        let levels = BVH_STACK + 8;
        let node = |left_or_first: u32, count: u32| crate::bvh::Node { min: [0.0; 3], left_or_first, max: [1.0; 3], count };
        let mut nodes = Vec::new();
        for level in 0..levels as u32 {
            if level > 0 {
                nodes.push(node(0, 1));
            }
            nodes.push(node(2 * level + 1, 0));
        }
        nodes.push(node(0, 1));
        nodes.push(node(0, 1));
        let bvh = Bvh { nodes, order: vec![0] };
        assert!(bvh.depth() > BVH_STACK);
        assert_eq!(bvh.validate(), Err(Invalid::TooDeep(bvh.depth())));
    }
}
