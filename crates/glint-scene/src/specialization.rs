//! What a kernel is compiled for. A software rasteriser compiles each kernel
//! to CPU code when it is first used, and the time it takes grows with the code
//! it is given: a kernel specialised to a scene carries no intersection code for
//! primitive kinds the scene does not hold, and no reflected or refracted rays
//! when no material makes any, and, for a command that renders one view, no
//! code of the others (each becomes a `const` in the kernel's prelude, whose
//! dead branches the driver's compiler removes before it generates code).

use crate::gpu_types::{GpuMaterial, GpuScene, View, ANY_VIEW, PRIM_CONE, PRIM_PLANE, PRIM_POLYGON, PRIM_SPHERE, PRIM_TRIANGLE};

/// The primitive kinds a kernel can intersect, whether its ray tree goes past
/// the eye ray, and the view it renders.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub struct Specialization {
    pub spheres: bool,
    pub triangles: bool,
    pub polygons: bool,
    pub cones: bool,
    pub planes: bool,
    /// Some material reflects or transmits, so rays may spawn reflected and
    /// refracted rays.
    pub secondary_rays: bool,
    /// The one view every dispatch renders, or `None`: each dispatch says
    /// (the viewer's kernels, a render that writes AOVs besides its image).
    pub view: Option<View>,
}

impl Specialization {
    /// Everything: for a kernel that must serve any scene.
    pub const ALL: Specialization = Specialization {
        spheres: true,
        triangles: true,
        polygons: true,
        cones: true,
        planes: true,
        secondary_rays: true,
        view: None,
    };

    /// What `scene` needs.
    pub fn of(scene: &GpuScene) -> Specialization {
        let mut needs = Specialization {
            spheres: false,
            triangles: false,
            polygons: false,
            cones: false,
            planes: false,
            secondary_rays: scene.materials.iter().any(spawns_secondary_rays),
            view: None,
        };
        for p in &scene.prims {
            match p.kind() {
                PRIM_SPHERE => needs.spheres = true,
                PRIM_TRIANGLE => needs.triangles = true,
                PRIM_POLYGON => needs.polygons = true,
                PRIM_CONE => needs.cones = true,
                PRIM_PLANE => needs.planes = true,
                other => unreachable!("primitive kind {other} is not packed by gpu_types"),
            }
        }
        needs
    }

    /// The same kinds, with secondary rays whatever the materials: for a scene
    /// whose materials change in place (the viewer's).
    pub fn with_secondary_rays(self) -> Specialization {
        Specialization { secondary_rays: true, ..self }
    }

    /// Specialised to `views`, the views a command renders, when it is one
    /// view: its kernel then compiles that view's code alone. With several,
    /// one kernel that serves them all compiles sooner than one per view.
    pub fn for_views(self, views: &[View]) -> Specialization {
        let one = views.split_first().filter(|(first, rest)| rest.iter().all(|v| v == *first));
        Specialization { view: one.map(|(&view, _)| view), ..self }
    }

    /// The specialisation a dispatch of `view` runs: this one when it is for
    /// that view or any, else the same kinds for any view.
    pub fn dispatching(self, view: View) -> Specialization {
        if self.view.is_none_or(|only| only == view) { self } else { Specialization { view: None, ..self } }
    }

    /// Whether a kernel of this specialisation renders `materials` rightly.
    pub fn covers(self, materials: &[GpuMaterial]) -> bool {
        self.secondary_rays || !materials.iter().any(spawns_secondary_rays)
    }

