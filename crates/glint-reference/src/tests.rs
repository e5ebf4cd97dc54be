//! Analytic checks of the reference tracer: every expected value is worked out
//! by hand from the model's equations.

use glam::{DVec3, Vec3};
use glint_scene::{
    Attenuation, Camera, DepthCue, Light, LightKind, Material, Object, Projection, RenderSettings, Scene,
    ShadowMode, Shape, SpecularModel,
};

use crate::*;

fn dv(v: Vec3) -> DVec3 {
    v.as_dvec3()
}

fn close(a: [f64; 3], b: DVec3, tol: f64) -> bool {
    (DVec3::from(a) - b).abs().max_element() <= tol
}

#[track_caller]
fn assert_close(a: [f64; 3], b: DVec3) {
    assert!(close(a, b, 1e-9), "got {a:?}, expected {b:?}");
}

fn camera(eye: Vec3, look_at: Vec3, projection: Projection) -> Camera {
    Camera { eye, look_at, up: Vec3::Y, projection }
}

fn scene(camera: Camera) -> Scene {
    Scene {
        width: 33,
        height: 33,
        background: Vec3::new(0.05, 0.1, 0.15),
        camera,
        ambient: Vec3::new(0.25, 0.5, 0.75),
        lights: Vec::new(),
        materials: Vec::new(),
        objects: Vec::new(),
        depth_cue: None,
        render: RenderSettings { cutoff: 0.0, ..RenderSettings::default() },
        animation: None,
        warnings: Vec::new(),
    }
}

fn add(scene: &mut Scene, material: Material, shapes: Vec<Shape>) -> u32 {
    scene.materials.push(material);
    scene.objects.push(Object { material: scene.materials.len() - 1, shapes });
    (scene.objects.len() - 1) as u32
}

/// Ambient-only material: its colour is k_a·I_a·O_d whatever the lights.
fn flat(color: Vec3, ka: f32) -> Material {
    Material { ambient: ka, diffuse: 0.0, specular: 0.0, color, ..Material::default() }
}

fn point_light(position: Vec3, color: Vec3, intensity: f32) -> Light {
    Light { kind: LightKind::Point { position }, color, intensity, attenuation: Attenuation::None, enabled: true }
}

fn directional(direction: Vec3) -> Light {
    Light { kind: LightKind::Directional { direction }, color: Vec3::ONE, intensity: 1.0, attenuation: Attenuation::None, enabled: true }
}

fn quad(center: Vec3, a: Vec3, b: Vec3) -> Shape {
    Shape::Polygon { vertices: vec![center - a - b, center + a - b, center + a + b, center - a + b] }
}

// ---------------------------------------------------------------- spheres, shading

#[test]
fn sphere_centre_pixel_depth() {
    let (eye, c, r) = (Vec3::new(1.0, 2.0, 5.0), Vec3::new(0.5, 0.25, -1.0), 0.75);
    let mut s = scene(camera(eye, c, Projection::Perspective { fov_y_degrees: 30.0 }));
    let id = add(&mut s, Material::default(), vec![Shape::Sphere { center: c, radius: r }]);
    let p = pixel(&s, 33, 33, 16, 16);
    let expected = (dv(eye) - dv(c)).length() - f64::from(r);
    assert!((p.depth - expected).abs() < 1e-9, "{} vs {expected}", p.depth);
    assert_eq!(p.object, Some(id));
    let corner = pixel(&s, 33, 33, 0, 0);
    assert_eq!(corner.depth, f64::INFINITY);
    assert_eq!(corner.object, None);
    assert_close(corner.rgb, dv(s.background));
}

