//! Random test scenes for differential testing: a few well separated objects of
//! every primitive kind above a floor (a square or an infinite plane), 1–3
//! lights, random materials (some checkered) and settings.

use std::f32::consts::{PI, TAU};

use glam::Vec3;
use glint_scene::{
    Attenuation, Camera, Checker, DepthCue, Light, LightKind, Material, Object, Projection, RenderSettings, Scene,
    ShadowMode, Shape, SpecularModel,
};

/// SplitMix64: tiny, good enough, no dependency.
pub(crate) struct Rng(u64);

impl Rng {
    pub(crate) fn new(seed: u64) -> Self {
        Self(seed)
    }
    fn next_u64(&mut self) -> u64 {
        self.0 = self.0.wrapping_add(0x9E37_79B9_7F4A_7C15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
        z ^ (z >> 31)
    }
    /// Uniform in [0, 1).
    pub(crate) fn unit(&mut self) -> f32 {
        (self.next_u64() >> 40) as f32 / (1u64 << 24) as f32
    }
    pub(crate) fn range(&mut self, lo: f32, hi: f32) -> f32 {
        lo + (hi - lo) * self.unit()
    }
    /// Uniform in 0..n.
    pub(crate) fn below(&mut self, n: usize) -> usize {
        (self.next_u64() % n as u64) as usize
    }
    pub(crate) fn chance(&mut self, p: f32) -> bool {
        self.unit() < p
    }
    fn color(&mut self, lo: f32, hi: f32) -> Vec3 {
        Vec3::new(self.range(lo, hi), self.range(lo, hi), self.range(lo, hi))
    }
    /// Uniform on the unit sphere.
    fn direction(&mut self) -> Vec3 {
        loop {
            let v = Vec3::new(self.range(-1.0, 1.0), self.range(-1.0, 1.0), self.range(-1.0, 1.0));
            let l = v.length();
            if l > 0.1 && l <= 1.0 {
                return v / l;
            }
        }
    }
    fn in_ball(&mut self, r: f32) -> Vec3 {
        loop {
            let v = Vec3::new(self.range(-1.0, 1.0), self.range(-1.0, 1.0), self.range(-1.0, 1.0));
            if v.length_squared() <= 1.0 {
                return v * r;
            }
        }
    }
    fn shuffle<T>(&mut self, v: &mut [T]) {
        for i in (1..v.len()).rev() {
            v.swap(i, self.below(i + 1));
        }
    }
}

/// Distance between cell centres (x and z), and the radius every object stays
/// within around its centre (whose y is in [−0.1, 0.1]): neighbours are at least
/// 2.2 − 2·0.9 = 0.4 apart.
const SPACING: f32 = 2.2;
pub(crate) const OBJECT_RADIUS: f32 = 0.9;
/// The floor, at least 0.3 below the lowest object point.
pub(crate) const FLOOR_Y: f32 = -1.3;

#[derive(Clone, Copy, PartialEq, Eq, Debug)]
enum Kind {
    Sphere,
    Triangle,
    ConvexPolygon,
    ConcavePolygon,
    Cone,
    Cylinder,
    Tetrahedron,
}

/// An orthonormal frame (e1, e2, n) around a random unit n.
fn frame(n: Vec3) -> (Vec3, Vec3) {
    let a = if n.x.abs() < 0.6 { Vec3::X } else { Vec3::Y };
    let e1 = (a - n * a.dot(n)).normalize();
    (e1, n.cross(e1))
}

/// A small random scene (64 × 48): a floor (a square polygon or an infinite
/// plane, often checkered) and 4–8 objects, each within
/// `OBJECT_RADIUS` of the centre of its own cell of a 3 × 3 grid (so no two
/// surfaces touch), covering spheres, triangles (some smooth), convex and concave
/// polygons, cones, cylinders and sometimes a tetrahedron mesh; 1–3 lights (point
/// and directional, some attenuated, sometimes an extra switched-off one);
/// plain, mirror, glass and metallic materials, some with a solid checker;
/// random camera, background,
/// depth cue, shadow mode and render settings. The same seed gives the same scene.
pub fn random_scene(seed: u64) -> Scene {
    let mut rng = Rng::new(seed ^ 0x6A09_E667_F3BC_C908);
    let mut materials = Vec::new();
    let mut objects = Vec::new();

    // The floor: matte, sometimes a dim mirror, often checkered; a square or an
    // infinite plane, its normal (a polygon's vertex order) up or down at random.
    let mut floor = plain_material(&mut rng, "floor");
    floor.specular *= 0.3;
    if rng.chance(0.2) {
        floor.reflect = Vec3::splat(rng.range(0.2, 0.5));
    }
    if rng.chance(0.5) {
        floor.checker = Some(Checker { color: rng.color(0.15, 1.0), size: rng.range(0.7, 2.5) });
    }
    materials.push(floor);
    let down = rng.chance(0.5);
    let floor = if rng.chance(0.4) {
        let point = Vec3::new(rng.range(-2.0, 2.0), FLOOR_Y, rng.range(-2.0, 2.0));
        Shape::Plane { point, normal: if down { Vec3::NEG_Y } else { Vec3::Y } }
    } else {
        let s = 9.0;
        let mut corners = vec![
            Vec3::new(-s, FLOOR_Y, -s),
            Vec3::new(s, FLOOR_Y, -s),
            Vec3::new(s, FLOOR_Y, s),
            Vec3::new(-s, FLOOR_Y, s),
        ];
        if down {
            corners.reverse();
        }
        Shape::Polygon { vertices: corners }
    };
    objects.push(Object { material: 0, shapes: vec![floor] });

    let mut cells: Vec<(i32, i32)> = (-1..=1).flat_map(|x| (-1..=1).map(move |z| (x, z))).collect();
    rng.shuffle(&mut cells);
    let count = 4 + rng.below(5);
    let mut kinds = vec![
        Kind::Sphere,
        Kind::Triangle,
        if rng.chance(0.5) { Kind::ConvexPolygon } else { Kind::ConcavePolygon },
        if rng.chance(0.5) { Kind::Cone } else { Kind::Cylinder },
    ];
    const ALL: [Kind; 7] = [
        Kind::Sphere,
        Kind::Triangle,
        Kind::ConvexPolygon,
        Kind::ConcavePolygon,
        Kind::Cone,
        Kind::Cylinder,
        Kind::Tetrahedron,
    ];
    while kinds.len() < count {
        kinds.push(ALL[rng.below(ALL.len())]);
    }
    rng.shuffle(&mut kinds);

    for (&(cx, cz), &kind) in cells.iter().zip(&kinds) {
        let c = Vec3::new(cx as f32 * SPACING, rng.range(-0.1, 0.1), cz as f32 * SPACING);
        let shapes = shape(&mut rng, kind, c);
        let closed = matches!(kind, Kind::Sphere | Kind::Tetrahedron);
        let mut m = match rng.unit() {
            x if x < 0.45 => plain_material(&mut rng, "plain"),
            x if x < 0.65 => mirror_material(&mut rng),
            x if x < (if closed { 0.9 } else { 0.8 }) => glass_material(&mut rng),
            _ => metallic_material(&mut rng),
        };
        if rng.chance(0.2) {
            m.checker = Some(Checker { color: rng.color(0.15, 1.0), size: rng.range(0.2, 0.6) });
        }
        materials.push(m);
        objects.push(Object { material: materials.len() - 1, shapes });
    }

    let mut lights = Vec::new();
    let light_count = 1 + rng.below(3);
    for _ in 0..light_count {
        lights.push(light(&mut rng, light_count));
    }
    if rng.chance(0.15) {
        let mut off = light(&mut rng, 1);
        off.enabled = false;
        let at = rng.below(lights.len() + 1);
        lights.insert(at, off);
    }

    let distance = rng.range(7.5, 9.5);
    let azimuth = rng.range(0.0, TAU);
    let elevation = rng.range(15.0, 50.0).to_radians();
    let look_at = Vec3::new(rng.range(-0.3, 0.3), rng.range(-0.3, 0.2), rng.range(-0.3, 0.3));
    let eye = look_at
        + distance * Vec3::new(elevation.cos() * azimuth.cos(), elevation.sin(), elevation.cos() * azimuth.sin());
    let projection = if rng.chance(0.6) {
        Projection::Perspective { fov_y_degrees: rng.range(40.0, 55.0) }
    } else {
        Projection::Orthographic { height: rng.range(6.5, 8.0) }
    };

    let depth_cue = rng.chance(0.3).then(|| DepthCue {
        color: rng.color(0.0, 0.6),
        near: distance - 3.0,
        far: distance + 5.0,
        near_scale: 1.0,
        far_scale: rng.range(0.2, 0.6),
    });
    let shadows = rng.chance(0.85);
    let render = RenderSettings {
        max_depth: 2 + rng.below(5) as u32,
        cutoff: [0.0, 1.0 / 256.0, 0.01, 0.05][rng.below(4)],
        shadows,
        shadow_mode: if rng.chance(0.4) { ShadowMode::Tinted } else { ShadowMode::Opaque },
        reflections: rng.chance(0.9),
        refractions: rng.chance(0.9),
        turn_normals: true,
    };

    Scene {
        width: 64,
        height: 48,
        background: rng.color(0.0, 0.3),
        camera: Camera { eye, look_at, up: Vec3::Y, projection },
        ambient: rng.color(0.1, 0.3),
        lights,
        materials,
        objects,
        depth_cue,
        render,
        animation: None,
        warnings: Vec::new(),
    }
}

fn shape(rng: &mut Rng, kind: Kind, c: Vec3) -> Vec<Shape> {
    match kind {
        Kind::Sphere => vec![Shape::Sphere { center: c, radius: rng.range(0.4, OBJECT_RADIUS) }],
        Kind::Triangle => {
            // Fat triangles: three points near a circle of radius 0.85 in a random plane.
            let (e1, e2) = frame(rng.direction());
            let a0 = rng.range(0.0, TAU);
            let v: [Vec3; 3] = std::array::from_fn(|i| {
                let a = a0 + i as f32 * TAU / 3.0 + rng.range(-0.4, 0.4);
                let r = rng.range(0.6, 0.9);
                c + r * (a.cos() * e1 + a.sin() * e2)
            });
            let n = (v[1] - v[0]).cross(v[2] - v[0]).normalize();
            let normals = rng.chance(0.5).then(|| {
                std::array::from_fn(|_| loop {
                    let m = (n + 0.5 * rng.in_ball(1.0)).normalize();
                    if m.dot(n) > 0.6 {
                        break m;
                    }
                })
            });
            vec![Shape::Triangle { vertices: v, normals }]
        }
        Kind::ConvexPolygon => {
            let (e1, e2) = frame(rng.direction());
            let sides = 3 + rng.below(6);
            let a0 = rng.range(0.0, TAU);
            let r = rng.range(0.6, 0.9);
            let vertices = (0..sides)
                .map(|i| {
                    let a = a0 + i as f32 * TAU / sides as f32;
                    c + r * (a.cos() * e1 + a.sin() * e2)
                })
                .collect();
            vec![Shape::Polygon { vertices }]
        }
        Kind::ConcavePolygon => {
            let (e1, e2) = frame(rng.direction());
            let flat: Vec<(f32, f32)> = if rng.chance(0.5) {
                // A star: alternating outer and inner radius.
                let points = 5 + rng.below(3);
                let (outer, inner) = (0.9, rng.range(0.3, 0.5));
                let a0 = rng.range(0.0, TAU);
                (0..2 * points)
                    .map(|i| {
                        let a = a0 + i as f32 * PI / points as f32;
                        let r = if i % 2 == 0 { outer } else { inner };
                        (r * a.cos(), r * a.sin())
                    })
                    .collect()
            } else {
                // An L, centred on its bounding square (half size 0.6, so corners at 0.85).
                let t = rng.range(0.4, 0.7);
                let l = [(0.0, 0.0), (1.0, 0.0), (1.0, t), (t, t), (t, 1.0), (0.0, 1.0)];
                l.iter().map(|&(x, y)| (1.2 * (x - 0.5), 1.2 * (y - 0.5))).collect()
            };
            let vertices = flat.into_iter().map(|(x, y)| c + x * e1 + y * e2).collect();
            vec![Shape::Polygon { vertices }]
        }
        Kind::Cone | Kind::Cylinder => {
            let axis = rng.direction();
            let half = rng.range(0.35, 0.65);
            let r0 = rng.range(0.25, 0.6);
            let r1 = match kind {
                Kind::Cylinder => r0,
                _ if rng.chance(0.5) => 0.0,
                _ => rng.range(0.05, 0.9 * r0),
            };
            let (r0, r1) = if rng.chance(0.5) { (r0, r1) } else { (r1, r0) };
            vec![Shape::Cone { base: c - axis * half, base_radius: r0, apex: c + axis * half, apex_radius: r1 }]
        }
        Kind::Tetrahedron => {
            let (e1, e2) = frame(rng.direction());
            let e3 = e1.cross(e2);
            let r = rng.range(0.6, 0.9);
            let corners = [Vec3::new(1.0, 1.0, 1.0), Vec3::new(1.0, -1.0, -1.0), Vec3::new(-1.0, 1.0, -1.0), Vec3::new(-1.0, -1.0, 1.0)]
                .map(|p| c + r / 3f32.sqrt() * (p.x * e1 + p.y * e2 + p.z * e3));
            let smooth = rng.chance(0.5);
            [[0, 1, 2], [0, 3, 1], [0, 2, 3], [1, 3, 2]]
                .iter()
                .map(|f| {
                    let vertices = f.map(|i| corners[i]);
                    let normals = smooth.then(|| vertices.map(|v| (v - c).normalize()));
                    Shape::Triangle { vertices, normals }
                })
                .collect()
        }
    }
}

fn plain_material(rng: &mut Rng, name: &str) -> Material {
    Material {
        name: name.into(),
        ambient: rng.range(0.05, 0.4),
        diffuse: rng.range(0.3, 0.9),
        specular: rng.range(0.0, 0.7),
        shininess: rng.range(2.0, 150.0),
        color: rng.color(0.15, 1.0),
        specular_color: rng.chance(0.3).then(|| rng.color(0.5, 1.0)),
        specular_model: if rng.chance(0.5) { SpecularModel::Phong } else { SpecularModel::BlinnPhong },
        metallic_f0: None,
        reflect: Vec3::ZERO,
        transmit: Vec3::ZERO,
        ior: 1.0,
        fresnel: false,
        checker: None,
    }
}

fn mirror_material(rng: &mut Rng) -> Material {
    let mut m = plain_material(rng, "mirror");
    m.diffuse *= 0.4;
    m.reflect = if rng.chance(0.5) { Vec3::splat(rng.range(0.4, 0.9)) } else { rng.color(0.3, 0.9) };
    m
}

fn glass_material(rng: &mut Rng) -> Material {
    let mut m = plain_material(rng, "glass");
    m.ambient *= 0.3;
    m.diffuse *= 0.2;
    m.reflect = Vec3::splat(rng.range(0.0, 0.2));
    m.transmit = if rng.chance(0.6) { Vec3::splat(rng.range(0.5, 0.95)) } else { rng.color(0.4, 0.95) };
    m.ior = rng.range(1.3, 1.7);
    m.fresnel = rng.chance(0.5);
    m
}

fn metallic_material(rng: &mut Rng) -> Material {
    let mut m = plain_material(rng, "metal");
    m.metallic_f0 = Some(rng.color(0.5, 1.0));
    m.diffuse *= 0.3;
    if rng.chance(0.5) {
        m.reflect = Vec3::splat(rng.range(0.1, 0.4));
    }
    m
}

fn light(rng: &mut Rng, count: usize) -> Light {
    let share = 1.0 / count as f32;
    let color = rng.color(0.6, 1.0);
    let azimuth = rng.range(0.0, TAU);
    let elevation = rng.range(35.0, 75.0).to_radians();
    let towards = Vec3::new(elevation.cos() * azimuth.cos(), elevation.sin(), elevation.cos() * azimuth.sin());
    if rng.chance(0.35) {
        return Light {
            kind: LightKind::Directional { direction: -towards },
            color,
            intensity: share * rng.range(0.7, 1.2),
            attenuation: Attenuation::None,
            enabled: true,
        };
    }
    let d = rng.range(6.0, 10.0);
    let (attenuation, intensity) = match rng.below(4) {
        0 => (Attenuation::InverseSquare, d * d * share * rng.range(0.7, 1.2)),
        1 => {
            let (c1, c2, c3) = (1.0, rng.range(0.0, 0.1), rng.range(0.0, 0.01));
            let at_d = c1 + c2 * d + c3 * d * d;
            (Attenuation::Polynomial { c1, c2, c3 }, at_d * share * rng.range(0.7, 1.2))
        }
        _ => (Attenuation::None, share * rng.range(0.7, 1.2)),
    };
    Light { kind: LightKind::Point { position: towards * d }, color, intensity, attenuation, enabled: true }
}

#[cfg(test)]
mod tests {
    use std::collections::BTreeMap;

