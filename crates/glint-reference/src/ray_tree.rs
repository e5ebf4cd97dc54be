//! What the tracer reports as it walks a ray tree, and the two listeners to it:
//! the signature of the tree's discrete decisions (which pixels sit on an edge)
//! and the recorded tree itself, ray by ray with every term — the twin of the
//! GPU probe (glint-gpu/src/probe.rs), which the probe tests compare it with.
//! Both are fed by the one recursion in lib.rs, so what is recorded is exactly
//! what the reference computed.

use glam::DVec3;

use crate::{Hit, Tracer};

/// What a ray of the tree is.
#[derive(Debug, Clone, Copy, PartialEq, Eq, PartialOrd, Ord, Hash)]
pub enum RayKind {
    Eye,
    Reflect,
    Refract,
    Shadow,
}

/// A ray about to be traced: where it sits in the tree and what its colour is
/// multiplied by on its way to the pixel.
#[derive(Debug, Clone, Copy)]
pub(crate) struct Pending {
    pub(crate) kind: RayKind,
    /// Id `Observer::ray` gave the ray this one came from.
    pub(crate) parent: Option<usize>,
    pub(crate) depth: u32,
    pub(crate) weight: DVec3,
}

/// Told everything the tracer does, in the order it does it: a ray, then the
/// terms and decisions at its hit, then its children's rays. Every report
/// between one `ray` and the next is about the first.
pub(crate) trait Observer {
    /// A ray and what it hit; returns the id its children get as parent.
    fn ray(&mut self, _ray: &Pending, _origin: DVec3, _dir: DVec3, _hit: Option<&Hit>) -> usize {
        0
    }
    fn ambient(&mut self, _term: DVec3) {}
    /// Light `light` is behind the surface: no shadow ray, nothing added.
    fn light_away(&mut self, _light: usize) {}
    /// A primitive the next reported shadow ray crosses before its light.
    fn occluder(&mut self, _primitive: u32, _occluder: Occluder) {}
    /// A light the surface faces, with the shadow ray from `point` along `dir`
    /// (its occluders are the ones reported just before).
    fn light(&mut self, _point: DVec3, _dir: DVec3, _shadow: ShadowRay) {}
    fn cue(&mut self, _scale: f64) {}
    /// η = n1/n2 at the hit, whether the transmitted share was totally
    /// reflected, and which children are traced.
    fn branch(&mut self, _eta: f64, _tir: bool, _reflect: bool, _refract: bool) {}
}

/// Counting only.
impl Observer for () {}

/// The discrete decisions of a ray tree, a word each (tag << 40 | value):
/// which primitive each ray hit, backface, normal fallback and checker tile,
/// per light facing or not, shadowed or not and each primitive its shadow ray
/// crossed, total internal reflection, which children were traced. Two rays
/// with equal signatures are shaded by the same continuous formula.
#[derive(Default)]
pub(crate) struct Signature(pub(crate) Vec<u64>);

const TAG_RAY: u64 = 1;
const TAG_SURFACE: u64 = 2;
const TAG_LIGHT: u64 = 3;
const TAG_OCCLUDER: u64 = 4;
const TAG_CHILDREN: u64 = 5;

impl Signature {
    fn note(&mut self, tag: u64, value: u64) {
        self.0.push(tag << 40 | value);
    }

    /// The words of the first ray alone: up to its first child's ray.
    fn first_ray(mut self) -> Vec<u64> {
        let end = self.0.iter().skip(1).position(|w| w >> 40 == TAG_RAY).map_or(self.0.len(), |i| i + 1);
        self.0.truncate(end);
        self.0
    }
}

impl Observer for Signature {
    fn ray(&mut self, _: &Pending, _: DVec3, _: DVec3, hit: Option<&Hit>) -> usize {
        self.note(TAG_RAY, hit.map_or(0, |h| u64::from(h.primitive) + 1));
        if let Some(h) = hit {
            self.note(TAG_SURFACE, u64::from(h.backface) | u64::from(h.shading_fallback) << 1 | u64::from(h.odd_tile) << 2);
        }
        0
    }
    fn light_away(&mut self, light: usize) {
        self.note(TAG_LIGHT, (light as u64) << 4);
    }
    fn occluder(&mut self, primitive: u32, occluder: Occluder) {
        self.note(TAG_OCCLUDER, u64::from(primitive) << 1 | u64::from(occluder.tints));
    }
    fn light(&mut self, _: DVec3, _: DVec3, shadow: ShadowRay) {
        self.note(TAG_LIGHT, (shadow.light as u64) << 4 | 1 | u64::from(shadow.blocked()) << 1);
    }
    fn branch(&mut self, _: f64, tir: bool, reflect: bool, refract: bool) {
        self.note(TAG_CHILDREN, u64::from(tir) | u64::from(reflect) << 1 | u64::from(refract) << 2);
    }
}

