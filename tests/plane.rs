//! Infinite planes and the checker on the device, against the equations on
//! the host: a plane pixel's shade and distance, what the probe records there,
//! the checker's colour at known points of planes, polygons and spheres,
//! shadows on a plane, rays parallel to it, and a camera below it.

mod support;

use glam::DVec3;
use glint_encoding::gpu_types::{View, RAY_EYE, RAY_SHADOW};
use glint_gpu::probe::Prober;
use glint_gpu::shaders::ShaderSource;
use glint_gpu::{Acceleration, Image, RenderOptions};
use glint_scene::{Ray, Scene};
use support::{assert_close, parse, render, render_options};

const HEADER: &str = r#"
[image]
width = 96
height = 72
background = [0.1, 0.2, 0.3]

[camera]
eye = [0.5, 2, 6]
look_at = [0, 0, 0]
fov = 50

[ambient]
intensity = 0.25
"#;

/// A floor at y = 0 as an infinite plane: matte, lit from above.
const FLOOR: &str = r#"
[[light]]
type = "point"
position = [1, 6, 2]

[material.floor]
color = [0.4, 0.8, 0.6]
ka = 0.5
kd = 0.7
ks = 0

[[object]]
type = "plane"
point = [3, 0, -7]
normal = [0, 1, 0]
material = "floor"
"#;

fn view(scene: &Scene, view: View) -> Image {
    render_options(scene, Acceleration::Bvh, RenderOptions { view, ..Default::default() }).0
}

/// The eye ray through pixel (x, y)'s centre.
fn eye_ray(scene: &Scene, x: u32, y: u32) -> Ray {
    scene.camera.ray(scene.width, scene.height, f64::from(x) + 0.5, f64::from(y) + 0.5).unwrap()
}

/// Where the ray meets the plane y = 0, if ahead of it.
fn floor_hit(ray: &Ray) -> Option<(f64, DVec3)> {
    let t = -ray.origin.y / ray.direction.y;
    (t > 0.0 && t.is_finite()).then(|| (t, ray.origin + t * ray.direction))
}

fn pixels(scene: &Scene) -> impl Iterator<Item = (u32, u32)> {
    let (w, h) = (scene.width, scene.height);
    (0..h).flat_map(move |y| (0..w).map(move |x| (x, y)))
}

#[test]
fn an_infinite_plane_pixel_is_the_analytic_shade_at_the_analytic_distance() {
    let scene = parse(&format!("{HEADER}{FLOOR}"));
    let (image, _) = render(&scene);
    let (depth, ids, normals) = (view(&scene, View::Depth), view(&scene, View::Id), view(&scene, View::Normal));
    let (od, light) = (DVec3::new(0.4, 0.8, 0.6), DVec3::new(1.0, 6.0, 2.0));
    let mut floor = 0;
    for (x, y) in pixels(&scene) {
        let ray = eye_ray(&scene, x, y);
        let Some((t, p)) = floor_hit(&ray) else {
            assert_eq!(ids.linear_at(x, y)[0], -1.0, "({x}, {y}) looks above the horizon");
            continue;
        };
        let l = (light - p).normalize();
        let expected = 0.5 * 0.25 * od + 0.7 * od * l.y;
        assert_close(image.linear_at(x, y), expected.to_array(), 1.0 / 255.0, &format!("shade at ({x}, {y})"));
        assert!((f64::from(depth.linear_at(x, y)[0]) / t - 1.0).abs() < 1e-5, "depth at ({x}, {y})");
        assert_eq!(ids.linear_at(x, y)[0], 0.0, "the plane is object 0 at ({x}, {y})");
        assert_eq!(normals.linear_at(x, y), [0.0, 1.0, 0.0]);
        floor += 1;
    }
    assert!(floor > 3000, "the floor covers {floor} pixels");
}