/// A sphere straight ahead, a point light up and to the right: the centre pixel by hand.
fn lit_sphere(material: Material, attenuation: Attenuation) -> (Scene, [f64; 3], DVec3) {
    let eye = Vec3::new(0.0, 0.0, 10.0);
    let mut s = scene(camera(eye, Vec3::ZERO, Projection::Perspective { fov_y_degrees: 30.0 }));
    add(&mut s, material, vec![Shape::Sphere { center: Vec3::ZERO, radius: 2.0 }]);
    let mut light = point_light(Vec3::new(3.0, 4.0, 6.0), Vec3::new(1.0, 0.75, 0.5), 1.5);
    light.attenuation = attenuation;
    s.lights.push(light);
    let got = pixel(&s, 33, 33, 16, 16).rgb;
    // Hit (0, 0, 2), N = V = +z, L = normalize((3, 4, 4)), H = normalize(L + V).
    let m = &s.materials[0];
    let n = DVec3::Z;
    let to = DVec3::new(3.0, 4.0, 4.0);
    let (l, dist) = (to / to.length(), to.length());
    let v = DVec3::Z;
    let h = (l + v).normalize();
    let il = DVec3::new(1.0, 0.75, 0.5) * 1.5 * attenuation.factor(dist);
    let od = dv(m.color);
    let lobe = match m.specular_model {
        SpecularModel::BlinnPhong => n.dot(h),
        SpecularModel::Phong => (2.0 * n.dot(l) * n - l).dot(v),
    }
    .powf(f64::from(m.shininess));
    let spec = match m.metallic_f0 {
        Some(f0) => (dv(f0) + (DVec3::ONE - dv(f0)) * (1.0 - v.dot(h)).powi(5)) * lobe,
        None => f64::from(m.specular) * dv(m.specular_color.unwrap_or(Vec3::ONE)) * lobe,
    };
    let expected = f64::from(m.ambient) * dv(s.ambient) * od + il * (f64::from(m.diffuse) * od * n.dot(l) + spec);
    (s, got, expected)
}

fn shiny() -> Material {
    Material {
        ambient: 0.25,
        diffuse: 0.625,
        specular: 0.5,
        shininess: 20.0,
        color: Vec3::new(0.875, 0.5, 0.25),
        specular_model: SpecularModel::BlinnPhong,
        ..Material::default()
    }
}

#[test]
fn lit_sphere_blinn_phong() {
    let (_, got, expected) = lit_sphere(shiny(), Attenuation::None);
    assert_close(got, expected);
    // Written out once more with the numbers: N·L = 4/√41, N·H from H = (L + Z)/|L + Z|.
    let nl = 4.0 / 41f64.sqrt();
    let nh = (nl + 1.0) / (2.0 + 2.0 * nl).sqrt();
    let r = 0.25 * 0.25 * 0.875 + 1.5 * (0.625 * 0.875 * nl + 0.5 * nh.powi(20));
    assert!((got[0] - r).abs() < 1e-9, "{} vs {r}", got[0]);
}

#[test]
fn lit_sphere_phong_coloured_highlight() {
    let m = Material { specular_model: SpecularModel::Phong, specular_color: Some(Vec3::new(0.5, 1.0, 0.25)), ..shiny() };
    let (_, got, expected) = lit_sphere(m, Attenuation::None);
    assert_close(got, expected);
    // R·V = 2(N·L)(N·V) − L·V = N·L for V = N.
    let nl = 4.0 / 41f64.sqrt();
    let g = 0.25 * 0.5 * 0.5 + 1.5 * 0.75 * (0.625 * 0.5 * nl + 0.5 * nl.powi(20));
    assert!((got[1] - g).abs() < 1e-9);
}

#[test]
fn lit_sphere_metallic_and_attenuated() {
    let m = Material { metallic_f0: Some(Vec3::new(0.95, 0.65, 0.5)), ..shiny() };
    let (_, got, expected) = lit_sphere(m.clone(), Attenuation::None);
    assert_close(got, expected);
    let (_, got, expected) = lit_sphere(m.clone(), Attenuation::InverseSquare);
    assert_close(got, expected);
    let (_, got, expected) = lit_sphere(m, Attenuation::Polynomial { c1: 0.5, c2: 0.25, c3: 0.125 });
    assert_close(got, expected);
}

