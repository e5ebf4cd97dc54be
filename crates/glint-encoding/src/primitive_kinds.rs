//! The registry of primitive kinds: the one list of what each kind is called
//! in the kernels, and the record (`GpuPrim`) each shape is packed into. Its
//! `PRIM_` codes and `HAS_` flags reach WGSL through the prelude
//! (`gpu_types::wgsl_prelude`, `Specialization::wgsl`), and the kernels'
//! dispatch on the kind (glint-gpu's primitive_dispatch.rs) is generated from it.
//! A kind missing here is a miss and a zero normal in the kernels, never
//! another kind's code.

use bytemuck::{Pod, Zeroable};
use glam::Vec3;
use glint_scene::{plane_axes, polygon_normal, Shape};

/// What a kind's intersection takes besides the primitive and the interval.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Inputs {
    /// The ray (`Ray`, or `Rays4` for a packet).
    Ray,
    /// The ray's frame the caller makes once per ray (`RayFrame`, `RayFrame4`).
    Frame,
    Both,
}

/// One primitive kind, as the kernels name it.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct PrimitiveKind {
    /// Its `PRIM_` code: what `prim_kind` returns for it.
    pub code: u32,
    /// The code's constant, in Rust and WGSL.
    pub code_name: &'static str,
    /// The `HAS_` flag of a kernel specialised to scenes that hold it.
    pub flag: &'static str,
    /// The file that holds its intersection and normal, relative to `shaders/`.
    pub file: &'static str,
    /// `fn(GpuPrim, inputs, t_min, t_max) -> f32`: the closest hit, or MISS.
    pub intersect: &'static str,
    pub inputs: Inputs,
    /// Its geometric normal: `fn(GpuPrim) -> vec3<f32>`, or with `at_point`
    /// `fn(GpuPrim, vec3<f32>) -> vec3<f32>`.
    pub normal: &'static str,
    pub normal_at_point: bool,
    /// An interpolated shading normal, `fn(GpuPrim, vec3<f32>) -> vec3<f32>`,
    /// where it differs from the geometric one.
    pub shading_normal: Option<&'static str>,
    /// Whether it has finite bounds, so that it goes into the BVH; an
    /// unbounded kind (the plane) is tested by every ray before the walk.
    pub bounded: bool,
    /// The test of a packet's four rays at once (packet.wgsl), if it has one;
    /// without it the packet tests its rays one at a time.
    pub packet_intersect: Option<&'static str>,
}

/// Declares each kind's code as a Rust constant and lists the kinds, in the
/// order of their codes (and of the kernels' dispatch).
macro_rules! primitive_kinds {
    ($($code_name:ident = $code:literal { $($field:ident: $value:expr),* $(,)? })*) => {
        $(pub const $code_name: u32 = $code;)*

        /// Every kind, indexed by its code.
        pub const KINDS: &[PrimitiveKind] = &[$(PrimitiveKind { code: $code, code_name: stringify!($code_name), $($field: $value),* }),*];
    };
}

primitive_kinds! {
    PRIM_SPHERE = 0 {
        flag: "HAS_SPHERES",
        file: "lib/sphere.wgsl",
        intersect: "sphere_intersect",
        inputs: Inputs::Ray,
        normal: "sphere_normal",
        normal_at_point: true,
        shading_normal: None,
        bounded: true,
        packet_intersect: None,
    }
    PRIM_TRIANGLE = 1 {
        flag: "HAS_TRIANGLES",
        file: "lib/triangle.wgsl",
        intersect: "triangle_intersect",
        inputs: Inputs::Frame,
        normal: "triangle_geometric_normal",
        normal_at_point: false,
        shading_normal: Some("triangle_shading_normal"),
        bounded: true,
        packet_intersect: Some("triangle_intersect4"),
    }
    PRIM_POLYGON = 2 {
        flag: "HAS_POLYGONS",
        file: "lib/polygon.wgsl",
        intersect: "polygon_intersect",
        inputs: Inputs::Both,
        // A polygon is flat: its plane's normal.
        normal: "plane_normal",
        normal_at_point: false,
        shading_normal: None,
        bounded: true,
        packet_intersect: Some("polygon_intersect4"),
    }
    PRIM_CONE = 3 {
        flag: "HAS_CONES",
        file: "lib/cone.wgsl",
        intersect: "cone_intersect",
        inputs: Inputs::Ray,
        normal: "cone_normal",
        normal_at_point: true,
        shading_normal: None,
        bounded: true,
        packet_intersect: None,
    }
    PRIM_PLANE = 4 {
        flag: "HAS_PLANES",
        file: "lib/plane.wgsl",
        intersect: "plane_intersect",
        inputs: Inputs::Ray,
        normal: "plane_normal",
        normal_at_point: false,
        shading_normal: None,
        bounded: false,
        packet_intersect: Some("plane_intersect4"),
    }
}

/// The kind of `code`, if it is one.
pub fn kind(code: u32) -> Option<&'static PrimitiveKind> {
    KINDS.get(code as usize)
}

/// A set of kinds: bit `code` for each kind it holds.
pub const ALL_KINDS: u32 = (1 << KINDS.len()) - 1;

/// The WGSL constants of the kinds' codes, for the prelude.
pub fn wgsl_codes() -> String {
    KINDS.iter().map(|k| format!("const {}: u32 = {}u;\n", k.code_name, k.code)).collect()
}

