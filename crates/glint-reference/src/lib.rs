//! A small, plain CPU reference of Glint's Whitted tracer in f64, used only by
//! tests: the GPU kernels are checked against it pixel by pixel (differential
//! testing). Brute-force nearest hit over all primitives, plain recursion, no BVH.
//!
//! The model, per colour channel in linear RGB:
//!
//! * Local: I = k_a·I_a·O_d + Σ_lights att·S·I_l·(k_d·O_d·max(0, N_s·L) + spec), a light
//!   contributing nothing (and casting no shadow ray) when N_s·L ≤ 0 or N_g·L ≤ 0.
//! * Whitted: I = s_o·(local + k_r·I_r + k_t·I_t) + (1 − s_o)·I_dc for a hit at
//!   distance t with depth cue s_o = DepthCue::scale(t) (s_o = 1 without one); a miss
//!   gives the background, not depth-cued.
//!
//! See the crate's functions for the details of each term. `Tracer::ray_tree`
//! records one pixel's tree ray by ray and term by term (`ray_tree.rs`), the
//! twin of the GPU probe.

#![forbid(unsafe_code)]

mod checker;
mod geometry;
mod random;
mod ray_tree;
#[cfg(test)]
mod tests;

use glam::DVec3;
pub use glint_encoding::RayStats;
use glint_scene::{LightKind, Material, Scene, ShadowMode, SpecularModel};

use geometry::Geom;
pub use random::random_scene;
use ray_tree::{Observer, Pending, Signature};
pub use ray_tree::{Occluder, RayKind, RefRay, RefTree, ShadowRay};

/// A rendered image: one eye ray through each pixel centre, row-major from the
/// top-left pixel (index j·width + i).
#[derive(Debug, Clone, PartialEq)]
pub struct RefImage {
    pub width: u32,
    pub height: u32,
    /// Linear RGB, no exposure or tone mapping.
    pub rgb: Vec<[f64; 3]>,
    /// Distance t along the (unit) eye ray to its hit, +∞ on a miss.
    pub depth: Vec<f64>,
    /// Index into `scene.objects` of the object the eye ray hit.
    pub object: Vec<Option<u32>>,
    /// Ray counts of each pixel.
    pub pixel_stats: Vec<RayStats>,
    /// Sum of `pixel_stats`.
    pub stats: RayStats,
}

impl RefImage {
    pub fn index(&self, i: u32, j: u32) -> usize {
        (j * self.width + i) as usize
    }
}

/// One pixel of a render.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PixelSample {
    pub rgb: [f64; 3],
    pub depth: f64,
    pub object: Option<u32>,
    pub stats: RayStats,
}

/// The nearest intersection of a ray with the scene.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Hit {
    /// Ray parameter; the distance when the direction is a unit vector.
    pub t: f64,
    /// Index into `scene.objects`.
    pub object: u32,
    /// Index of the primitive in object order: all shapes of object 0, then of
    /// object 1, …
    pub primitive: u32,
    pub point: DVec3,
    /// Unit geometric normal N_g, turned to face the incoming ray.
    pub geometric: DVec3,
    /// Unit shading normal N_s, turned to face the incoming ray; N_g if the
    /// interpolated normal still faced away after the flip.
    pub shading: DVec3,
    /// The ray met the back of the surface (N_g·d > 0 before flipping).
    pub backface: bool,
    /// N_s was replaced by N_g because it faced away from the ray.
    pub shading_fallback: bool,
    /// The point is on an odd tile of its material's checker (`checker.rs`).
    pub odd_tile: bool,
}

/// Offset for rays leaving a surface at `p`: 1e-4·max(1, max|p_i|).
pub fn ray_epsilon(p: DVec3) -> f64 {
    1e-4 * p.abs().max_element().max(1.0)
}

/// Schlick: F0 + (1 − F0)(1 − cos θ)^5 with 1 − cos θ clamped to [0, 1].
pub fn schlick(f0: f64, cos_theta: f64) -> f64 {
    let m = (1.0 - cos_theta).clamp(0.0, 1.0);
    f0 + (1.0 - f0) * m.powi(5)
}