#[test]
fn zero_shininess_lobe_is_zero_behind_the_highlight() {
    // Phong with n = 0: the lobe is 1 where R·V > 0 and 0 (not 0^0 = 1) where R·V ≤ 0.
    let m = Material { specular_model: SpecularModel::Phong, shininess: 0.0, ..shiny() };
    let (_, got, expected) = lit_sphere(m.clone(), Attenuation::None);
    assert_close(got, expected);
    // Seen from (0, −8, 10) the top (0, 0, 2) of the sphere has V = (0, −1, 1)/√2; a
    // light far along −y, just above the horizon, reflects to R ≈ +y: R·V < 0.
    let mut s = lit_sphere(m, Attenuation::None).0;
    s.lights[0] = point_light(Vec3::new(0.0, -40.0, 2.5), Vec3::ONE, 1.0);
    let (eye, p, n) = (DVec3::new(0.0, -8.0, 10.0), DVec3::new(0.0, 0.0, 2.0), DVec3::Z);
    let l = (DVec3::new(0.0, -40.0, 2.5) - p).normalize();
    assert!((2.0 * n.dot(l) * n - l).dot((eye - p).normalize()) < 0.0);
    let mm = &s.materials[0];
    let expected = f64::from(mm.ambient) * dv(s.ambient) * dv(mm.color) + f64::from(mm.diffuse) * dv(mm.color) * n.dot(l);
    assert_close(trace_ray(&s, eye, p - eye), expected);
}

#[test]
fn depth_cue_blends_hits_but_not_background() {
    let (mut s, plain, _) = lit_sphere(shiny(), Attenuation::None);
    let dc = DepthCue { color: Vec3::new(0.5, 0.25, 1.0), near: 4.0, far: 12.0, near_scale: 1.0, far_scale: 0.25 };
    s.depth_cue = Some(dc);
    let got = pixel(&s, 33, 33, 16, 16).rgb;
    let so = 1.0 - 0.75 * (8.0 - 4.0) / 8.0; // hit at distance 8
    assert_close(got, so * DVec3::from(plain) + (1.0 - so) * dv(dc.color));
    assert_close(pixel(&s, 33, 33, 0, 0).rgb, dv(s.background));
}

// ---------------------------------------------------------------- shadows

/// A floor at y = −1, an occluder above (0, −1, 0), a point light at (0, 5, 0).
fn shadow_scene(occluders: Vec<(Material, Vec3)>) -> Scene {
    let mut s = scene(camera(Vec3::new(0.0, 3.0, 6.0), Vec3::new(0.0, -1.0, 0.0), Projection::Perspective { fov_y_degrees: 40.0 }));
    let floor = Material { ambient: 0.5, diffuse: 0.75, specular: 0.25, shininess: 8.0, color: Vec3::new(0.8, 0.6, 0.4), ..Material::default() };
    add(&mut s, floor, vec![quad(Vec3::new(0.0, -1.0, 0.0), Vec3::X * 20.0, Vec3::Z * 20.0)]);
    for (m, c) in occluders {
        add(&mut s, m, vec![Shape::Sphere { center: c, radius: 0.5 }]);
    }
    s.lights.push(point_light(Vec3::new(0.0, 5.0, 0.0), Vec3::ONE, 1.0));
    s
}

fn glass(transmit: Vec3) -> Material {
    Material { transmit, ior: 1.5, ..Material::default() }
}

#[test]
fn shadowed_point_is_ambient_only() {
    let s = shadow_scene(vec![(Material::default(), Vec3::new(0.0, 1.0, 0.0))]);
    let eye = dv(s.camera.eye);
    let floor = &s.materials[0];
    let ambient = f64::from(floor.ambient) * dv(s.ambient) * dv(floor.color);
    let target = DVec3::new(0.1, -1.0, 0.2);
    let mut stats = RayStats::default();
    let got = Tracer::new(&s).trace(eye, target - eye, &mut stats);
    assert_close(got, ambient);
    assert_eq!(stats, RayStats { eye_hit: 1, shadow: 1, ..RayStats::default() });

    // Without shadows the same point gets the full diffuse and specular terms.
    let mut lit = s.clone();
    lit.render.shadows = false;
    let got = trace_ray(&lit, eye, target - eye);
    let (n, v) = (DVec3::Y, (eye - target).normalize());
    let l = (DVec3::new(0.0, 5.0, 0.0) - target).normalize();
    let h = (l + v).normalize();
    let direct = 0.75 * dv(floor.color) * n.dot(l) + DVec3::splat(0.25 * n.dot(h).powf(8.0));
    assert_close(got, ambient + direct);

    // A floor point away from the occluder is lit.
    let target = DVec3::new(2.0, -1.0, 0.0);
    assert!(!close(trace_ray(&s, eye, target - eye), ambient, 1e-3));
}