/// One primitive, 64 bytes; what `a`, `b`, `c` hold depends on the kind:
/// sphere a = (centre, radius); triangle a, b, c = vertices, `first` = index of
/// its three vertex normals when `count` = 3; polygon a = (unit normal, n·v0),
/// b and c = the plane's axes u and v (`plane_axes`, for the checker),
/// vertices[first .. first + count]; cone a = (base, base radius), b = (apex,
/// apex radius); infinite plane a = (unit normal, n·p), b and c = u and v.
#[repr(C)]
#[derive(Debug, Clone, Copy, PartialEq, Pod, Zeroable)]
pub struct GpuPrim {
    pub a: [f32; 4],
    pub b: [f32; 4],
    pub c: [f32; 4],
    /// kind in the low 8 bits, material index above.
    pub kind_material: u32,
    pub object: u32,
    pub first: u32,
    pub count: u32,
}

impl GpuPrim {
    /// `shape`, of `object` and with `material`, as the kernels read it. A
    /// polygon's vertices and a smooth triangle's normals go on `points`.
    pub fn pack(shape: &Shape, object: u32, material: usize, points: &mut Vec<[f32; 4]>) -> GpuPrim {
        let mut p = GpuPrim { object, kind_material: (material as u32) << 8, ..Zeroable::zeroed() };
        match shape {
            Shape::Sphere { center, radius } => {
                p.kind_material |= PRIM_SPHERE;
                p.a = v4(*center, *radius);
            }
            Shape::Triangle { vertices, normals } => {
                p.kind_material |= PRIM_TRIANGLE;
                (p.a, p.b, p.c) = (v4(vertices[0], 0.0), v4(vertices[1], 0.0), v4(vertices[2], 0.0));
                if let Some(ns) = normals {
                    p.first = points.len() as u32;
                    p.count = 3;
                    points.extend(ns.iter().map(|n| v4(*n, 0.0)));
                }
            }
            Shape::Polygon { vertices } => {
                p.kind_material |= PRIM_POLYGON;
                let n = polygon_normal(vertices).unwrap_or(Vec3::Z);
                p.a = v4(n, n.dot(vertices[0]));
                (p.b, p.c) = axes(n);
                p.first = points.len() as u32;
                p.count = vertices.len() as u32;
                points.extend(vertices.iter().map(|v| v4(*v, 0.0)));
            }
            Shape::Cone { base, base_radius, apex, apex_radius } => {
                p.kind_material |= PRIM_CONE;
                p.a = v4(*base, *base_radius);
                p.b = v4(*apex, *apex_radius);
            }
            Shape::Plane { point, normal } => {
                p.kind_material |= PRIM_PLANE;
                p.a = v4(*normal, normal.dot(*point));
                (p.b, p.c) = axes(*normal);
            }
        }
        p
    }

    /// The `PRIM_` kind (WGSL `prim_kind`).
    pub fn kind(&self) -> u32 {
        self.kind_material & 0xff
    }

    /// Index of its material (WGSL `prim_material`).
    pub fn material(&self) -> usize {
        (self.kind_material >> 8) as usize
    }
}

fn v4(v: Vec3, w: f32) -> [f32; 4] {
    [v.x, v.y, v.z, w]
}

/// The axes u and v of the plane of unit `normal`, for the checker.
fn axes(normal: Vec3) -> ([f32; 4], [f32; 4]) {
    let [u, v] = plane_axes(normal.as_dvec3());
    (v4(u.as_vec3(), 0.0), v4(v.as_vec3(), 0.0))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn each_kind_sits_at_its_code_with_names_of_its_own() {
        for (i, k) in KINDS.iter().enumerate() {
            assert_eq!(k.code as usize, i, "{}", k.code_name);
            assert_eq!(kind(k.code), Some(k));
            for other in &KINDS[..i] {
                assert!(k.code_name != other.code_name && k.flag != other.flag && k.intersect != other.intersect, "{}", k.code_name);
            }
        }
        assert_eq!(kind(KINDS.len() as u32), None);
    }

    /// Every registered kind is packed from a shape, and each shape has the
    /// one name every tool shows it by (`Shape::name`).
    #[test]
    fn every_registered_kind_is_packed_from_a_shape_with_a_name() {
        let shapes = [
            Shape::sphere(Vec3::ZERO, 1.0),
            Shape::triangle([Vec3::ZERO, Vec3::X, Vec3::Y], None),
            Shape::polygon(vec![Vec3::ZERO, Vec3::X, Vec3::new(1.0, 1.0, 0.0), Vec3::Y]).map(|(shape, _)| shape),
            Shape::cone(Vec3::ZERO, 1.0, Vec3::Y, 0.5),
            Shape::cone(Vec3::ZERO, 1.0, Vec3::Y, 1.0),
            Shape::plane(Vec3::ZERO, Vec3::Y),
        ]
        .map(Result::unwrap);
        assert_eq!(shapes.iter().map(Shape::name).collect::<Vec<_>>(), glint_scene::SHAPE_NAMES);
        let mut points = Vec::new();
        let packed: Vec<GpuPrim> = shapes.iter().map(|shape| GpuPrim::pack(shape, 0, 0, &mut points)).collect();
        for kind in KINDS {
            assert!(packed.iter().any(|p| p.kind() == kind.code), "no shape is packed as {}", kind.code_name);
        }
    }
}
