//! Analytic GPU tests: expectations computed on the host in f64 from the
//! equations, compared with pixels the kernels produce on the device.

mod support;

use glam::DVec3;
use glint_encoding::gpu_types::View;
use glint_gpu::{Acceleration, RenderOptions};
use glint_scene::Ray;
use support::{assert_close, parse, render, render_options};

const HEADER: &str = r#"
[image]
width = 96
height = 72
background = [0.1, 0.2, 0.3]

[camera]
eye = [0, 1, 6]
look_at = [0, 0.5, 0]
fov = 40
"#;

/// Ray–sphere intersection on the host.
fn hit_sphere(ray: &Ray, center: DVec3, radius: f64) -> Option<f64> {
    let oc = ray.origin - center;
    let b = oc.dot(ray.direction);
    let disc = b * b - (oc.length_squared() - radius * radius);
    (disc >= 0.0).then(|| -b - disc.sqrt()).filter(|t| *t > 0.0)
}

#[test]
fn sphere_silhouette_matches_projected_disc() {
    for camera in ["fov = 40", "type = \"orthographic\"\nheight = 3"] {
        let scene = parse(&format!(
            "{}\n[ambient]\nintensity = 1\n[material.white]\ncolor = 1\nka = 1\n[[object]]\ntype = \"sphere\"\ncenter = [0.3, 0.6, 0]\nradius = 1\nmaterial = \"white\"\n",
            HEADER.replace("fov = 40", camera)
        ));
        let (image, _) = render(&scene);
        let (w, h) = (scene.width, scene.height);
        let inside = |x: u32, y: u32| {
            let ray = scene.camera.ray(w, h, f64::from(x) + 0.5, f64::from(y) + 0.5).unwrap();
            hit_sphere(&ray, DVec3::new(0.3, 0.6, 0.0), 1.0).is_some()
        };
        let mut hits = 0;
        for y in 0..h {
            for x in 0..w {
                let expected = inside(x, y);
                hits += usize::from(expected);
                let got = image.linear_at(x, y)[0] > 0.5;
                if got != expected {
                    // Only pixels on the silhouette, whose neighbours disagree, may differ.
                    let edge = [(0i32, 1i32), (1, 0), (0, -1), (-1, 0)].iter().any(|(dx, dy)| {
                        let (nx, ny) = (x as i32 + dx, y as i32 + dy);
                        nx >= 0 && ny >= 0 && (nx as u32) < w && (ny as u32) < h && inside(nx as u32, ny as u32) != expected
                    });
                    assert!(edge, "{camera}: pixel ({x}, {y}) is {got}, expected {expected}");
                }
            }
        }
        assert!(hits > 500, "{camera}: the sphere covers only {hits} pixels");
    }
}

#[test]
fn blinn_phong_pixels_match_the_equation() {
    let (ka, kd, ks, n) = (0.2, 0.6, 0.3, 20.0);
    let od = DVec3::new(0.9, 0.5, 0.2);
    let ia = DVec3::new(0.3, 0.3, 0.4);
    let light_pos = DVec3::new(3.0, 4.0, 5.0);
    let il = DVec3::new(0.9, 0.8, 0.7);
    let center = DVec3::new(0.0, 0.5, 0.0);
    let scene = parse(&format!(
        r#"{HEADER}
[ambient]
color = [0.3, 0.3, 0.4]
intensity = 1
[[light]]
type = "point"
position = [3, 4, 5]
color = [0.9, 0.8, 0.7]
[material.m]
color = [0.9, 0.5, 0.2]
ka = {ka}
kd = {kd}
ks = {ks}
shininess = {n}
model = "blinn"
[[object]]
type = "sphere"
center = [0, 0.5, 0]
radius = 1.2
material = "m"
"#
    ));
    let (image, _) = render(&scene);
    let mut checked = 0;
    for (x, y) in [(48, 36), (40, 30), (55, 25), (60, 40), (35, 45), (52, 20)] {
        let ray = scene.camera.ray(96, 72, f64::from(x) + 0.5, f64::from(y) + 0.5).unwrap();
        let t = hit_sphere(&ray, center, 1.2).expect("chosen pixels are on the sphere");
        let p = ray.origin + t * ray.direction;
        let nrm = (p - center).normalize();
        let l = (light_pos - p).normalize();
        let v = -ray.direction;
        let hv = (l + v).normalize();
        let mut c = ka * ia * od;
        if nrm.dot(l) > 0.0 {
            c += il * (kd * nrm.dot(l) * od + ks * nrm.dot(hv).max(0.0).powf(n) * DVec3::ONE);
        }
        assert_close(image.linear_at(x, y), c.to_array(), 1.0 / 255.0, &format!("pixel ({x}, {y})"));
        checked += 1;
    }
    assert_eq!(checked, 6);
}