/// A primitive a shadow ray crosses on its way to the light.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Occluder {
    pub object: u32,
    /// Distance from the shadow ray's (offset) origin.
    pub t: f64,
    /// Tinted shadows let light through it, times its k_t; else it blocks.
    pub tints: bool,
}

/// A light as a hit sees it, and the shadow ray cast towards it.
#[derive(Debug, Clone, PartialEq)]
pub struct ShadowRay {
    /// Index among the lights that are on, in scene order.
    pub light: usize,
    pub n_dot_l: f64,
    /// To the light; +∞ for a directional one.
    pub distance: f64,
    /// False with shadows off: the light counts as unblocked.
    pub traced: bool,
    /// Every primitive crossed, in scene order.
    pub occluders: Vec<Occluder>,
    /// S: the light let through, 0 when blocked.
    pub transmittance: DVec3,
    /// att·S·I_l: the light that arrives.
    pub reach: DVec3,
    /// reach·k_d·O_d·(N·L).
    pub diffuse: DVec3,
    /// reach times the specular term.
    pub specular: DVec3,
}

impl ShadowRay {
    pub fn blocked(&self) -> bool {
        self.transmittance == DVec3::ZERO
    }
}

/// One ray of a recorded tree.
#[derive(Debug, Clone, PartialEq)]
pub struct RefRay {
    pub kind: RayKind,
    /// Index in `RefTree::rays` of the ray this one came from; `None` for the eye ray.
    pub parent: Option<usize>,
    pub depth: u32,
    /// For a shadow ray the hit point it leaves from, before the offset.
    pub origin: DVec3,
    pub dir: DVec3,
    /// What its colour is multiplied by on its way to the pixel; a shadow
    /// ray's is its parent's.
    pub weight: DVec3,
    /// What an eye, reflected or refracted ray hit; `None` on a miss and for shadow rays.
    pub hit: Option<Hit>,
    /// k_a·I_a·O_d at the hit.
    pub ambient: DVec3,
    /// s_o at the hit, 1 without depth cueing.
    pub cue_scale: f64,
    /// η = n1/n2 at the hit (1 where no children were considered: a miss, the last level).
    pub eta: f64,
    pub total_internal_reflection: bool,
    /// For shadow rays.
    pub shadow: Option<ShadowRay>,
    /// The linear colour this ray adds to the pixel: weight × background on a
    /// miss, weight × (s_o·ambient + (1 − s_o)·depth-cue colour) at a hit, and
    /// for a shadow ray its light's terms times its parent's weight and s_o.
    pub contribution: DVec3,
}

/// A ray tree: rays in the order traced (a parent before its children;
/// reflection before refraction).
#[derive(Debug, Clone, PartialEq)]
pub struct RefTree {
    /// What the first ray brings back: the pixel's colour for an eye ray, the
    /// sum of the contributions over the first ray's weight.
    pub color: [f64; 3],
    pub rays: Vec<RefRay>,
}

impl RefRay {
    /// A ray before anything is known of what it meets.
    fn new(ray: &Pending, origin: DVec3, dir: DVec3) -> Self {
        Self {
            kind: ray.kind,
            parent: ray.parent,
            depth: ray.depth,
            origin,
            dir,
            weight: ray.weight,
            hit: None,
            ambient: DVec3::ZERO,
            cue_scale: 1.0,
            eta: 1.0,
            total_internal_reflection: false,
            shadow: None,
            contribution: DVec3::ZERO,
        }
    }
}

/// Records the tree; contributions are added once it is complete.
#[derive(Default)]
struct Recording {
    rays: Vec<RefRay>,
    current: usize,
    occluders: Vec<Occluder>,
}

impl Recording {
    fn push(&mut self, ray: RefRay) -> usize {
        self.rays.push(ray);
        self.rays.len() - 1
    }
}

impl Observer for Recording {
    fn ray(&mut self, ray: &Pending, origin: DVec3, dir: DVec3, hit: Option<&Hit>) -> usize {
        self.current = self.push(RefRay { hit: hit.copied(), ..RefRay::new(ray, origin, dir) });
        self.current
    }
    fn ambient(&mut self, term: DVec3) {
        self.rays[self.current].ambient = term;
    }
    fn occluder(&mut self, _: u32, occluder: Occluder) {
        self.occluders.push(occluder);
    }
    fn light(&mut self, point: DVec3, dir: DVec3, shadow: ShadowRay) {
        let parent = &self.rays[self.current];
        let pending = Pending { kind: RayKind::Shadow, parent: Some(self.current), depth: parent.depth, weight: parent.weight };
        let shadow = ShadowRay { occluders: std::mem::take(&mut self.occluders), ..shadow };
        self.push(RefRay { shadow: Some(shadow), ..RefRay::new(&pending, point, dir) });
    }
    fn cue(&mut self, scale: f64) {
        self.rays[self.current].cue_scale = scale;
    }
    fn branch(&mut self, eta: f64, tir: bool, _: bool, _: bool) {
        let ray = &mut self.rays[self.current];
        ray.eta = eta;
        ray.total_internal_reflection = tir;
    }
}

