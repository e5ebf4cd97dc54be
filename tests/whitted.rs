//! The Whitted model term by term on the GPU, each against the equation
//! evaluated on the host in f64 at chosen pixels.

mod support;

use glam::DVec3;
use glint_scene::Ray;
use support::{assert_close, parse, render};

const TOL: f64 = 1.0 / 255.0;

/// A 64×64 perspective view of a unit sphere at the origin, with `extra` TOML.
fn sphere_scene(material: &str, extra: &str) -> String {
    format!(
        r#"
[image]
width = 64
height = 64
[camera]
eye = [0, 0, 4]
look_at = [0, 0, 0]
fov = 40
[material.m]
{material}
[[object]]
type = "sphere"
center = [0, 0, 0]
radius = 1
material = "m"
{extra}
"#
    )
}

fn sphere_hit(ray: &Ray) -> Option<DVec3> {
    let b = ray.origin.dot(ray.direction);
    let disc = b * b - (ray.origin.length_squared() - 1.0);
    (disc >= 0.0).then(|| ray.origin + (-b - disc.sqrt()) * ray.direction)
}

/// Evaluates `f(point, normal, view)` at every pixel whose centre ray hits the
/// unit sphere and compares with the GPU image.
fn check_sphere(scene_toml: &str, f: impl Fn(DVec3, DVec3, DVec3) -> DVec3) -> usize {
    let scene = parse(scene_toml);
    let (image, _) = render(&scene);
    let mut checked = 0;
    for y in (2..62).step_by(3) {
        for x in (2..62).step_by(3) {
            let ray = scene.camera.ray(64, 64, f64::from(x) + 0.5, f64::from(y) + 0.5).unwrap();
            let Some(p) = sphere_hit(&ray) else { continue };
            let n = p.normalize();
            if n.dot(-ray.direction) < 0.05 {
                continue; // the silhouette
            }
            assert_close(image.linear_at(x, y), f(p, n, -ray.direction).to_array(), TOL, &format!("({x}, {y})"));
            checked += 1;
        }
    }
    assert!(checked > 50);
    checked
}

const LIGHT: DVec3 = DVec3::new(2.0, 3.0, 4.0);
const POINT_LIGHT: &str = "[[light]]\ntype = \"point\"\nposition = [2, 3, 4]\ncolor = [0.9, 0.8, 0.6]\n";
const IL: DVec3 = DVec3::new(0.9, 0.8, 0.6);

#[test]
fn ambient_alone() {
    check_sphere(
        &sphere_scene("color = [0.8, 0.4, 0.2]\nka = 0.7\nkd = 0\nks = 0", "[ambient]\ncolor = [0.5, 1, 0.25]\nintensity = 0.8"),
        |_, _, _| 0.7 * DVec3::new(0.4, 0.8, 0.2) * DVec3::new(0.8, 0.4, 0.2),
    );
}

#[test]
fn lambert_alone() {
    check_sphere(&sphere_scene("color = [0.8, 0.4, 0.2]\nka = 0\nkd = 0.9\nks = 0", POINT_LIGHT), |p, n, _| {
        0.9 * IL * DVec3::new(0.8, 0.4, 0.2) * n.dot((LIGHT - p).normalize()).max(0.0)
    });
}

fn phong_lobe(p: DVec3, n: DVec3, v: DVec3, shininess: f64) -> f64 {
    let l = (LIGHT - p).normalize();
    if n.dot(l) <= 0.0 {
        return 0.0;
    }
    let r = 2.0 * n.dot(l) * n - l;
    r.dot(v).max(0.0).powf(shininess)
}

fn blinn_lobe(p: DVec3, n: DVec3, v: DVec3, shininess: f64) -> f64 {
    let l = (LIGHT - p).normalize();
    if n.dot(l) <= 0.0 {
        return 0.0;
    }
    n.dot((l + v).normalize()).max(0.0).powf(shininess)
}

#[test]
fn phong_highlight_alone_with_white_highlights() {
    check_sphere(
        &sphere_scene("color = 1\nka = 0\nkd = 0\nks = 0.8\nshininess = 12\nmodel = \"phong\"", POINT_LIGHT),
        |p, n, v| 0.8 * IL * phong_lobe(p, n, v, 12.0),
    );
}

