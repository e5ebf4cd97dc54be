//! The registry of primitive kinds: the one list of what each kind is called
//! in the kernels. Its `PRIM_` codes and `HAS_` flags reach WGSL through the
//! prelude (`gpu_types::wgsl_prelude`, `Specialization::wgsl`), and the kernels'
//! dispatch on the kind (glint-gpu's primitive_dispatch.rs) is generated from it.
//! A kind missing here is a miss and a zero normal in the kernels, never
//! another kind's code.

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
}
