//! What a kernel is compiled for. A software rasteriser compiles each kernel
//! to CPU code when it is first used, and the time it takes grows with the code
//! it is given: a kernel specialised to a scene carries no intersection code for
//! primitive kinds the scene does not hold (the kinds become `const` flags in
//! the kernel's prelude, whose dead branches the driver's compiler removes
//! before it generates code).

use crate::gpu_types::{GpuPrim, PRIM_CONE, PRIM_PLANE, PRIM_POLYGON, PRIM_SPHERE, PRIM_TRIANGLE};

/// The primitive kinds a kernel can intersect.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub struct Specialization {
    pub spheres: bool,
    pub triangles: bool,
    pub polygons: bool,
    pub cones: bool,
    pub planes: bool,
}

impl Specialization {
    /// Every kind: for a kernel that must serve any scene.
    pub const ALL: Specialization = Specialization { spheres: true, triangles: true, polygons: true, cones: true, planes: true };

    /// The kinds among `prims`.
    pub fn of(prims: &[GpuPrim]) -> Specialization {
        let mut kinds = Specialization { spheres: false, triangles: false, polygons: false, cones: false, planes: false };
        for p in prims {
            match p.kind() {
                PRIM_SPHERE => kinds.spheres = true,
                PRIM_TRIANGLE => kinds.triangles = true,
                PRIM_POLYGON => kinds.polygons = true,
                PRIM_CONE => kinds.cones = true,
                PRIM_PLANE => kinds.planes = true,
                other => unreachable!("primitive kind {other} is not packed by gpu_types"),
            }
        }
        kinds
    }

    fn flags(self) -> [(&'static str, bool); 5] {
        [
            ("HAS_SPHERES", self.spheres),
            ("HAS_TRIANGLES", self.triangles),
            ("HAS_POLYGONS", self.polygons),
            ("HAS_CONES", self.cones),
            ("HAS_PLANES", self.planes),
        ]
    }

    /// The WGSL constants that carry it, appended to a kernel's prelude.
    pub fn wgsl(self) -> String {
        self.flags().iter().map(|(name, on)| format!("const {name}: bool = {on};\n")).collect()
    }
}

impl std::fmt::Display for Specialization {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        let names = [
            ("spheres", self.spheres),
            ("triangles", self.triangles),
            ("polygons", self.polygons),
            ("cones", self.cones),
            ("planes", self.planes),
        ];
        let kinds: Vec<&str> = names.iter().filter(|(_, on)| *on).map(|(name, _)| *name).collect();
        if kinds.is_empty() {
            f.write_str("no primitives")
        } else {
            f.write_str(&kinds.join("+"))
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use bytemuck::Zeroable;

    fn prim(kind: u32) -> GpuPrim {
        GpuPrim { kind_material: kind | (7 << 8), ..GpuPrim::zeroed() }
    }

    #[test]
    fn a_scene_specialises_to_the_kinds_it_holds() {
        let kinds = Specialization::of(&[prim(PRIM_TRIANGLE), prim(PRIM_CONE), prim(PRIM_TRIANGLE)]);
        assert_eq!(kinds, Specialization { spheres: false, triangles: true, polygons: false, cones: true, planes: false });
        assert_eq!(kinds.to_string(), "triangles+cones");
        let every = [PRIM_SPHERE, PRIM_POLYGON, PRIM_TRIANGLE, PRIM_CONE, PRIM_PLANE].map(prim);
        assert_eq!(Specialization::of(&every), Specialization::ALL);
    }

    #[test]
    fn every_flag_is_a_wgsl_constant() {
        let wgsl = Specialization::of(&[prim(PRIM_SPHERE)]).wgsl();
        assert!(wgsl.contains("const HAS_SPHERES: bool = true;"));
        for name in ["HAS_TRIANGLES", "HAS_POLYGONS", "HAS_CONES", "HAS_PLANES"] {
            assert!(wgsl.contains(&format!("const {name}: bool = false;")), "{wgsl}");
        }
    }
}