#[test]
fn blinn_highlight_alone_with_coloured_highlights() {
    check_sphere(
        &sphere_scene(
            "color = 1\nka = 0\nkd = 0\nks = 0.8\nshininess = 12\nmodel = \"blinn\"\nspecular_color = [1, 0.5, 0.25]",
            POINT_LIGHT,
        ),
        |p, n, v| 0.8 * IL * DVec3::new(1.0, 0.5, 0.25) * blinn_lobe(p, n, v, 12.0),
    );
}

#[test]
fn metallic_highlight_follows_schlick() {
    let f0 = DVec3::new(1.0, 0.7, 0.3);
    check_sphere(
        &sphere_scene("color = 1\nka = 0\nkd = 0\nks = 0.8\nshininess = 8\nmodel = \"blinn\"\nmetallic = [1, 0.7, 0.3]", POINT_LIGHT),
        |p, n, v| {
            let l = (LIGHT - p).normalize();
            let h = (l + v).normalize();
            let f = f0 + (DVec3::ONE - f0) * (1.0 - v.dot(h)).clamp(0.0, 1.0).powi(5);
            IL * f * blinn_lobe(p, n, v, 8.0)
        },
    );
}

/// The brightest pixel of a specular-only render sits where the host's equation
/// peaks, for both lobes, and the lobes differ as their equations say.
#[test]
fn highlights_peak_at_the_predicted_pixel() {
    for (model, lobe) in [("phong", phong_lobe as fn(DVec3, DVec3, DVec3, f64) -> f64), ("blinn", blinn_lobe)] {
        let scene = parse(&sphere_scene(
            &format!("color = 1\nka = 0\nkd = 0\nks = 1\nshininess = 50\nmodel = \"{model}\""),
            POINT_LIGHT,
        ));
        let (image, _) = render(&scene);
        let mut gpu_best = (0.0f32, (0, 0));
        let mut host_best = (0.0f64, (0, 0));
        for y in 0..64 {
            for x in 0..64 {
                let v = image.linear_at(x, y)[0];
                if v > gpu_best.0 {
                    gpu_best = (v, (x, y));
                }
                let ray = scene.camera.ray(64, 64, f64::from(x) + 0.5, f64::from(y) + 0.5).unwrap();
                if let Some(p) = sphere_hit(&ray) {
                    let h = lobe(p, p.normalize(), -ray.direction, 50.0);
                    if h > host_best.0 {
                        host_best = (h, (x, y));
                    }
                }
            }
        }
        let ((gx, gy), (hx, hy)) = (gpu_best.1, host_best.1);
        assert!(gx.abs_diff(hx) <= 1 && gy.abs_diff(hy) <= 1, "{model}: GPU peak {:?}, host {:?}", gpu_best, host_best);
        assert!(gpu_best.0 > 0.8, "{model}: peak {}", gpu_best.0);
    }
}

/// A point light at distance d in front of a wall, diffuse only: the pixel at the
/// foot of the light is k_d·O_d·I·att(d).
#[test]
fn attenuation_forms_at_known_distances() {
    for (form, expected) in [
        ("attenuation = \"none\"", 1.0),
        ("attenuation = \"inverse_square\"", 1.0 / 4.0),
        ("attenuation = \"polynomial\"\ncoefficients = [0.5, 0.25, 0.125]", 1.0 / (0.5 + 0.25 * 2.0 + 0.125 * 4.0)),
        ("attenuation = \"polynomial\"\ncoefficients = [0.2, 0, 0]", 1.0),
    ] {
        let scene = parse(&format!(
            r#"
[image]
width = 33
height = 33
[camera]
type = "orthographic"
eye = [0, 0, 5]
look_at = [0, 0, 0]
height = 4
[[light]]
type = "point"
position = [0, 0, 2]
{form}
[material.wall]
color = [0.5, 0.75, 1]
ka = 0
kd = 0.8
ks = 0
[[object]]
type = "polygon"
vertices = [[-3, -3, 0], [3, -3, 0], [3, 3, 0], [-3, 3, 0]]
material = "wall"
"#
        ));
        let (image, _) = render(&scene);
        // Pixel (16, 16) is centred on the axis: N·L = 1, d = 2.
        assert_close(image.linear_at(16, 16), (0.8 * expected * DVec3::new(0.5, 0.75, 1.0)).to_array(), TOL, form);
    }
}