#[test]
fn tinted_shadows_multiply_transmittance_once_per_primitive() {
    let eye = DVec3::new(0.0, 3.0, 6.0);
    let target = DVec3::new(0.1, -1.0, 0.2);
    let (t1, t2) = (Vec3::new(0.5, 0.25, 0.75), Vec3::new(0.5, 1.0, 0.25));
    let unshadowed = |s: &Scene| {
        let mut s = s.clone();
        s.render.shadows = false;
        DVec3::from(trace_ray(&s, eye, target - eye))
    };
    let floor = |s: &Scene| {
        let m = &s.materials[0];
        f64::from(m.ambient) * dv(s.ambient) * dv(m.color)
    };

    let mut s = shadow_scene(vec![(glass(t1), Vec3::new(0.0, 1.0, 0.0))]);
    let (lit, ambient) = (unshadowed(&s), floor(&s));
    assert_close(trace_ray(&s, eye, target - eye), ambient);
    s.render.shadow_mode = ShadowMode::Tinted;
    assert_close(trace_ray(&s, eye, target - eye), ambient + dv(t1) * (lit - ambient));

    let mut s = shadow_scene(vec![(glass(t1), Vec3::new(0.0, 1.0, 0.0)), (glass(t2), Vec3::new(0.0, 2.5, 0.0))]);
    s.render.shadow_mode = ShadowMode::Tinted;
    assert_close(trace_ray(&s, eye, target - eye), ambient + dv(t1) * dv(t2) * (lit - ambient));

    let mut s = shadow_scene(vec![(glass(t1), Vec3::new(0.0, 1.0, 0.0)), (Material::default(), Vec3::new(0.0, 2.5, 0.0))]);
    s.render.shadow_mode = ShadowMode::Tinted;
    assert_close(trace_ray(&s, eye, target - eye), ambient);
}

#[test]
fn occluders_beyond_a_point_light_do_not_shadow() {
    let mut s = shadow_scene(vec![(Material::default(), Vec3::new(0.0, 6.0, 0.0))]);
    let eye = dv(s.camera.eye);
    let target = DVec3::new(0.1, -1.0, 0.2);
    let with = trace_ray(&s, eye, target - eye);
    s.render.shadows = false;
    assert_close(with, DVec3::from(trace_ray(&s, eye, target - eye)));
}

// ---------------------------------------------------------------- reflection, refraction

#[test]
fn mirror_sees_wall_times_reflectance() {
    let mut s = scene(camera(Vec3::ZERO, Vec3::new(0.0, 0.0, -1.0), Projection::Perspective { fov_y_degrees: 40.0 }));
    s.ambient = Vec3::ONE;
    let km = Vec3::new(0.8, 0.5, 0.25);
    let mirror = Material { reflect: km, ..flat(Vec3::ONE, 0.0) };
    add(&mut s, mirror, vec![quad(Vec3::new(0.0, 0.0, -5.0), Vec3::X * 4.0, Vec3::Y * 4.0)]);
    let wall = Vec3::new(0.2, 0.4, 0.6);
    add(&mut s, flat(wall, 1.0), vec![quad(Vec3::new(0.0, 0.0, 5.0), Vec3::X * 40.0, Vec3::Y * 40.0)]);
    let img = render(&s, 33, 33);
    for (i, j) in [(16, 16), (0, 0), (32, 5), (7, 30)] {
        assert_close(img.rgb[img.index(i, j)], dv(km) * dv(wall));
        assert_eq!(img.object[img.index(i, j)], Some(0));
    }
    assert!((img.depth[img.index(16, 16)] - 5.0).abs() < 1e-12);
    assert_eq!(img.stats, RayStats { eye_hit: 33 * 33, reflect: 33 * 33, ..RayStats::default() });

    // max_depth 1: no mirror ray, only the mirror's own (black) local colour.
    s.render.max_depth = 1;
    assert_close(pixel(&s, 33, 33, 16, 16).rgb, DVec3::ZERO);
    // Reflections off: likewise.
    s.render.max_depth = 5;
    s.render.reflections = false;
    assert_close(pixel(&s, 33, 33, 16, 16).rgb, DVec3::ZERO);
}