    use glam::DVec3;
    use glint_scene::SHAPE_NAMES;

    use super::*;

    #[test]
    fn random_scenes_are_deterministic_varied_and_separated() {
        let mut names: BTreeMap<&str, usize> = BTreeMap::new();
        let mut features = [0usize; 8];
        for seed in 0..40 {
            let s = random_scene(seed);
            assert_eq!(s, random_scene(seed));
            assert_ne!(s, random_scene(seed + 1000));
            assert!(s.camera.basis().is_some());
            assert!((1..=16).contains(&s.render.max_depth));
            let lit = s.lights.iter().filter(|l| l.enabled).count();
            assert!((1..=3).contains(&lit));
            // Object 0 is the floor; every other object sits in a ball of its own.
            let balls: Vec<(DVec3, f64)> = s.objects[1..]
                .iter()
                .map(|o| {
                    let (lo, hi) = o.shapes.iter().filter_map(Shape::bounds).fold((Vec3::INFINITY, Vec3::NEG_INFINITY), |(a, b), (l, h)| (a.min(l), b.max(h)));
                    assert!(lo.y > FLOOR_Y + 0.25, "seed {seed}: object reaches down to {}", lo.y);
                    let c = ((lo + hi) / 2.0).as_dvec3();
                    let r = o.shapes.iter().flat_map(shape_points).map(|p| (p - c).length()).fold(0.0, f64::max);
                    (c, r)
                })
                .collect();
            for (a, (ca, ra)) in balls.iter().enumerate() {
                assert!(*ra <= f64::from(OBJECT_RADIUS) * 1.5);
                for (cb, rb) in &balls[a + 1..] {
                    assert!((*ca - *cb).length() - ra - rb > 0.1, "seed {seed}: objects too close");
                }
            }
            for shape in s.objects.iter().flat_map(|o| &o.shapes) {
                *names.entry(shape.name()).or_default() += 1;
                features[0] += usize::from(matches!(shape, Shape::Triangle { normals: Some(_), .. }));
            }
            features[1] += usize::from(s.depth_cue.is_some());
            features[2] += usize::from(s.render.shadow_mode == ShadowMode::Tinted);
            features[3] += usize::from(s.materials.iter().any(|m| m.is_transmissive()));
            features[4] += usize::from(s.materials.iter().any(|m| m.reflect.max_element() > 0.0));
            features[5] += usize::from(matches!(s.camera.projection, Projection::Orthographic { .. }));
            features[6] += usize::from(s.materials[0].checker.is_some());
            features[7] += usize::from(s.materials[1..].iter().any(|m| m.checker.is_some()));
        }
        // Every kind, by each name it has (a cone, a cylinder), so that
        // tests/differential.rs traces it on the GPU and the CPU.
        assert!(SHAPE_NAMES.iter().all(|name| names.get(name).is_some_and(|&n| n >= 10)), "{names:?}");
        assert!(features.iter().all(|&f| f >= 3), "{features:?}");
    }

    /// Points that bound a shape (vertices, sphere extremes, cone rims: the
    /// bounds' corners are too loose).
    fn shape_points(s: &Shape) -> Vec<DVec3> {
        match s {
            Shape::Sphere { center, radius } => {
                [DVec3::X, DVec3::NEG_X, DVec3::Y, DVec3::NEG_Y, DVec3::Z, DVec3::NEG_Z].map(|d| center.as_dvec3() + d * f64::from(*radius)).to_vec()
            }
            Shape::Triangle { vertices, .. } => vertices.iter().map(|v| v.as_dvec3()).collect(),
            Shape::Polygon { vertices } => vertices.iter().map(|v| v.as_dvec3()).collect(),
            Shape::Cone { base, base_radius, apex, apex_radius } => {
                let (e1, e2) = frame((*apex - *base).normalize());
                (0..64)
                    .flat_map(|k| {
                        let a = k as f32 * TAU / 64.0;
                        let dir = a.cos() * e1 + a.sin() * e2;
                        [*base + dir * *base_radius, *apex + dir * *apex_radius].map(Vec3::as_dvec3)
                    })
                    .collect()
            }
            Shape::Plane { .. } => unreachable!("only the floor is a plane"),
        }
    }
}