/// The refracted unit direction of unit `d` through unit `n` (facing the
/// incoming ray) with eta = n1/n2, or `None` on total internal reflection.
pub fn refract(d: DVec3, n: DVec3, eta: f64) -> Option<DVec3> {
    let cos_i = -d.dot(n);
    let sin2_t = eta * eta * (1.0 - cos_i * cos_i);
    if sin2_t > 1.0 {
        return None;
    }
    let cos_t = (1.0 - sin2_t).sqrt();
    Some((eta * d + (eta * cos_i - cos_t) * n).normalize())
}

/// Mirror direction d − 2(d·n)n.
pub fn reflect(d: DVec3, n: DVec3) -> DVec3 {
    d - 2.0 * d.dot(n) * n
}

fn d3(v: glam::Vec3) -> DVec3 {
    DVec3::new(f64::from(v.x), f64::from(v.y), f64::from(v.z))
}

fn arr(v: DVec3) -> [f64; 3] {
    [v.x, v.y, v.z]
}

#[derive(Debug, Clone)]
struct Prim {
    geom: Geom,
    object: u32,
    material: usize,
}

#[derive(Debug, Clone, Copy)]
enum LightGeom {
    /// Position.
    Point(DVec3),
    /// Unit vector towards the light (−direction).
    Directional(DVec3),
}

#[derive(Debug, Clone, Copy)]
struct LightF {
    geom: LightGeom,
    radiance: DVec3,
    attenuation: glint_scene::Attenuation,
}

/// Per-ray-tree bookkeeping: counts, and whoever is told each step
/// (`ray_tree.rs`: the decisions' signature, the recorded tree, or no one).
struct Recorder<'o> {
    stats: RayStats,
    observer: &'o mut dyn Observer,
}

impl<'o> Recorder<'o> {
    fn new(observer: &'o mut dyn Observer) -> Self {
        Self { stats: RayStats::default(), observer }
    }
}

/// The scene converted to f64 once; all queries go through it.
pub struct Tracer<'a> {
    scene: &'a Scene,
    prims: Vec<Prim>,
    lights: Vec<LightF>,
}

impl<'a> Tracer<'a> {
    pub fn new(scene: &'a Scene) -> Self {
        let mut prims = Vec::new();
        for (id, object) in scene.objects.iter().enumerate() {
            for shape in &object.shapes {
                prims.push(Prim { geom: Geom::new(shape), object: id as u32, material: object.material });
            }
        }
        // Switched-off lights are left out entirely: they cast no shadow rays.
        let lights = scene
            .lights
            .iter()
            .filter(|l| l.enabled)
            .map(|l| LightF {
                geom: match l.kind {
                    LightKind::Point { position } => LightGeom::Point(d3(position)),
                    LightKind::Directional { direction } => LightGeom::Directional(-d3(direction).normalize()),
                },
                radiance: d3(l.color) * f64::from(l.intensity),
                attenuation: l.attenuation,
            })
            .collect();
        Self { scene, prims, lights }
    }

    pub fn scene(&self) -> &Scene {
        self.scene
    }

    fn material(&self, prim: &Prim) -> &Material {
        &self.scene.materials[prim.material]
    }

    /// The nearest hit with t in (t_min, t_max), brute force over all primitives.
    pub fn nearest_hit(&self, origin: DVec3, dir: DVec3, t_min: f64, t_max: f64) -> Option<Hit> {
        let mut best: Option<(f64, usize)> = None;
        let mut t_far = t_max;
        for (i, p) in self.prims.iter().enumerate() {
            if let Some(t) = p.geom.intersect(origin, dir, t_min, t_far) {
                best = Some((t, i));
                t_far = t;
            }
        }
        let (t, i) = best?;
        let prim = &self.prims[i];
        let point = origin + t * dir;
        let (mut geometric, mut shading) = prim.geom.normals(point);
        let backface = geometric.dot(dir) > 0.0;
        if backface {
            geometric = -geometric;
            shading = -shading;
        }
        let shading_fallback = shading.dot(dir) > 0.0;
        if shading_fallback {
            shading = geometric;
        }
        let odd_tile = checker::odd_tile(self.material(prim), &prim.geom, point);
        Some(Hit { t, object: prim.object, primitive: i as u32, point, geometric, shading, backface, shading_fallback, odd_tile })
    }