/// A unit glass sphere of ambient-only material (local colour 0.5 everywhere).
fn inner_sphere(ior: f32) -> Scene {
    let mut s = scene(camera(Vec3::new(0.0, 0.0, 5.0), Vec3::ZERO, Projection::Perspective { fov_y_degrees: 30.0 }));
    s.ambient = Vec3::ONE;
    s.render.max_depth = 2;
    let m = Material { transmit: Vec3::ONE, ior, ..flat(Vec3::splat(0.5), 1.0) };
    add(&mut s, m, vec![Shape::Sphere { center: Vec3::ZERO, radius: 1.0 }]);
    s
}

#[test]
fn total_internal_reflection_sends_transmission_to_the_mirror_ray() {
    // From (0, 0.8, 0) along +x the ray meets the sphere from inside at (0.6, 0.8, 0)
    // with cos θ_i = 0.6, sin θ_i = 0.8 > 1/1.5: totally reflected, the whole k_t
    // goes to the mirror ray, which hits the sphere again (local 0.5, depth 2).
    let s = inner_sphere(1.5);
    let t = Tracer::new(&s);
    let (o, d) = (DVec3::new(0.0, 0.8, 0.0), DVec3::X);
    let hit = t.nearest_hit(o, d, 0.0, f64::INFINITY).unwrap();
    assert!(hit.backface);
    assert!((hit.point - DVec3::new(0.6, 0.8, 0.0)).length() < 1e-12);
    assert!((hit.geometric - DVec3::new(-0.6, -0.8, 0.0)).length() < 1e-12);
    assert!(refract(d, hit.shading, 1.5).is_none());
    let mut stats = RayStats::default();
    assert_close(t.trace(o, d, &mut stats), DVec3::splat(1.0));
    assert_eq!(stats, RayStats { eye_hit: 1, reflect: 1, ..RayStats::default() });

    // With ior 1.1 (sin θ_c = 0.909 > 0.8) the ray leaves into the background.
    let s = inner_sphere(1.1);
    let mut stats = RayStats::default();
    assert_close(Tracer::new(&s).trace(o, d, &mut stats), DVec3::splat(0.5) + dv(s.background));
    assert_eq!(stats, RayStats { eye_hit: 1, refract: 1, ..RayStats::default() });
}

#[test]
fn refraction_obeys_snell() {
    let n = DVec3::new(0.0, 1.0, 0.0);
    let d = DVec3::new(0.6, -0.8, 0.0);
    let t = refract(d, n, 1.0 / 1.5).unwrap();
    assert!((t.length() - 1.0).abs() < 1e-12);
    assert!((t.x - 0.6 / 1.5).abs() < 1e-12, "sin θ_t = sin θ_i / 1.5");
    assert!(t.y < 0.0);
    // Leaving the denser side: sin θ_t = 1.5·0.6 = 0.9 is possible, 1.5·0.8 is not.
    let t = refract(d, n, 1.5).unwrap();
    assert!((t.x - 0.9).abs() < 1e-12);
    assert!(refract(DVec3::new(0.8, -0.6, 0.0), n, 1.5).is_none());
}

#[test]
fn fresnel_at_normal_incidence_is_f0() {
    // Head-on through the centre: F = F0 = ((1 − 1.5)/(1 + 1.5))² = 0.04 at the front;
    // the mirror ray misses (background), the refracted one hits the back at depth 2.
    let mut s = inner_sphere(1.5);
    s.materials[0].fresnel = true;
    s.materials[0].transmit = Vec3::splat(0.75);
    s.materials[0].reflect = Vec3::splat(0.125);
    let mut stats = RayStats::default();
    let got = Tracer::new(&s).trace(DVec3::new(0.0, 0.0, 5.0), -DVec3::Z, &mut stats);
    let f = 0.04;
    let kr = 0.125 + 0.75 * f;
    let kt = 0.75 * (1.0 - f);
    assert_close(got, DVec3::splat(0.5) + kr * dv(s.background) + kt * 0.5);
    assert_eq!(stats, RayStats { eye_hit: 1, reflect: 1, refract: 1, ..RayStats::default() });
    assert!((schlick(0.04, 1.0) - 0.04).abs() < 1e-15 && (schlick(0.04, 0.0) - 1.0).abs() < 1e-15);
}

// ---------------------------------------------------------------- cones, polygons, triangles

fn ortho_scene(eye: Vec3) -> Scene {
    scene(camera(eye, Vec3::ZERO, Projection::Orthographic { height: 4.0 }))
}