/// s_o at a known distance blends the surface with the depth-cue colour.
#[test]
fn depth_cue_blends_at_a_known_distance() {
    for (distance, s_o) in [(3.0, 1.0), (7.0, 1.0 - 0.5 * (7.0 - 5.0) / 4.0), (12.0, 0.5)] {
        let scene = parse(&format!(
            r#"
[image]
width = 9
height = 9
[camera]
type = "orthographic"
eye = [0, 0, {distance}]
look_at = [0, 0, 0]
height = 2
[ambient]
intensity = 1
[depth_cue]
color = [0.1, 0.9, 0.3]
near = 5
far = 9
near_scale = 1
far_scale = 0.5
[material.wall]
color = [0.8, 0.2, 0.4]
ka = 1
kd = 0
ks = 0
[[object]]
type = "polygon"
vertices = [[-3, -3, 0], [3, -3, 0], [3, 3, 0], [-3, 3, 0]]
material = "wall"
"#
        ));
        let (image, _) = render(&scene);
        let local = DVec3::new(0.8, 0.2, 0.4);
        let expected = s_o * local + (1.0 - s_o) * DVec3::new(0.1, 0.9, 0.3);
        assert_close(image.linear_at(4, 4), expected.to_array(), TOL, &format!("distance {distance}"));
    }
}

/// A mirror facing a coloured wall: the mirror's pixels show the wall's colour
/// times k_m (a colour here), on top of the mirror's own (black) shading.
#[test]
fn mirror_shows_the_wall_times_k_m() {
    let scene = parse(
        r#"
[image]
width = 32
height = 32
background = [0, 0, 0]
[camera]
type = "orthographic"
eye = [0, 0, 5]
look_at = [0, 0, 0]
height = 2
[ambient]
intensity = 1
[material.mirror]
color = 0
ka = 0
kd = 0
ks = 0
reflect = [0.9, 0.6, 0.3]
[material.wall]
color = [0.2, 0.7, 0.5]
ka = 1
kd = 0
ks = 0
# The mirror faces the camera; the wall is behind the camera, facing the mirror.
[[object]]
type = "polygon"
vertices = [[-2, -2, 0], [2, -2, 0], [2, 2, 0], [-2, 2, 0]]
material = "mirror"
[[object]]
type = "polygon"
vertices = [[-3, -3, 8], [3, -3, 8], [3, 3, 8], [-3, 3, 8]]
material = "wall"
"#,
    );
    let (image, stats) = render(&scene);
    let expected = DVec3::new(0.9, 0.6, 0.3) * DVec3::new(0.2, 0.7, 0.5);
    for (x, y) in [(3, 3), (16, 16), (28, 9)] {
        assert_close(image.linear_at(x, y), expected.to_array(), TOL, &format!("({x}, {y})"));
    }
    assert_eq!(stats.reflect, 32 * 32);
}