    /// How much of a light reaches along the shadow ray (origin, dir) up to `t_max`:
    /// 0 behind any opaque occluder; in tinted mode each transmissive primitive
    /// crossed multiplies by its k_t (once per primitive).
    fn transmittance(&self, origin: DVec3, dir: DVec3, t_max: f64, rec: &mut Recorder) -> DVec3 {
        let tinted = self.scene.render.shadow_mode == ShadowMode::Tinted;
        let mut s = DVec3::ONE;
        // On past an opaque occluder too: the observer is told every one.
        for (i, p) in self.prims.iter().enumerate() {
            let Some(t) = p.geom.intersect(origin, dir, 0.0, t_max) else { continue };
            let m = self.material(p);
            let tints = tinted && m.is_transmissive();
            rec.observer.occluder(i as u32, Occluder { object: p.object, t, tints });
            s = if tints { s * d3(m.transmit) } else { DVec3::ZERO };
        }
        s
    }

    /// The local illumination at a hit seen from direction `-d`.
    fn local(&self, hit: &Hit, m: &Material, d: DVec3, rec: &mut Recorder) -> DVec3 {
        let od = checker::diffuse_colour(m, hit.odd_tile);
        let mut color = f64::from(m.ambient) * d3(self.scene.ambient) * od;
        rec.observer.ambient(color);
        let v = -d;
        // With `turn_normals` off (a student's bug the grading diagnoses), a
        // back face is lit with the normals its geometry gives.
        let unturned = hit.backface && !self.scene.render.turn_normals;
        let (ns, ng) = if unturned { (-hit.shading, -hit.geometric) } else { (hit.shading, hit.geometric) };
        let p = hit.point;
        for (li, light) in self.lights.iter().enumerate() {
            let (l, distance, att) = match light.geom {
                LightGeom::Point(pos) => {
                    let to = pos - p;
                    let dist = to.length();
                    (to / dist, dist, light.attenuation.factor(dist))
                }
                LightGeom::Directional(l) => (l, f64::INFINITY, 1.0),
            };
            let n_dot_l = ns.dot(l);
            if n_dot_l <= 0.0 || ng.dot(l) <= 0.0 {
                rec.observer.light_away(li);
                continue;
            }
            let traced = self.scene.render.shadows;
            let s = if traced {
                rec.stats.shadow += 1;
                let eps = ray_epsilon(p);
                self.transmittance(p + ng * eps, l, distance - eps, rec)
            } else {
                DVec3::ONE
            };
            let reach = att * s * light.radiance;
            let shadow = |diffuse, specular| ShadowRay {
                light: li,
                n_dot_l,
                distance,
                traced,
                occluders: Vec::new(),
                transmittance: s,
                reach,
                diffuse,
                specular,
            };
            if s == DVec3::ZERO {
                rec.observer.light(p, l, shadow(DVec3::ZERO, DVec3::ZERO));
                continue;
            }
            let h = (l + v).normalize();
            let cos_a = match m.specular_model {
                SpecularModel::Phong => (2.0 * n_dot_l * ns - l).dot(v),
                SpecularModel::BlinnPhong => ns.dot(h),
            };
            // max(0, cos)^n, taken as 0 whenever cos ≤ 0, also for n = 0 (where
            // 0^0 would otherwise make the lobe 1 behind the highlight).
            let lobe = if cos_a > 0.0 { cos_a.powf(f64::from(m.shininess)) } else { 0.0 };
            let spec = match m.metallic_f0 {
                Some(f0) => {
                    let f0 = d3(f0);
                    let f = (1.0 - v.dot(h)).clamp(0.0, 1.0).powi(5);
                    (f0 + (DVec3::ONE - f0) * f) * lobe
                }
                None => f64::from(m.specular) * d3(m.specular_color.unwrap_or(glam::Vec3::ONE)) * lobe,
            };
            let (diffuse, specular) = (reach * f64::from(m.diffuse) * od * n_dot_l, reach * spec);
            rec.observer.light(p, l, shadow(diffuse, specular));
            color += diffuse + specular;
        }
        color
    }