/// A floor polygon at y = 0 under a sphere (centre (0, 1.5, 0), radius 0.7),
/// both of the material `floor`, which `setting` defines (TOML: ambient,
/// lights and materials).
fn floor_and_sphere(setting: &str) -> glint_scene::Scene {
    parse(&format!(
        r#"{HEADER}
{setting}
[[object]]
type = "polygon"
vertices = [[-4, 0, -4], [4, 0, -4], [4, 0, 4], [-4, 0, 4]]
material = "floor"
[[object]]
type = "sphere"
center = [0, 1.5, 0]
radius = 0.7
material = "floor"
"#
    ))
}

const SPHERE: DVec3 = DVec3::new(0.0, 1.5, 0.0);

/// Where on the floor of `floor_and_sphere` each pixel's eye ray lands, and
/// whether the sphere hides `light` from there, for the pixels that see the
/// floor well inside its edges and away from the shadow's edge (classified
/// with a margin, the shadow being penumbra-free).
fn floor_pixels(scene: &glint_scene::Scene, light: DVec3) -> Vec<(u32, u32, DVec3, bool)> {
    let mut pixels = Vec::new();
    for y in 0..72 {
        for x in 0..96 {
            let ray = scene.camera.ray(96, 72, f64::from(x) + 0.5, f64::from(y) + 0.5).unwrap();
            if hit_sphere(&ray, SPHERE, 0.75).is_some() || ray.direction.y >= 0.0 {
                continue; // the sphere itself, its rim, or sky
            }
            let p = ray.origin - ray.origin.y / ray.direction.y * ray.direction;
            if p.x.abs() > 3.9 || p.z.abs() > 3.9 {
                continue;
            }
            let to_light = Ray { origin: p, direction: (light - p).normalize() };
            if hit_sphere(&to_light, SPHERE, 0.65).is_some() {
                pixels.push((x, y, p, true));
            } else if hit_sphere(&to_light, SPHERE, 0.75).is_none() {
                pixels.push((x, y, p, false));
            }
        }
    }
    pixels
}

#[test]
fn pixel_in_shadow_is_the_ambient_term() {
    // Lit from straight above.
    let scene = floor_and_sphere(
        r#"
[ambient]
color = [1, 1, 1]
intensity = 0.25
[[light]]
type = "point"
position = [0, 8, 0]
[material.floor]
color = [0.4, 0.8, 0.6]
ka = 0.5
kd = 0.7
ks = 0
"#,
    );
    let (image, _) = render(&scene);
    let ambient = [0.5 * 0.25 * 0.4, 0.5 * 0.25 * 0.8, 0.5 * 0.25 * 0.6];
    let (mut shadowed, mut lit) = (0, 0);
    for (x, y, _, blocked) in floor_pixels(&scene, DVec3::new(0.0, 8.0, 0.0)) {
        if blocked {
            assert_close(image.linear_at(x, y), ambient, 1.0 / 255.0, &format!("shadowed ({x}, {y})"));
            shadowed += 1;
        } else {
            assert!(image.linear_at(x, y)[1] > ambient[1] as f32 + 0.05, "({x}, {y}) should be lit");
            lit += 1;
        }
    }
    assert!(shadowed > 20 && lit > 200, "shadowed {shadowed}, lit {lit}");
}

#[test]
fn cameras_put_world_points_at_the_computed_pixel() {
    for camera in [
        "fov = 40",
        "fov = 75\nup = [0.3, 1, 0]",
        "type = \"orthographic\"\nheight = 4",
    ] {
        for point in [DVec3::new(0.8, 1.1, -0.5), DVec3::new(-1.2, 0.2, 0.7), DVec3::new(0.1, -0.4, 1.5)] {
            let toml = format!(
                "{}\n[ambient]\nintensity = 1\n[material.m]\ncolor = 1\nka = 1\n[[object]]\ntype = \"sphere\"\ncenter = [{}, {}, {}]\nradius = 0.02\nmaterial = \"m\"\n",
                HEADER.replace("fov = 40", camera),
                point.x,
                point.y,
                point.z
            );
            // Move the point onto the exact centre of the pixel it projects into, so
            // a tiny sphere there covers that pixel's centre ray.
            let scene = parse(&toml);
            let (px, py) = scene.camera.project(96, 72, point).unwrap();
            let (x, y) = (px.floor() as u32, py.floor() as u32);
            let ray = scene.camera.ray(96, 72, f64::from(x) + 0.5, f64::from(y) + 0.5).unwrap();
            let t = (point - ray.origin).dot(ray.direction);
            let centred = ray.origin + t * ray.direction;
            let scene = parse(&toml.replace(
                &format!("[{}, {}, {}]", point.x, point.y, point.z),
                &format!("[{}, {}, {}]", centred.x, centred.y, centred.z),
            ));
            let (image, _) = render(&scene);
            let lit: Vec<(u32, u32)> = (0..72)
                .flat_map(|y| (0..96).map(move |x| (x, y)))
                .filter(|&(x, y)| image.linear_at(x, y)[0] > 0.5)
                .collect();
            assert!(lit.contains(&(x, y)), "{camera}: {point} should cover pixel ({x}, {y}); lit: {lit:?}");
            assert!(lit.len() <= 4, "{camera}: a tiny sphere lit {lit:?}");
        }
    }
}