#[test]
fn the_probe_records_a_plane_hit_and_its_shadow_ray() {
    let scene = parse(&format!("{HEADER}{FLOOR}"));
    let renderer = support::renderer();
    let prepared = renderer.prepare(&scene, scene.width, scene.height, Acceleration::Bvh).unwrap();
    let prober = Prober::new(renderer, &ShaderSource::Embedded).unwrap();
    let (x, y) = (48, 60);
    let tree = prober.probe(renderer, &prepared.buffers, x, y, &RenderOptions::default()).unwrap();
    let (t, p) = floor_hit(&eye_ray(&scene, x, y)).unwrap();
    let eye = &tree.rays[0];
    assert_eq!((eye.kind, eye.object, eye.geometric), (RAY_EYE, 0, [0.0, 1.0, 0.0]));
    assert!((f64::from(eye.t) / t - 1.0).abs() < 1e-5 && (DVec3::from(eye.point.map(f64::from)) - p).length() < 1e-4);
    let shadow = tree.rays.iter().find(|r| r.kind == RAY_SHADOW).expect("a shadow ray to the light");
    assert_eq!(shadow.transmittance, [1.0; 3], "nothing blocks the light");
    assert_close(tree.color, render(&scene).0.linear_at(x, y).map(f64::from), 1e-6, "the probed colour is the pixel's");
}

#[test]
fn the_checker_colours_tiles_by_position_in_the_plane_of_a_floor() {
    // The floor as an infinite plane, then as a polygon: each is tiled in its
    // plane's coordinates (x, z), with no flicker between the tiles of y = ±0.
    let checker = "checker = { color = [0.9, 0.8, 0.1], size = 0.75 }";
    let polygon = "[[object]]\ntype = \"polygon\"\nvertices = [[-40, 0, -40], [-40, 0, 40], [40, 0, 40], [40, 0, -40]]\nmaterial = \"floor\"\n";
    let plane = FLOOR.replace("ks = 0", &format!("ks = 0\n{checker}"));
    let square = format!("{}{polygon}", &plane[..plane.find("[[object]]").unwrap()]);
    for floor in [plane, square] {
        let scene = parse(&format!("{HEADER}{floor}"));
        let albedo = view(&scene, View::Albedo);
        let (mut even, mut odd) = (0, 0);
        for (x, y) in pixels(&scene) {
            let Some((_, p)) = floor_hit(&eye_ray(&scene, x, y)) else { continue };
            let (u, v) = (p.x / 0.75, p.z / 0.75);
            // Away from tile edges, where f32 and f64 may round apart.
            if (u - u.round()).abs() < 0.02 || (v - v.round()).abs() < 0.02 || p.length() > 30.0 {
                continue;
            }
            let is_odd = (u.floor() + v.floor()).rem_euclid(2.0) == 1.0;
            let expected = if is_odd { [0.9, 0.8, 0.1] } else { [0.4, 0.8, 0.6] };
            assert_close(albedo.linear_at(x, y), expected, 1e-6, &format!("tile at ({x}, {y}), {p}"));
            if is_odd { odd += 1 } else { even += 1 }
        }
        assert!(even > 500 && odd > 500, "even {even}, odd {odd}");
    }
}

#[test]
fn the_checker_on_a_sphere_is_solid() {
    let scene = parse(&format!(
        "{HEADER}\n[material.ball]\ncolor = 0.2\nchecker = {{ color = 1, size = 0.5 }}\n\
         [[object]]\ntype = \"sphere\"\ncenter = [0.1, 0.7, 0.2]\nradius = 1.1\nmaterial = \"ball\"\n"
    ));
    let albedo = view(&scene, View::Albedo);
    let (centre, mut checked) = (DVec3::new(0.1, 0.7, 0.2), 0);
    for (x, y) in pixels(&scene) {
        let ray = eye_ray(&scene, x, y);
        let oc = ray.origin - centre;
        let b = oc.dot(ray.direction);
        let disc = b * b - oc.length_squared() + 1.1 * 1.1;
        if disc < 0.05 {
            continue; // a miss, or the silhouette
        }
        let q = (ray.origin + (-b - disc.sqrt()) * ray.direction) / 0.5;
        if [q.x, q.y, q.z].iter().any(|c| (c - c.round()).abs() < 0.02) {
            continue;
        }
        let odd = (q.x.floor() + q.y.floor() + q.z.floor()).rem_euclid(2.0) == 1.0;
        assert_close(albedo.linear_at(x, y), if odd { [1.0; 3] } else { [0.2; 3] }, 1e-6, &format!("({x}, {y})"));
        checked += 1;
    }
    assert!(checked > 300, "{checked} pixels checked");
}