    /// Colour of the ray (origin, unit dir), traced as `ray` says. Returns the
    /// colour and the hit.
    fn trace_rec(&self, origin: DVec3, dir: DVec3, ray: Pending, rec: &mut Recorder) -> (DVec3, Option<Hit>) {
        let (depth, weight) = (ray.depth, ray.weight);
        let hit = self.nearest_hit(origin, dir, 0.0, f64::INFINITY);
        if depth == 1 {
            if hit.is_some() {
                rec.stats.eye_hit += 1;
            } else {
                rec.stats.eye_miss += 1;
            }
        }
        let id = rec.observer.ray(&ray, origin, dir, hit.as_ref());
        let Some(hit) = hit else {
            return (d3(self.scene.background), None);
        };
        let prim = &self.prims[hit.primitive as usize];
        let m = self.material(prim);
        let local = self.local(&hit, m, dir, rec);
        let (so, cue) = match &self.scene.depth_cue {
            Some(dc) => (dc.scale(hit.t), d3(dc.color)),
            None => (1.0, DVec3::ZERO),
        };
        rec.observer.cue(so);
        let mut inner = local;
        let r = &self.scene.render;
        if depth < r.max_depth {
            let ior = f64::from(m.ior);
            let eta = if hit.backface { ior } else { 1.0 / ior };
            let mut kr = d3(m.reflect);
            let mut kt = if r.refractions { d3(m.transmit) } else { DVec3::ZERO };
            let n = hit.shading;
            let refracted = refract(dir, n, eta);
            let mut tir = false;
            if kt.max_element() > 0.0 {
                match refracted {
                    None => {
                        tir = true;
                        kr += kt;
                        kt = DVec3::ZERO;
                    }
                    Some(t_dir) if m.fresnel => {
                        let f0 = ((1.0 - ior) / (1.0 + ior)).powi(2);
                        let cos = if eta > 1.0 { -t_dir.dot(n) } else { -dir.dot(n) };
                        let f = schlick(f0, cos);
                        kr += kt * f;
                        kt *= 1.0 - f;
                    }
                    Some(_) => {}
                }
            }
            // Reflections off: no reflected ray at all, TIR and Fresnel shares included.
            if !r.reflections {
                kr = DVec3::ZERO;
            }
            let eps = ray_epsilon(hit.point);
            let wr = weight * so * kr;
            let wt = weight * so * kt;
            let spawn = |w: DVec3| w.max_element() > f64::from(r.cutoff) && w.max_element() > 0.0;
            let (do_r, do_t) = (spawn(wr), spawn(wt));
            rec.observer.branch(eta, tir, do_r, do_t);
            let child = |kind, weight| Pending { kind, parent: Some(id), depth: depth + 1, weight };
            if do_r {
                rec.stats.reflect += 1;
                let (c, _) = self.trace_rec(hit.point + hit.geometric * eps, reflect(dir, n), child(RayKind::Reflect, wr), rec);
                inner += kr * c;
            }
            if do_t {
                rec.stats.refract += 1;
                let t_dir = refracted.expect("k_t > 0 only when refraction is possible");
                let (c, _) = self.trace_rec(hit.point - hit.geometric * eps, t_dir, child(RayKind::Refract, wt), rec);
                inner += kt * c;
            }
        }
        (so * inner + (1.0 - so) * cue, Some(hit))
    }

    /// An eye ray's colour and hit, each step told to `observer`; `dir` is normalised.
    fn trace_observed(&self, origin: DVec3, dir: DVec3, observer: &mut dyn Observer) -> (DVec3, Option<Hit>, RayStats) {
        let eye = Pending { kind: RayKind::Eye, parent: None, depth: 1, weight: DVec3::ONE };
        let mut rec = Recorder::new(observer);
        let (c, hit) = self.trace_rec(origin, dir.normalize(), eye, &mut rec);
        (c, hit, rec.stats)
    }

    /// Colour of a ray treated as an eye ray (depth 1, weight 1); `dir` is normalised.
    pub fn trace(&self, origin: DVec3, dir: DVec3, stats: &mut RayStats) -> [f64; 3] {
        let (c, _, ray_stats) = self.trace_observed(origin, dir, &mut ());
        *stats += ray_stats;
        arr(c)
    }