    fn flags(self) -> [(&'static str, bool); 6] {
        [
            ("HAS_SPHERES", self.spheres),
            ("HAS_TRIANGLES", self.triangles),
            ("HAS_POLYGONS", self.polygons),
            ("HAS_CONES", self.cones),
            ("HAS_PLANES", self.planes),
            ("HAS_SECONDARY_RAYS", self.secondary_rays),
        ]
    }

    /// The WGSL constants that carry it, appended to a kernel's prelude.
    pub fn wgsl(self) -> String {
        let mut wgsl: String = self.flags().iter().map(|(name, on)| format!("const {name}: bool = {on};\n")).collect();
        wgsl.push_str(&format!("const ONLY_VIEW: u32 = {}u;\n", self.view.map_or(ANY_VIEW, |view| view as u32)));
        wgsl
    }
}

fn spawns_secondary_rays(m: &GpuMaterial) -> bool {
    m.reflect.iter().chain(&m.transmit).any(|&k| k > 0.0)
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
        f.write_str(if kinds.is_empty() { "no primitives".to_string() } else { kinds.join("+") }.as_str())?;
        if !self.secondary_rays {
            f.write_str(", eye rays only")?;
        }
        if let Some(view) = self.view {
            write!(f, ", {} view only", format!("{view:?}").to_lowercase())?;
        }
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::gpu_types::GpuPrim;
    use bytemuck::Zeroable;

    fn scene(kinds: &[u32], reflect: f32) -> GpuScene {
        GpuScene {
            prims: kinds.iter().map(|&kind| GpuPrim { kind_material: kind | (7 << 8), ..GpuPrim::zeroed() }).collect(),
            nodes: Vec::new(),
            grids: Vec::new(),
            bvh_root: 0,
            materials: vec![GpuMaterial { reflect: [0.0, reflect, 0.0], ..GpuMaterial::zeroed() }],
            lights: Vec::new(),
            points: Vec::new(),
            light_count: 0,
        }
    }

    #[test]
    fn a_scene_specialises_to_the_kinds_it_holds() {
        let needs = Specialization::of(&scene(&[PRIM_TRIANGLE, PRIM_CONE, PRIM_TRIANGLE], 0.5));
        let want = Specialization {
            spheres: false,
            triangles: true,
            polygons: false,
            cones: true,
            planes: false,
            secondary_rays: true,
            view: None,
        };
        assert_eq!(needs, want);
        assert_eq!(needs.to_string(), "triangles+cones");
        let every = scene(&[PRIM_SPHERE, PRIM_POLYGON, PRIM_TRIANGLE, PRIM_CONE, PRIM_PLANE], 1.0);
        assert_eq!(Specialization::of(&every), Specialization::ALL);
    }

    #[test]
    fn matte_scenes_trace_eye_rays_only_unless_their_materials_may_change() {
        let matte = Specialization::of(&scene(&[PRIM_SPHERE], 0.0));
        assert!(!matte.secondary_rays);
        assert_eq!(matte.to_string(), "spheres, eye rays only");
        let glass = [GpuMaterial { transmit: [0.0, 0.0, 0.9], ..GpuMaterial::zeroed() }];
        assert!(!matte.covers(&glass) && matte.covers(&[GpuMaterial::zeroed()]));
        assert!(matte.with_secondary_rays().covers(&glass));
    }

    #[test]
    fn every_flag_is_a_wgsl_constant() {
        let wgsl = Specialization::of(&scene(&[PRIM_SPHERE], 0.0)).wgsl();
        assert!(wgsl.contains("const HAS_SPHERES: bool = true;"));
        for name in ["HAS_TRIANGLES", "HAS_POLYGONS", "HAS_CONES", "HAS_PLANES", "HAS_SECONDARY_RAYS"] {
            assert!(wgsl.contains(&format!("const {name}: bool = false;")), "{wgsl}");
        }
    }

    #[test]
    fn a_command_of_one_view_specialises_to_it_and_other_dispatches_get_any_view() {
        let kinds = Specialization::of(&scene(&[PRIM_TRIANGLE], 0.0));
        let depth = kinds.for_views(&[View::Depth, View::Depth]);
        assert_eq!(depth.view, Some(View::Depth));
        assert_eq!(depth.to_string(), "triangles, eye rays only, depth view only");
        assert_eq!(kinds.for_views(&[View::Depth, View::Normal]), kinds);
        assert_eq!(depth.dispatching(View::Depth), depth);
        assert_eq!(depth.dispatching(View::Normal), kinds);
        assert_eq!(kinds.dispatching(View::Normal), kinds);
        assert!(depth.wgsl().contains(&format!("const ONLY_VIEW: u32 = {}u;", View::Depth as u32)));
        assert!(kinds.wgsl().contains(&format!("const ONLY_VIEW: u32 = {ANY_VIEW}u;")));
    }
}