#[test]
fn a_sphere_casts_its_shadow_on_an_infinite_plane() {
    let scene = parse(&format!(
        "{HEADER}{}\n[[object]]\ntype = \"sphere\"\ncenter = [0, 1.5, 0]\nradius = 0.7\n",
        FLOOR.replace("position = [1, 6, 2]", "position = [0, 8, 0]")
    ));
    let (image, _) = render(&scene);
    let (sphere, light) = (DVec3::new(0.0, 1.5, 0.0), DVec3::new(0.0, 8.0, 0.0));
    let ambient = (0.5 * 0.25 * DVec3::new(0.4, 0.8, 0.6)).to_array();
    let blocked = |p: DVec3, r: f64| {
        let d = (light - p).normalize();
        let oc = p - sphere;
        let b = oc.dot(d);
        b * b - oc.length_squared() + r * r >= 0.0 && b < 0.0
    };
    let (mut shadowed, mut lit) = (0, 0);
    for (x, y) in pixels(&scene) {
        let ray = eye_ray(&scene, x, y);
        // Near the light, where a lit floor is well above the ambient term.
        let Some((t, p)) = floor_hit(&ray).filter(|(_, p)| p.length() < 5.0) else { continue };
        let oc = ray.origin - sphere;
        let b = oc.dot(ray.direction);
        if b * b - oc.length_squared() + 0.75 * 0.75 >= 0.0 && -b < t {
            continue; // the sphere, or its rim, is in front
        }
        if blocked(p, 0.65) {
            assert_close(image.linear_at(x, y), ambient, 1.0 / 255.0, &format!("shadowed ({x}, {y})"));
            shadowed += 1;
        } else if !blocked(p, 0.75) {
            assert!(image.linear_at(x, y)[1] > ambient[1] as f32 + 0.05, "({x}, {y}) should be lit");
            lit += 1;
        }
    }
    assert!(shadowed > 20 && lit > 500, "shadowed {shadowed}, lit {lit}");
}

#[test]
fn rays_parallel_to_a_plane_miss_it() {
    // An orthographic camera looking along the floor: every ray is parallel to
    // it, and the middle row's rays run in it.
    let header = HEADER.replace("eye = [0.5, 2, 6]", "eye = [0, 0, 6]").replace("fov = 50", "type = \"orthographic\"\nheight = 3");
    let scene = parse(&format!("{header}{FLOOR}\n[[object]]\ntype = \"sphere\"\ncenter = [0, 0, -2]\nradius = 0.5\n"));
    let ids = view(&scene, View::Id);
    let sphere = pixels(&scene).filter(|&(x, y)| ids.linear_at(x, y)[0] == 1.0).count();
    assert_eq!(pixels(&scene).filter(|&(x, y)| ids.linear_at(x, y)[0] == 0.0).count(), 0, "a parallel ray hit the plane");
    assert!(sphere > 100, "the sphere behind is seen past the plane's edge-on line ({sphere} pixels)");
}

#[test]
fn a_camera_below_a_plane_sees_its_unlit_underside() {
    let header = HEADER.replace("eye = [0.5, 2, 6]", "eye = [0.5, -2, 6]");
    let scene = parse(&format!("{header}{FLOOR}"));
    let (image, _) = render(&scene);
    let normals = view(&scene, View::Normal);
    let mut below = 0;
    for (x, y) in pixels(&scene) {
        if floor_hit(&eye_ray(&scene, x, y)).is_none() {
            continue;
        }
        // Turned towards the viewer, and facing away from the light above.
        assert_eq!(normals.linear_at(x, y), [0.0, -1.0, 0.0], "({x}, {y})");
        assert_close(image.linear_at(x, y), (0.5 * 0.25 * DVec3::new(0.4, 0.8, 0.6)).to_array(), 1e-6, &format!("({x}, {y})"));
        below += 1;
    }
    assert!(below > 3000, "the underside covers {below} pixels");
}