/// An orthographic view through a tilted glass slab of thickness T at a wall
/// whose left half is white: the edge shifts by T·sin(θi − θt)/cos θt.
#[test]
fn glass_slab_displaces_an_edge_by_snells_offset() {
    let (ior, thickness, tilt) = (1.5f64, 1.0f64, 40f64.to_radians());
    // The slab's faces are planes through the origin and through -T·n, n tilted about y.
    let n = DVec3::new(tilt.sin(), 0.0, tilt.cos());
    // Each face is wound so its normal points out of the slab: refraction decides
    // entering or leaving from the side of the normal the ray arrives on.
    let quad = |offset: f64, outward: f64| -> String {
        let (u, v) = (DVec3::new(tilt.cos(), 0.0, -tilt.sin()), outward * DVec3::Y);
        let c = -offset * n;
        let pts = [c - 5.0 * u - 5.0 * v, c + 5.0 * u - 5.0 * v, c + 5.0 * u + 5.0 * v, c - 5.0 * u + 5.0 * v];
        format!("[{}]", pts.iter().map(|p| format!("[{}, {}, {}]", p.x, p.y, p.z)).collect::<Vec<_>>().join(", "))
    };
    let scene = parse(&format!(
        r#"
[image]
width = 200
height = 10
background = [0, 0, 0]
[camera]
type = "orthographic"
eye = [0, 0, 10]
look_at = [0, 0, 0]
height = 0.4
[ambient]
intensity = 1
[render]
max_depth = 4
[material.glass]
color = 0
ka = 0
kd = 0
ks = 0
transmit = 1
ior = {ior}
[material.white]
color = 1
ka = 1
kd = 0
ks = 0
[[object]]
type = "polygon"
vertices = {front}
material = "glass"
[[object]]
type = "polygon"
vertices = {back}
material = "glass"
[[object]]
type = "polygon"
vertices = [[-20, -5, -6], [0, -5, -6], [0, 5, -6], [-20, 5, -6]]
material = "white"
"#,
        front = quad(0.0, 1.0),
        back = quad(thickness, -1.0),
    ));
    let (image, _) = render(&scene);
    // Snell: the ray leaves parallel to itself, shifted sideways by
    // T·sin(θi − θt)/cos θt; it bends towards −x inside, so a pixel at x sees
    // the wall at x − shift, and the white half (x < 0) ends where x = shift.
    let theta_t = (tilt.sin() / ior).asin();
    let shift = thickness * (tilt - theta_t).sin() / theta_t.cos();
    // Pixel centres: x = −4 + (i + 0.5)·0.04 (view width 0.4·20 = 8 over 200 px).
    let expected_col = ((shift + 4.0) / 0.04 - 0.5).ceil();
    let row = 5;
    let edge = (1..200).find(|&x| image.linear_at(x - 1, row)[0] > 0.5 && image.linear_at(x, row)[0] < 0.5).expect("an edge");
    assert!(
        (edge as f64 - expected_col).abs() <= 1.0,
        "edge at column {edge}, Snell predicts {expected_col} (shift {shift:.4} world units)"
    );
    // Without the slab the edge is at x = 0, column 100: the slab must move it.
    assert!(edge.abs_diff(100) > 3);
}

/// Inside a dense medium, looking up at its surface: rays beyond the critical
/// angle reflect totally and see the red floor, the others leave into the blue sky.
#[test]
fn total_internal_reflection_beyond_the_critical_angle() {
    let ior = 1.5f64;
    let scene = parse(&format!(
        r#"
[image]
width = 120
height = 4
background = [0, 0, 1]
[camera]
eye = [0, 0, 0]
look_at = [0, 1, 0]
up = [0, 0, -1]
fov = 10
[ambient]
intensity = 1
[render]
max_depth = 3
[material.water]
color = 0
ka = 0
kd = 0
ks = 0
transmit = 1
ior = {ior}
[material.red]
color = [1, 0, 0]
ka = 1
kd = 0
ks = 0
# The surface's normal points up, away from the camera: rays meet its back.
[[object]]
type = "polygon"
vertices = [[-100, 1, -100], [-100, 1, 100], [100, 1, 100], [100, 1, -100]]
material = "water"
[[object]]
type = "polygon"
vertices = [[-100, -1, -100], [100, -1, -100], [100, -1, 100], [-100, -1, 100]]
material = "red"
"#
    ));
    let (image, _) = render(&scene);
    let critical = (1.0 / ior).asin();
    let (mut tir, mut out) = (0, 0);
    for x in 0..120 {
        let ray = scene.camera.ray(120, 4, f64::from(x) + 0.5, 1.5).unwrap();
        let incidence = ray.direction.dot(DVec3::Y).acos();
        let c = image.linear_at(x, 1);
        if incidence > critical + 0.01 {
            assert!(c[0] > 0.99 && c[2] < 0.01, "pixel {x} at {:.2}° should reflect totally: {c:?}", incidence.to_degrees());
            tir += 1;
        } else if incidence < critical - 0.01 {
            assert!(c[2] > 0.99 && c[0] < 0.01, "pixel {x} at {:.2}° should pass: {c:?}", incidence.to_degrees());
            out += 1;
        }
    }
    assert!(tir > 10 && out > 10, "tir {tir}, out {out}");
}