#[test]
fn cylinder_and_cone_silhouettes() {
    // 40 × 40 pixels over a 4 × 4 view: pixel (i, j) centre at x = −1.95 + 0.1 i,
    // y = 1.95 − 0.1 j.
    for (r0, r1) in [(1.0f32, 1.0f32), (1.2, 0.3), (0.0, 1.5)] {
        let mut s = ortho_scene(Vec3::new(0.0, 0.0, 10.0));
        add(&mut s, Material::default(), vec![Shape::Cone {
            base: Vec3::new(0.0, -1.5, 0.0),
            base_radius: r0,
            apex: Vec3::new(0.0, 1.5, 0.0),
            apex_radius: r1,
        }]);
        let img = render(&s, 40, 40);
        let mut hits = 0;
        for j in 0..40 {
            for i in 0..40 {
                let (x, y) = (-1.95 + 0.1 * f64::from(i), 1.95 - 0.1 * f64::from(j));
                let r = f64::from(r0) + (f64::from(r1) - f64::from(r0)) * (y + 1.5) / 3.0;
                let inside = y.abs() < 1.5 && x.abs() < r;
                if (x.abs() - r).abs() < 1e-6 {
                    continue;
                }
                let k = img.index(i, j);
                assert_eq!(img.object[k].is_some(), inside, "r0 {r0} r1 {r1} pixel ({i}, {j}) x {x} y {y} r {r}");
                if inside {
                    hits += 1;
                    // The front wall is at z = √(r² − x²).
                    let z = (r * r - x * x).sqrt();
                    assert!((img.depth[k] - (10.0 - z)).abs() < 1e-9, "depth {} vs {}", img.depth[k], 10.0 - z);
                }
            }
        }
        assert!(hits > 100);
    }
}

#[test]
fn cylinder_row_matches_radius() {
    let mut s = ortho_scene(Vec3::new(0.0, 0.0, 10.0));
    add(&mut s, Material::default(), vec![Shape::Cone {
        base: Vec3::new(0.0, -1.5, 0.0),
        base_radius: 1.0,
        apex: Vec3::new(0.0, 1.5, 0.0),
        apex_radius: 1.0,
    }]);
    let row: Vec<bool> = (0..40).map(|i| pixel(&s, 40, 40, i, 20).object.is_some()).collect();
    // x = −0.95 … 0.95 are inside: pixels 10 … 29.
    let expected: Vec<bool> = (0..40).map(|i| (10..=29).contains(&i)).collect();
    assert_eq!(row, expected);
}

#[test]
fn cone_normals_and_inside() {
    let mut s = ortho_scene(Vec3::new(0.0, 0.0, 10.0));
    add(&mut s, Material::default(), vec![Shape::Cone {
        base: Vec3::new(0.0, -1.5, 0.0),
        base_radius: 1.25,
        apex: Vec3::new(0.0, 1.5, 0.0),
        apex_radius: 0.25,
    }]);
    let t = Tracer::new(&s);
    // r(0) = 0.75; slope k = −1/3, so N ∝ radial − k·a = (0, 1/3, 1).
    let hit = t.nearest_hit(DVec3::new(0.0, 0.0, 10.0), -DVec3::Z, 0.0, f64::INFINITY).unwrap();
    assert!((hit.t - 9.25).abs() < 1e-12);
    assert!((hit.geometric - DVec3::new(0.0, 1.0 / 3.0, 1.0).normalize()).length() < 1e-12);
    assert!(!hit.backface);
    // From inside (an open surface), the far wall is met from the back.
    let hit = t.nearest_hit(DVec3::ZERO, DVec3::X, 0.0, f64::INFINITY).unwrap();
    assert!(hit.backface);
    assert!((hit.t - 0.75).abs() < 1e-12);
    assert!((hit.geometric - DVec3::new(-1.0, -1.0 / 3.0, 0.0).normalize()).length() < 1e-12);
    // Along the axis of an open cylinder nothing is hit.
    let mut s = ortho_scene(Vec3::new(0.0, 10.0, 0.0));
    s.camera.up = Vec3::Z;
    add(&mut s, Material::default(), vec![Shape::Cone {
        base: Vec3::new(0.0, -1.5, 0.0),
        base_radius: 1.0,
        apex: Vec3::new(0.0, 1.5, 0.0),
        apex_radius: 1.0,
    }]);
    assert_eq!(pixel(&s, 41, 41, 20, 20).object, None);
}