/// Some unit vector perpendicular to unit `n`.
fn perpendicular(n: DVec3) -> DVec3 {
    let a = if n.x.abs() < 0.6 { DVec3::X } else { DVec3::Y };
    (a - n * a.dot(n)).normalize()
}

impl Tracer<'_> {
    /// The ray tree through image position (`x`, `y`) of a `width` × `height`
    /// image, (i + 0.5, j + 0.5) being pixel (i, j)'s centre.
    pub fn ray_tree(&self, width: u32, height: u32, x: f64, y: f64) -> RefTree {
        let (origin, dir) = self.eye_ray(width, height, x, y);
        self.ray_tree_along(origin, dir, RayKind::Eye, 1, DVec3::ONE)
    }

    /// The tree below one ray of `kind` at `depth` carrying `weight`, from
    /// `origin` along `dir` (normalised): a step of some tree, taken afresh.
    pub fn ray_tree_along(&self, origin: DVec3, dir: DVec3, kind: RayKind, depth: u32, weight: DVec3) -> RefTree {
        let mut recording = Recording::default();
        let ray = Pending { kind, parent: None, depth, weight };
        let (color, _) = self.trace_rec(origin, dir.normalize(), ray, &mut crate::Recorder::new(&mut recording));
        let mut rays = recording.rays;
        let background = crate::d3(self.scene.background);
        let cue = self.scene.depth_cue.map_or(DVec3::ZERO, |dc| crate::d3(dc.color));
        for i in 0..rays.len() {
            let r = &rays[i];
            let contribution = match (&r.shadow, r.parent) {
                (Some(s), Some(p)) => rays[p].weight * rays[p].cue_scale * (s.diffuse + s.specular),
                _ if r.hit.is_none() => r.weight * background,
                _ => r.weight * (r.cue_scale * r.ambient + (1.0 - r.cue_scale) * cue),
            };
            rays[i].contribution = contribution;
        }
        RefTree { color: crate::arr(color), rays }
    }

    /// The decisions ray `index` of `tree` makes at its hit, traced along
    /// (`origin`, `dir`) instead (a shadow ray's are its parent's).
    fn decisions(&self, tree: &RefTree, index: usize, origin: DVec3, dir: DVec3) -> Vec<u64> {
        let r = &tree.rays[index];
        let pending = Pending { kind: r.kind, parent: r.parent, depth: r.depth, weight: r.weight };
        let mut signature = Signature::default();
        self.trace_rec(origin, dir, pending, &mut crate::Recorder::new(&mut signature));
        signature.first_ray()
    }

    /// Whether what ray `index` of `tree` decides (what it hits and on which
    /// side, which lights it sees past which occluders, total internal
    /// reflection, which children it traces) is within `delta` of going the
    /// other way: it changes when the ray's direction turns by `delta` radians
    /// or its origin moves by `delta`·max(1, |origin|) across it (four ways
    /// each), or when another object's surface is hit within `delta`·max(1, t).
    /// A shadow ray's decisions are its parent's. Where this is true, f32 and
    /// f64 may trace different trees; elsewhere they must agree.
    pub fn near_tie(&self, tree: &RefTree, index: usize, delta: f64) -> bool {
        let index = match tree.rays[index].kind {
            RayKind::Shadow => tree.rays[index].parent.expect("a shadow ray has a parent"),
            _ => index,
        };
        let r = &tree.rays[index];
        let own = self.decisions(tree, index, r.origin, r.dir);
        let u = perpendicular(r.dir);
        let shift = delta * r.origin.abs().max_element().max(1.0);
        let mut moved = [u, -u, r.dir.cross(u), -r.dir.cross(u)]
            .into_iter()
            .flat_map(|a| [(r.origin, (r.dir + delta * a).normalize()), (r.origin + shift * a, r.dir)]);
        if moved.any(|(o, d)| self.decisions(tree, index, o, d) != own) {
            return true;
        }
        let Some(hit) = r.hit else { return false };
        self.prims.iter().filter(|p| p.object != hit.object).any(|p| {
            p.geom.intersect(r.origin, r.dir, 0.0, f64::INFINITY).is_some_and(|t| (t - hit.t).abs() <= delta * hit.t.max(1.0))
        })
    }
}