/// Eye and light at the centre of a mirror sphere: every ray hits the inside and
/// reflects again, so the counts follow from max_depth and the cutoff by hand.
#[test]
fn ray_counts_of_a_hand_countable_scene() {
    for (cutoff, reflections_per_pixel) in [(None, 2u64), (Some(0.0), 4)] {
        let mut scene = parse(
            r#"
[image]
width = 4
height = 4
[camera]
eye = [0, 0, 0]
look_at = [0, 0, -1]
fov = 60
[render]
max_depth = 5
[[light]]
type = "point"
position = [0, 0, 0]
[material.mirror]
color = 0.5
reflect = 0.1
[[object]]
type = "sphere"
center = [0, 0, 0]
radius = 10
material = "mirror"
"#,
        );
        if let Some(c) = cutoff {
            scene.render.cutoff = c; // what --no-cutoff does
        }
        let (_, stats) = render(&scene);
        // Weights 0.1, 0.01, 0.001, 0.0001 at depths 2..5; the default cutoff of
        // 1/256 keeps the first two.
        assert_eq!(stats.eye_hit, 16);
        assert_eq!(stats.eye_miss, 0);
        assert_eq!(stats.reflect, 16 * reflections_per_pixel, "cutoff {cutoff:?}");
        assert_eq!(stats.refract, 0);
        assert_eq!(stats.shadow, 16 * (1 + reflections_per_pixel), "cutoff {cutoff:?}");
    }
}

/// Tinted shadows: light through a transmissive occluder is multiplied by its
/// k_t; opaque mode blocks it; an occluder beyond the light does not shadow.
/// The camera sees the floor point under the light from the side, past the
/// occluder that sits on the shadow ray.
#[test]
fn shadows_tinted_opaque_and_beyond_the_light() {
    for (mode, material, occluder_y, expected_factor) in [
        ("tinted", "filter", 1.0, DVec3::new(0.5, 0.25, 1.0)),
        ("opaque", "filter", 1.0, DVec3::ZERO),
        ("opaque", "floor", 3.0, DVec3::ONE), // above the light at y = 2
    ] {
        let scene = parse(&format!(
            r#"
[image]
width = 9
height = 9
[camera]
type = "orthographic"
eye = [5, 5, 0]
look_at = [0, 0, 0]
height = 0.2
[render]
shadow_mode = "{mode}"
[[light]]
type = "point"
position = [0, 2, 0]
[material.floor]
color = 1
ka = 0
kd = 1
ks = 0
[material.filter]
color = 0
ka = 0
kd = 0
ks = 0
transmit = [0.5, 0.25, 1]
[[object]]
type = "polygon"
vertices = [[-5, 0, -5], [-5, 0, 5], [5, 0, 5], [5, 0, -5]]
material = "floor"
[[object]]
type = "sphere"
center = [0, {occluder_y}, 0]
radius = 0.3
material = "{material}"
"#
        ));
        let (image, _) = render(&scene);
        // The centre pixel sees the floor right under the light: N·L = 1, d = 2.
        assert_close(image.linear_at(4, 4), expected_factor.to_array(), TOL, &format!("{mode} occluder at y = {occluder_y}"));
    }
}

/// Switching reflections off stops every reflected ray, also the ones total
/// internal reflection and Fresnel would send; switching refraction off stops
/// the transmitted ones.
#[test]
fn reflection_and_refraction_switches_stop_their_rays() {
    let toml = |reflections: bool, refractions: bool| {
        format!(
            r#"
[image]
width = 16
height = 16
[camera]
eye = [0, 0, 4]
look_at = [0, 0, 0]
fov = 40
[render]
reflections = {reflections}
refractions = {refractions}
[material.glass]
color = 0
transmit = 0.9
ior = 1.5
fresnel = true
[[object]]
type = "sphere"
center = [0, 0, 0]
radius = 1
material = "glass"
"#
        )
    };
    let (_, all) = render(&parse(&toml(true, true)));
    assert!(all.reflect > 0 && all.refract > 0, "{all:?}");
    let (_, no_reflect) = render(&parse(&toml(false, true)));
    assert_eq!(no_reflect.reflect, 0);
    assert!(no_reflect.refract > 0);
    let (_, no_refract) = render(&parse(&toml(true, false)));
    assert_eq!(no_refract.refract, 0);
}
