//! What a scene needs its kernels to hold, the scene's half of what a kernel
//! is compiled for (how the kernels are tuned for the device is the other
//! half: glint-gpu's `Tuning`). A software rasteriser compiles each kernel
//! to CPU code when it is first used, and the time it takes grows with the code
//! it is given: a kernel specialised to a scene carries no intersection code for
//! primitive kinds the scene does not hold, no interpolated normals when no
//! triangle has vertex normals, no reflected or refracted rays when no
//! material makes any, no refraction when none transmits, no highlight,
//! checkerboard, light falloff, tinted shadow or depth cue when the scene has
//! none, no unturned normals unless grading's diagnosis asks for them, and,
//! for a command that renders one view, no code
//! of the others (each becomes a `const` in the kernel's prelude, whose dead
//! branches the driver's compiler removes before it generates code).

use glint_scene::MAX_DEPTH_LIMIT;

use crate::gpu_types::{
    GpuLight, GpuMaterial, GpuScene, SceneUniforms, View, ANY_VIEW, ATTENUATION_NONE, FLAG_DEPTH_CUE, FLAG_TINTED_SHADOWS, FLAG_UNTURNED_NORMALS,
    MATERIAL_CHECKER, MATERIAL_METALLIC, PRIM_TRIANGLE,
};
use crate::primitive_kinds::{self, ALL_KINDS, KINDS};

/// The primitive kinds a kernel can intersect, whether its ray tree goes past
/// the eye ray, the terms its shading can have, and the view it renders.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub struct Specialization {
    /// The primitive kinds: bit `code` for each (primitive_kinds.rs).
    pub kinds: u32,
    /// Some triangle interpolates vertex normals (NFF `pp`, OBJ `vn`).
    pub smooth_triangles: bool,
    /// Some material reflects or transmits, so rays may spawn reflected and
    /// refracted rays.
    pub secondary_rays: bool,
    /// Some material transmits, so rays may refract and shadows be tinted.
    pub refractions: bool,
    /// Some material has a highlight (k_s > 0, or a metallic F0).
    pub highlights: bool,
    /// Some material is checkered.
    pub checker: bool,
    /// Some light fades with distance.
    pub attenuation: bool,
    /// Shadows are tinted by the transmitters they pass (`shadows = "tinted"`).
    pub tinted_shadows: bool,
    /// The scene has depth cueing.
    pub depth_cue: bool,
    /// Lighting takes the normals unturned (`turn_normals` off: grading's
    /// diagnosis of a student's bug).
    pub unturned_normals: bool,
    /// The one view every dispatch renders, or `None`: each dispatch says
    /// (the viewer's kernels, a render that writes AOVs besides its image).
    pub view: Option<View>,
    /// The deepest ray tree the kernel traces (`uniforms.max_depth` may be no
    /// more): its stack of pending rays holds that many, each of them zeroed
    /// when a pixel starts, so a shallower tree compiles less.
    pub max_depth: u32,
}

impl Specialization {
    /// Everything: for a kernel that must serve any scene.
    pub const ALL: Specialization = Specialization {
        kinds: ALL_KINDS,
        smooth_triangles: true,
        secondary_rays: true,
        refractions: true,
        highlights: true,
        checker: true,
        attenuation: true,
        tinted_shadows: true,
        depth_cue: true,
        unturned_normals: true,
        view: None,
        max_depth: MAX_DEPTH_LIMIT,
    };

    /// What `scene` needs: its primitives' kinds, the terms of the materials
    /// they use (a loader's default material may be unused), its lights' and
    /// those its render settings turn on (`uniforms`).
    pub fn of(scene: &GpuScene, uniforms: &SceneUniforms) -> Specialization {
        let mut used = vec![false; scene.materials.len()];
        for p in &scene.prims {
            used[p.material()] = true;
        }
        let materials = || scene.materials.iter().zip(&used).filter(|(_, used)| **used).map(|(m, _)| m);
        let mut needs = Specialization {
            kinds: 0,
            smooth_triangles: false,
            secondary_rays: materials().any(spawns_secondary_rays),
            refractions: materials().any(transmits),
            highlights: materials().any(has_highlight),
            checker: materials().any(is_checkered),
            attenuation: scene.lights.iter().any(fades),
            tinted_shadows: uniforms.flags & FLAG_TINTED_SHADOWS != 0,
            depth_cue: uniforms.flags & FLAG_DEPTH_CUE != 0,
            unturned_normals: uniforms.flags & FLAG_UNTURNED_NORMALS != 0,
            view: None,
            max_depth: uniforms.max_depth.max(1),
        };
        for p in &scene.prims {
            let kind = p.kind();
            assert!(primitive_kinds::kind(kind).is_some(), "primitive kind {kind} is not in the registry (primitive_kinds.rs)");
            needs.kinds |= 1 << kind;
            needs.smooth_triangles |= kind == PRIM_TRIANGLE && p.count == 3;
        }
        needs
    }