/// The diffuse view (a kernel of its own) is Lambert's term alone, with the
/// inverse-square falloff and hard shadows: k_d·O_d·I_l·max(0, N·L)·V/d², no
/// ambient and no highlight, whatever the scene's material says.
#[test]
fn the_diffuse_view_is_lamberts_term_alone() {
    let scene = floor_and_sphere(
        r#"
[ambient]
color = [1, 1, 1]
intensity = 0.5
[[light]]
type = "point"
position = [1, 6, 2]
color = [0.9, 0.8, 0.7]
[material.floor]
color = [0.4, 0.8, 0.6]
ka = 0.5
kd = 0.7
ks = 0.4
shininess = 8
"#,
    );
    let options = RenderOptions { view: View::Diffuse, ..RenderOptions::default() };
    let (image, _) = render_options(&scene, Acceleration::Bvh, options);
    let light = DVec3::new(1.0, 6.0, 2.0);
    let lambert = |p: DVec3, n: DVec3| {
        let to_light = light - p;
        let cosine = n.dot(to_light.normalize()).max(0.0);
        0.7 * DVec3::new(0.4, 0.8, 0.6) * DVec3::new(0.9, 0.8, 0.7) * cosine / to_light.length_squared()
    };
    let (mut shadowed, mut lit) = (0, 0);
    for (x, y, p, blocked) in floor_pixels(&scene, light) {
        let want = if blocked { DVec3::ZERO } else { lambert(p, DVec3::Y) };
        assert_close(image.linear_at(x, y), want.to_array(), 1e-4, &format!("floor pixel ({x}, {y})"));
        *(if blocked { &mut shadowed } else { &mut lit }) += 1;
    }
    let mut on_sphere = 0;
    for y in 0..72 {
        for x in 0..96 {
            let ray = scene.camera.ray(96, 72, f64::from(x) + 0.5, f64::from(y) + 0.5).unwrap();
            // Inside the silhouette, clear of its rim.
            if let (Some(t), Some(_)) = (hit_sphere(&ray, SPHERE, 0.7), hit_sphere(&ray, SPHERE, 0.69)) {
                let p = ray.origin + t * ray.direction;
                assert_close(image.linear_at(x, y), lambert(p, (p - SPHERE).normalize()).to_array(), 1e-4, &format!("sphere pixel ({x}, {y})"));
                on_sphere += 1;
            }
        }
    }
    assert!(shadowed > 20 && lit > 200 && on_sphere > 100, "shadowed {shadowed}, lit {lit}, on the sphere {on_sphere}");
}

#[test]
fn the_last_of_the_most_materials_a_scene_may_have_reaches_the_kernels() {
    use glint_encoding::gpu_types::MAX_MATERIALS;
    let mut scene = parse(&format!(
        "{HEADER}\n[ambient]\nintensity = 1\n[material.white]\ncolor = 1\nka = 1\nkd = 0\n\
         [[object]]\ntype = \"sphere\"\ncenter = [-1.2, 0.5, 0]\nradius = 0.5\nmaterial = \"white\"\n\
         [[object]]\ntype = \"sphere\"\ncenter = [1.2, 0.5, 0]\nradius = 0.5\nmaterial = \"white\"\n"
    ));
    let template = scene.materials[scene.objects[0].material].clone();
    let shade = |i: usize| glam::Vec3::new(i as f32 / MAX_MATERIALS as f32, 0.5, 1.0 - i as f32 / MAX_MATERIALS as f32);
    scene.materials = (0..MAX_MATERIALS as usize)
        .map(|i| glint_scene::Material { name: format!("m{i}"), color: shade(i), ..template.clone() })
        .collect();
    let (first, last) = (1, MAX_MATERIALS as usize - 1);
    scene.objects[0].material = first;
    scene.objects[1].material = last;
    let (image, _) = render(&scene);
    for (center, material) in [(DVec3::new(-1.2, 0.5, 0.0), first), (DVec3::new(1.2, 0.5, 0.0), last)] {
        let (x, y) = scene.camera.project(scene.width, scene.height, center).unwrap();
        let expected = shade(material).as_dvec3().to_array();
        assert_close(image.linear_at(x as u32, y as u32), expected, 1e-3, &format!("material {material}"));
    }
}