#[test]
fn concave_polygon_notch_is_background() {
    // An L covering [−1, 1]² minus the notch (0, 1) × (0, 1), in the z = 0 plane,
    // in both orientations.
    let l = [(0., 0.), (2., 0.), (2., 1.), (1., 1.), (1., 2.), (0., 2.)].map(|(x, y)| Vec3::new(x - 1.0, y - 1.0, 0.0));
    for reversed in [false, true] {
        let mut v = l.to_vec();
        if reversed {
            v.reverse();
        }
        let mut s = ortho_scene(Vec3::new(0.0, 0.0, 5.0));
        add(&mut s, Material::default(), vec![Shape::Polygon { vertices: v }]);
        let img = render(&s, 40, 40);
        for j in 0..40 {
            for i in 0..40 {
                let (x, y) = (-1.95 + 0.1 * f64::from(i), 1.95 - 0.1 * f64::from(j));
                let inside = x.abs() < 1.0 && y.abs() < 1.0 && !(x > 0.0 && y > 0.0);
                assert_eq!(img.object[img.index(i, j)].is_some(), inside, "({i}, {j})");
            }
        }
        assert_close(img.rgb[img.index(25, 14)], dv(s.background));
    }
}

#[test]
fn star_polygon_even_odd() {
    // A five-pointed star drawn as a pentagram (self-intersecting): the even-odd rule
    // leaves its central pentagon empty. Tip radius 1 in the z = 0 plane.
    let tips: Vec<Vec3> = (0..5)
        .map(|k| {
            let a = std::f32::consts::FRAC_PI_2 + (2 * k) as f32 * std::f32::consts::TAU / 5.0;
            Vec3::new(a.cos(), a.sin(), 0.0)
        })
        .collect();
    let mut s = ortho_scene(Vec3::new(0.0, 0.0, 5.0));
    add(&mut s, Material::default(), vec![Shape::Polygon { vertices: tips }]);
    let t = Tracer::new(&s);
    let hit_at = |x: f64, y: f64| t.nearest_hit(DVec3::new(x, y, 5.0), -DVec3::Z, 0.0, f64::INFINITY).is_some();
    assert!(!hit_at(0.0, 0.0), "centre pentagon is crossed twice");
    assert!(hit_at(0.0, 0.8), "top point");
    assert!(!hit_at(0.0, -0.9), "between the lower points");
    assert!(!hit_at(1.2, 0.0));
}

#[test]
fn smooth_triangle_interpolates_normals() {
    let mut s = ortho_scene(Vec3::new(0.0, 0.0, 5.0));
    let v = [Vec3::new(-1.0, -1.0, 0.0), Vec3::new(1.0, -1.0, 0.0), Vec3::new(0.0, 1.0, 0.0)];
    let n = [Vec3::new(-0.6, 0.0, 0.8), Vec3::new(0.6, 0.0, 0.8), Vec3::new(0.0, 0.6, 0.8)];
    add(&mut s, Material::default(), vec![Shape::Triangle { vertices: v, normals: Some(n) }]);
    let t = Tracer::new(&s);
    let hit = |x: f64, y: f64, z: f64| t.nearest_hit(DVec3::new(x, y, z), DVec3::new(0.0, 0.0, -z.signum()), 0.0, f64::INFINITY);
    // Centroid (0, −1/3): normalize(Σ n_i / 3).
    let h = hit(0.0, -1.0 / 3.0, 5.0).unwrap();
    assert!((h.shading - DVec3::new(0.0, 0.2, 0.8).normalize()).length() < 1e-7);
    assert!((h.geometric - DVec3::Z).length() < 1e-12);
    // Midpoint of edge v0 v1: the average of n0 and n1.
    let h = hit(0.0, -0.999999, 5.0).unwrap();
    assert!((h.shading - DVec3::Z).length() < 1e-5);
    // From behind, both normals flip.
    let h = hit(0.0, -1.0 / 3.0, -5.0).unwrap();
    assert!(h.backface && (h.shading - DVec3::new(0.0, -0.2, -0.8).normalize()).length() < 1e-7);
    // Outside the triangle.
    assert!(hit(0.9, 0.9, 5.0).is_none());
}

// ---------------------------------------------------------------- ray counts