    /// The same kinds, with every term materials, lights and render settings
    /// can make, whatever the scene's are: for a scene whose materials, lights
    /// and settings change in place (the viewer's). Unturned normals stay
    /// as the scene has them: only grading's diagnosis sets them, and no
    /// viewer edits them.
    pub fn editable(self) -> Specialization {
        let Specialization { kinds, smooth_triangles, view, unturned_normals, .. } = self;
        Specialization { kinds, smooth_triangles, view, unturned_normals, ..Specialization::ALL }
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
    /// Every material counts, used or not (it cannot tell): stricter than `of`.
    pub fn covers(self, materials: &[GpuMaterial]) -> bool {
        let needs = |on: bool, term: fn(&GpuMaterial) -> bool| on || !materials.iter().any(term);
        needs(self.secondary_rays, spawns_secondary_rays)
            && needs(self.refractions, transmits)
            && needs(self.highlights, has_highlight)
            && needs(self.checker, is_checkered)
    }

    /// Whether a kernel of this specialisation renders `lights` rightly.
    pub fn covers_lights(self, lights: &[GpuLight]) -> bool {
        self.attenuation || !lights.iter().any(fades)
    }

    /// Whether a kernel of this specialisation renders with `uniforms`' settings.
    pub fn covers_uniforms(self, uniforms: &SceneUniforms) -> bool {
        let needs = |on: bool, flag: u32| on || uniforms.flags & flag == 0;
        needs(self.tinted_shadows, FLAG_TINTED_SHADOWS)
            && needs(self.depth_cue, FLAG_DEPTH_CUE)
            && needs(self.unturned_normals, FLAG_UNTURNED_NORMALS)
            && uniforms.max_depth <= self.max_depth
    }

    /// Whether it holds the primitive kind of `code`.
    pub fn has(self, code: u32) -> bool {
        self.kinds & (1 << code) != 0
    }

    fn flags(self) -> impl Iterator<Item = (&'static str, bool)> {
        let kinds = KINDS.iter().map(move |k| (k.flag, self.has(k.code)));
        kinds.chain([
            ("HAS_SMOOTH_TRIANGLES", self.smooth_triangles),
            ("HAS_SECONDARY_RAYS", self.secondary_rays),
            ("HAS_REFRACTIONS", self.refractions),
            ("HAS_HIGHLIGHTS", self.highlights),
            ("HAS_CHECKER", self.checker),
            ("HAS_ATTENUATION", self.attenuation),
            ("HAS_TINTED_SHADOWS", self.tinted_shadows),
            ("HAS_DEPTH_CUE", self.depth_cue),
            ("HAS_UNTURNED_NORMALS", self.unturned_normals),
        ])
    }

    /// The WGSL constants that carry it, appended to a kernel's prelude.
    pub fn wgsl(self) -> String {
        let mut wgsl: String = self.flags().map(|(name, on)| format!("const {name}: bool = {on};\n")).collect();
        wgsl.push_str(&format!("const ONLY_VIEW: u32 = {}u;\n", self.view.map_or(ANY_VIEW, |view| view as u32)));
        wgsl.push_str(&format!("const MAX_DEPTH: u32 = {}u;\n", self.max_depth));
        wgsl
    }
}

fn spawns_secondary_rays(m: &GpuMaterial) -> bool {
    m.reflect.iter().any(|&k| k > 0.0) || transmits(m)
}

fn transmits(m: &GpuMaterial) -> bool {
    m.transmit.iter().any(|&k| k > 0.0)
}

// The specular term k_s·O_s·lobe is exactly 0 with k_s = 0 (the lobe is at
// most 1), so such materials render the same without it.
fn has_highlight(m: &GpuMaterial) -> bool {
    m.ks != 0.0 || m.flags & MATERIAL_METALLIC != 0
}

fn is_checkered(m: &GpuMaterial) -> bool {
    m.flags & MATERIAL_CHECKER != 0
}

fn fades(light: &GpuLight) -> bool {
    light.attenuation != ATTENUATION_NONE
}

impl std::fmt::Display for Specialization {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        let kinds: Vec<String> = KINDS.iter().filter(|k| self.has(k.code)).map(|k| k.flag["HAS_".len()..].to_lowercase()).collect();
        f.write_str(if kinds.is_empty() { "no primitives".to_string() } else { kinds.join("+") }.as_str())?;
        if !self.secondary_rays {
            f.write_str(", eye rays only")?;
        } else if !self.refractions {
            f.write_str(", no refraction")?;
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
    use crate::gpu_types::{GpuPrim, PRIM_PLANE, PRIM_POLYGON, PRIM_SPHERE};
    use bytemuck::Zeroable;

    fn of(scene: &GpuScene) -> Specialization {
        Specialization::of(scene, &SceneUniforms::zeroed())
    }

    fn scene(kinds: &[u32], reflect: f32) -> GpuScene {
        GpuScene {
            prims: kinds.iter().map(|&kind| GpuPrim { kind_material: kind, ..GpuPrim::zeroed() }).collect(),
            nodes: Vec::new(),
            grids: Vec::new(),
            bvh_root: 0,
            materials: vec![GpuMaterial { reflect: [0.0, reflect, 0.0], ..GpuMaterial::zeroed() }],
            lights: Vec::new(),
            points: Vec::new(),
            light_count: 0,
            planes: (0, 0),
        }
    }

    #[test]
    fn a_scene_specialises_to_the_kinds_it_holds() {
        let needs = of(&scene(&[PRIM_TRIANGLE, PRIM_PLANE, PRIM_TRIANGLE], 0.5));
        let want = Specialization {
            kinds: 1 << PRIM_TRIANGLE | 1 << PRIM_PLANE,
            smooth_triangles: false,
            secondary_rays: true,
            refractions: false,
            highlights: false,
            checker: false,
            attenuation: false,
            tinted_shadows: false,
            depth_cue: false,
            unturned_normals: false,
            view: None,
            max_depth: 1,
        };
        assert_eq!(needs, want);
        assert_eq!(needs.to_string(), "triangles+planes, no refraction");
        let mut every = scene(&KINDS.iter().map(|k| k.code).collect::<Vec<_>>(), 1.0);
        every.prims[PRIM_TRIANGLE as usize].count = 3;
        every.materials[0] = GpuMaterial { reflect: [1.0; 3], transmit: [0.5; 3], ks: 0.5, flags: MATERIAL_CHECKER, ..GpuMaterial::zeroed() };
        every.lights.push(GpuLight { attenuation: crate::gpu_types::ATTENUATION_INVERSE_SQUARE, ..GpuLight::zeroed() });
        let uniforms = SceneUniforms { flags: FLAG_TINTED_SHADOWS | FLAG_DEPTH_CUE | FLAG_UNTURNED_NORMALS, max_depth: MAX_DEPTH_LIMIT, ..SceneUniforms::zeroed() };
        assert_eq!(Specialization::of(&every, &uniforms), Specialization::ALL);
    }

    #[test]
    fn interpolated_normals_are_compiled_for_triangles_with_vertex_normals() {
        let mut mesh = scene(&[PRIM_TRIANGLE, PRIM_TRIANGLE], 0.0);
        assert!(!of(&mesh).smooth_triangles);
        mesh.prims[1].count = 3;
        assert!(of(&mesh).smooth_triangles);
        let polygon = GpuPrim { kind_material: PRIM_POLYGON, count: 3, ..GpuPrim::zeroed() };
        assert!(!of(&GpuScene { prims: vec![polygon], ..scene(&[], 0.0) }).smooth_triangles);
    }

    #[test]
    fn matte_scenes_trace_eye_rays_only_unless_their_materials_may_change() {
        let matte = of(&scene(&[PRIM_SPHERE], 0.0));
        assert!(!matte.secondary_rays);
        assert_eq!(matte.to_string(), "spheres, eye rays only");
        let glass = [GpuMaterial { transmit: [0.0, 0.0, 0.9], ..GpuMaterial::zeroed() }];
        assert!(!matte.covers(&glass) && matte.covers(&[GpuMaterial::zeroed()]));
        assert!(matte.editable().covers(&glass));
    }

    #[test]
    fn mirrors_alone_compile_no_refraction() {
        let mirror = of(&scene(&[PRIM_SPHERE], 0.5));
        assert!(mirror.secondary_rays && !mirror.refractions);
        let glass = GpuMaterial { transmit: [0.0, 0.0, 0.9], ..GpuMaterial::zeroed() };
        assert!(mirror.covers(&[GpuMaterial { reflect: [1.0; 3], ..GpuMaterial::zeroed() }]) && !mirror.covers(&[glass]));
        let mut transparent = scene(&[PRIM_SPHERE], 0.0);
        transparent.materials = vec![glass];
        let needs = of(&transparent);
        assert!(needs.secondary_rays && needs.refractions, "{needs:?}");
    }

    #[test]
    fn shading_terms_are_compiled_for_the_materials_and_lights_that_make_them() {
        let plain = of(&scene(&[PRIM_SPHERE], 0.0));
        assert!(!plain.highlights && !plain.checker && !plain.attenuation);
        let shiny = GpuMaterial { ks: 0.3, ..GpuMaterial::zeroed() };
        let metal = GpuMaterial { flags: MATERIAL_METALLIC, ..GpuMaterial::zeroed() };
        let checkered = GpuMaterial { flags: MATERIAL_CHECKER, ..GpuMaterial::zeroed() };
        for material in [shiny, metal, checkered] {
            assert!(!plain.covers(&[material]) && plain.editable().covers(&[material]), "{material:?}");
        }
        let fading = GpuLight { attenuation: crate::gpu_types::ATTENUATION_POLYNOMIAL, ..GpuLight::zeroed() };
        assert!(plain.covers_lights(&[GpuLight::zeroed()]) && !plain.covers_lights(&[fading]));
        assert!(plain.editable().covers_lights(&[fading]));
        let mut lit = scene(&[PRIM_SPHERE, PRIM_SPHERE], 0.0);
        lit.materials = vec![shiny, checkered, GpuMaterial { reflect: [0.5; 3], ..GpuMaterial::zeroed() }];
        lit.lights = vec![fading];
        assert!(!of(&lit).checker, "only the primitives' materials count");
        lit.prims[1].kind_material |= 1 << 8;
        let needs = of(&lit);
        assert!(needs.highlights && needs.checker && needs.attenuation && !needs.secondary_rays);
    }

    #[test]
    fn tinted_shadows_depth_cueing_and_unturned_normals_are_compiled_for_the_settings_that_turn_them_on() {
        let glass = scene(&[PRIM_SPHERE], 0.0);
        let opaque = of(&glass);
        assert!(!opaque.tinted_shadows && !opaque.depth_cue && !opaque.unturned_normals);
        for flag in [FLAG_TINTED_SHADOWS, FLAG_DEPTH_CUE, FLAG_UNTURNED_NORMALS] {
            let uniforms = SceneUniforms { flags: flag, ..SceneUniforms::zeroed() };
            let editable = flag != FLAG_UNTURNED_NORMALS;
            assert!(!opaque.covers_uniforms(&uniforms) && opaque.editable().covers_uniforms(&uniforms) == editable, "{flag}");
            assert!(Specialization::of(&glass, &uniforms).covers_uniforms(&uniforms), "{flag}");
        }
        assert!(opaque.covers_uniforms(&SceneUniforms::zeroed()));
    }

    #[test]
    fn the_ray_stack_holds_the_trees_of_the_scenes_depth_and_no_deeper() {
        let mirror = scene(&[PRIM_SPHERE], 1.0);
        let at = |max_depth| SceneUniforms { max_depth, ..SceneUniforms::zeroed() };
        let five = Specialization::of(&mirror, &at(5));
        assert_eq!(five.max_depth, 5);
        assert!(five.wgsl().contains("const MAX_DEPTH: u32 = 5u;"));
        assert!(five.covers_uniforms(&at(5)) && five.covers_uniforms(&at(2)));
        assert!(!five.covers_uniforms(&at(6)), "a deeper tree overruns the stack");
        assert!(five.editable().covers_uniforms(&at(MAX_DEPTH_LIMIT)));
    }

    #[test]
    fn every_flag_is_a_wgsl_constant() {
        let wgsl = of(&scene(&[PRIM_SPHERE], 0.0)).wgsl();
        assert!(wgsl.contains("const HAS_SPHERES: bool = true;"));
        let terms = ["HAS_SMOOTH_TRIANGLES", "HAS_SECONDARY_RAYS", "HAS_REFRACTIONS", "HAS_HIGHLIGHTS", "HAS_CHECKER", "HAS_ATTENUATION", "HAS_TINTED_SHADOWS", "HAS_DEPTH_CUE"];
        for name in KINDS.iter().filter(|k| k.code != PRIM_SPHERE).map(|k| k.flag).chain(terms) {
            assert!(wgsl.contains(&format!("const {name}: bool = false;")), "{wgsl}");
        }
    }

    #[test]
    fn a_command_of_one_view_specialises_to_it_and_other_dispatches_get_any_view() {
        let kinds = of(&scene(&[PRIM_TRIANGLE], 0.0));
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