#[cfg(test)]
mod tests {
    use std::path::Path;

    use super::*;
    use crate::random_scene;

    #[test]
    fn a_recorded_tree_adds_up_to_the_pixel_and_holds_the_rays_counted() {
        for seed in 0..8 {
            let scene = random_scene(seed);
            let tracer = Tracer::new(&scene);
            for (i, j) in [(32, 24), (20, 30), (45, 15), (10, 10), (50, 40)] {
                let tree = tracer.ray_tree(scene.width, scene.height, f64::from(i) + 0.5, f64::from(j) + 0.5);
                let pixel = tracer.pixel(scene.width, scene.height, i, j);
                assert_eq!(tree.color, pixel.rgb, "seed {seed} ({i}, {j})");
                let sum = tree.rays.iter().fold(DVec3::ZERO, |a, r| a + r.contribution);
                let off = (sum - DVec3::from(pixel.rgb)).abs().max_element();
                assert!(off < 1e-12, "seed {seed} ({i}, {j}): {sum} vs {:?}", pixel.rgb);
                let count = |kind| tree.rays.iter().filter(|r| r.kind == kind).count() as u64;
                let traced = tree.rays.iter().filter(|r| r.shadow.as_ref().is_some_and(|s| s.traced)).count() as u64;
                let s = pixel.stats;
                let counted = (count(RayKind::Eye), count(RayKind::Reflect), count(RayKind::Refract), traced);
                assert_eq!(counted, (1, s.reflect, s.refract, s.shadow), "seed {seed} ({i}, {j})");
                assert!(tree.rays.iter().enumerate().all(|(k, r)| r.parent.is_none_or(|p| p < k)));
            }
        }
    }

    /// A unit sphere before a wall, lit from the side, seen head on.
    fn sphere_before_a_wall(wall_twice: bool) -> glint_scene::Scene {
        let wall = r#"
[[object]]
type = "polygon"
vertices = [[-9, -9, -3], [9, -9, -3], [9, 9, -3], [-9, 9, -3]]
material = "matte"
"#;
        let source = format!(
            r#"
[image]
width = 33
height = 33
[camera]
eye = [0, 0, 5]
look_at = [0, 0, 0]
fov = 60
[[light]]
type = "point"
position = [5, 0, 10]
[material.matte]
color = 0.8
[[object]]
type = "sphere"
center = [0, 0, 0]
radius = 1
material = "matte"
{wall}{}"#,
            if wall_twice { wall } else { "" }
        );
        glint_scene::toml_scene::parse(&source, Path::new("inline.toml")).unwrap()
    }

    /// The x in [lo, hi] of the middle row where `f` changes, to 1e-9 pixels.
    fn edge(tracer: &Tracer, f: impl Fn(&RefTree) -> bool, (mut lo, mut hi): (f64, f64)) -> f64 {
        let at = |x| f(&tracer.ray_tree(33, 33, x, 16.5));
        let start = at(lo);
        assert_ne!(start, at(hi), "no edge in [{lo}, {hi}]");
        while hi - lo > 1e-9 {
            let mid = 0.5 * (lo + hi);
            if at(mid) == start { lo = mid } else { hi = mid }
        }
        lo
    }

    #[test]
    fn near_ties_are_where_the_reference_would_decide_otherwise() {
        let scene = sphere_before_a_wall(false);
        let tracer = Tracer::new(&scene);
        let tie = |x: f64, ray: usize| tracer.near_tie(&tracer.ray_tree(33, 33, x, 16.5), ray, 1e-4);
        // Head on, the eye ray and its shadow ray are far from any edge.
        assert!(!tie(16.5, 0) && !tie(16.5, 1));
        // At the sphere's silhouette the eye ray could as well hit the wall.
        let silhouette = edge(&tracer, |t| t.rays[0].hit.is_some_and(|h| h.object == 0), (16.5, 32.0));
        assert!(tie(silhouette, 0) && !tie(silhouette - 0.5, 0));
        // At the edge of the sphere's shadow on the wall the shadow ray could
        // as well pass: a near tie of the wall's hit, which casts it.
        let blocked = |t: &RefTree| t.rays[1].shadow.as_ref().is_some_and(ShadowRay::blocked);
        let shadow_edge = edge(&tracer, blocked, (0.5, 9.5));
        assert!(tie(shadow_edge, 1) && tie(shadow_edge, 0) && !tie(shadow_edge - 0.5, 1));
        // Two coincident walls: which one is hit is a tie wherever the ray goes.
        let twice = sphere_before_a_wall(true);
        let tracer = Tracer::new(&twice);
        assert!(tracer.near_tie(&tracer.ray_tree(33, 33, 2.5, 16.5), 0, 1e-4));
    }
}