/// Orthographic 4 × 4 view of a unit sphere: pixel centres at ±0.5, ±1.5, so the
/// middle 2 × 2 pixels hit and the other 12 miss. Light from the camera's side.
fn counting_scene(m: Material) -> Scene {
    let mut s = ortho_scene(Vec3::new(0.0, 0.0, 5.0));
    add(&mut s, m, vec![Shape::Sphere { center: Vec3::ZERO, radius: 1.0 }]);
    s.lights.push(directional(-Vec3::Z));
    s.render.cutoff = 1.0 / 256.0;
    s
}

#[test]
fn ray_counts_mirror_sphere() {
    let s = counting_scene(Material { reflect: Vec3::splat(0.5), ..Material::default() });
    let img = render(&s, 4, 4);
    // 4 hits, each lit (one shadow ray) and each spawning a mirror ray that leaves
    // the convex sphere and misses.
    assert_eq!(img.stats, RayStats { eye_hit: 4, eye_miss: 12, shadow: 4, reflect: 4, refract: 0 });
    let hits: Vec<(u32, u32)> = (0..4).flat_map(|j| (0..4).map(move |i| (i, j))).filter(|&(i, j)| img.object[img.index(i, j)].is_some()).collect();
    assert_eq!(hits, [(1, 1), (2, 1), (1, 2), (2, 2)]);
    assert_eq!(img.pixel_stats[img.index(1, 1)], RayStats { eye_hit: 1, shadow: 1, reflect: 1, ..RayStats::default() });
    assert_eq!(img.pixel_stats[img.index(0, 0)], RayStats { eye_miss: 1, ..RayStats::default() });

    // A switched-off light casts nothing; shadows off cast nothing.
    let mut off = s.clone();
    off.lights.push(Light { enabled: false, ..point_light(Vec3::new(0.0, 0.0, 3.0), Vec3::ONE, 1.0) });
    assert_eq!(render(&off, 4, 4).stats, img.stats);
    let mut no_shadows = s.clone();
    no_shadows.render.shadows = false;
    assert_eq!(render(&no_shadows, 4, 4).stats.shadow, 0);
    // A cutoff above k_m stops the mirror rays; max_depth 1 too.
    let mut cut = s.clone();
    cut.render.cutoff = 0.6;
    assert_eq!(render(&cut, 4, 4).stats.reflect, 0);
    let mut shallow = s;
    shallow.render.max_depth = 1;
    assert_eq!(render(&shallow, 4, 4).stats.reflect, 0);
}

#[test]
fn ray_counts_glass_sphere() {
    let mut s = counting_scene(Material { reflect: Vec3::splat(0.1), transmit: Vec3::splat(0.9), ior: 1.5, ..Material::default() });
    s.render.max_depth = 2;
    // Each of the 4 hits: one shadow ray, a mirror ray (misses) and a refracted ray
    // that meets the back of the sphere from inside at depth 2, where the flipped
    // normal faces +z, the light's side: one more (blocked) shadow ray, no children.
    let img = render(&s, 4, 4);
    assert_eq!(img.stats, RayStats { eye_hit: 4, eye_miss: 12, shadow: 8, reflect: 4, refract: 4 });
}

// ---------------------------------------------------------------- random scenes

#[test]
fn random_scenes_render_finite_and_mostly_stable() {
    for seed in 0..12 {
        let s = random_scene(seed);
        let t = Tracer::new(&s);
        let img = t.render(s.width, s.height);
        assert!(img.rgb.iter().flatten().all(|c| c.is_finite() && *c >= 0.0), "seed {seed}");
        assert!(img.stats.eye_hit > 200, "seed {seed}: the cluster fills part of the view");
        assert_eq!(img.stats.eye_hit + img.stats.eye_miss, u64::from(s.width * s.height));
        let mask = t.stability_mask(s.width, s.height, 1e-3);
        let stable = mask.iter().filter(|&&m| m).count();
        assert!(stable * 10 >= mask.len() * 7, "seed {seed}: only {stable} of {} pixels stable", mask.len());
        // Single-pixel entry point agrees with the render.
        let (i, j) = (s.width / 2, s.height / 2);
        let p = t.pixel(s.width, s.height, i, j);
        assert_eq!(p.rgb, img.rgb[img.index(i, j)]);
    }
}