    fn eye_ray(&self, width: u32, height: u32, x: f64, y: f64) -> (DVec3, DVec3) {
        let ray = self.scene.camera.ray(width, height, x, y).expect("the camera has no basis (up parallel to the view)");
        (ray.origin, ray.direction)
    }

    /// Pixel (i, j) of a `width` × `height` render: the ray through its centre.
    pub fn pixel(&self, width: u32, height: u32, i: u32, j: u32) -> PixelSample {
        let (o, d) = self.eye_ray(width, height, f64::from(i) + 0.5, f64::from(j) + 0.5);
        let (c, hit, stats) = self.trace_observed(o, d, &mut ());
        PixelSample { rgb: arr(c), depth: hit.map_or(f64::INFINITY, |h| h.t), object: hit.map(|h| h.object), stats }
    }

    pub fn render(&self, width: u32, height: u32) -> RefImage {
        let n = (width * height) as usize;
        let mut img = RefImage {
            width,
            height,
            rgb: Vec::with_capacity(n),
            depth: Vec::with_capacity(n),
            object: Vec::with_capacity(n),
            pixel_stats: Vec::with_capacity(n),
            stats: RayStats::default(),
        };
        for j in 0..height {
            for i in 0..width {
                let p = self.pixel(width, height, i, j);
                img.rgb.push(p.rgb);
                img.depth.push(p.depth);
                img.object.push(p.object);
                img.pixel_stats.push(p.stats);
                img.stats += p.stats;
            }
        }
        img
    }

    /// The discrete decisions of the ray tree through image position (x, y)
    /// (`ray_tree::Signature`). Two positions with equal signatures are shaded
    /// by the same continuous formula.
    pub fn signature(&self, width: u32, height: u32, x: f64, y: f64) -> Vec<u64> {
        let (o, d) = self.eye_ray(width, height, x, y);
        let mut signature = Signature::default();
        self.trace_observed(o, d, &mut signature);
        signature.0
    }

    /// Whether pixel (i, j) is away from every discontinuity: the ray trees through
    /// the centre and through the centre moved by ±`delta_px` pixels along x, y and
    /// both diagonals make the same discrete decisions. Where this is false (object
    /// silhouettes, shadow edges, polygon edges, the TIR boundary, cutoff decisions,
    /// …) single- and double-precision renders may legitimately differ.
    pub fn pixel_stable(&self, width: u32, height: u32, i: u32, j: u32, delta_px: f64) -> bool {
        let (x, y) = (f64::from(i) + 0.5, f64::from(j) + 0.5);
        let centre = self.signature(width, height, x, y);
        let dd = delta_px;
        [(dd, 0.0), (-dd, 0.0), (0.0, dd), (0.0, -dd), (dd, dd), (-dd, -dd), (dd, -dd), (-dd, dd)]
            .into_iter()
            .all(|(dx, dy)| self.signature(width, height, x + dx, y + dy) == centre)
    }

    /// `pixel_stable` for every pixel, row-major.
    pub fn stability_mask(&self, width: u32, height: u32, delta_px: f64) -> Vec<bool> {
        (0..height).flat_map(|j| (0..width).map(move |i| (i, j))).map(|(i, j)| self.pixel_stable(width, height, i, j, delta_px)).collect()
    }
}

/// Renders `scene` at `width` × `height`: one ray through each pixel centre.
pub fn render(scene: &Scene, width: u32, height: u32) -> RefImage {
    Tracer::new(scene).render(width, height)
}

/// Pixel (i, j) of a `width` × `height` render.
pub fn pixel(scene: &Scene, width: u32, height: u32, i: u32, j: u32) -> PixelSample {
    Tracer::new(scene).pixel(width, height, i, j)
}

/// Colour of one ray treated as an eye ray (depth 1); `dir` need not be unit.
pub fn trace_ray(scene: &Scene, origin: DVec3, dir: DVec3) -> [f64; 3] {
    Tracer::new(scene).trace(origin, dir, &mut RayStats::default())
}

/// `Tracer::stability_mask`: which pixels are safe to compare exactly.
pub fn stability_mask(scene: &Scene, width: u32, height: u32, delta_px: f64) -> Vec<bool> {
    Tracer::new(scene).stability_mask(width, height, delta_px)
}
