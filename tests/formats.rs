//! Scene formats and primitives on the GPU: concave polygons, open cones and
//! cylinders, OBJ/MTL meshes.

mod support;

use glam::DVec3;
use glint_encoding::gpu_types::View;
use glint_gpu::{Acceleration, RenderOptions};
use support::{assert_close, parse, render, render_options};

/// Every pixel of `image` whose classification by `inside` differs must be on
/// an edge (a 4-neighbour classified differently).
fn assert_matches_mask(image: &glint_gpu::Image, inside: impl Fn(u32, u32) -> bool, what: &str) -> usize {
    let (w, h) = (image.width, image.height);
    let mut count = 0;
    for y in 0..h {
        for x in 0..w {
            let expected = inside(x, y);
            count += usize::from(expected);
            if (image.linear_at(x, y)[0] > 0.5) != expected {
                let edge = [(0i32, 1i32), (1, 0), (0, -1), (-1, 0)].iter().any(|(dx, dy)| {
                    let (nx, ny) = (x as i32 + dx, y as i32 + dy);
                    nx >= 0 && ny >= 0 && (nx as u32) < w && (ny as u32) < h && inside(nx as u32, ny as u32) != expected
                });
                assert!(edge, "{what}: pixel ({x}, {y}) should be {}", if expected { "covered" } else { "background" });
            }
        }
    }
    count
}

const ORTHO_HEADER: &str = r#"
[image]
width = 80
height = 80
[camera]
type = "orthographic"
eye = [0, 0, 10]
look_at = [0, 0, 0]
height = 8
[ambient]
intensity = 1
[material.white]
color = 1
ka = 1
kd = 0
ks = 0
"#;

/// World (x, y) of pixel (i, j)'s centre for ORTHO_HEADER's camera.
fn world(i: u32, j: u32) -> (f64, f64) {
    (-4.0 + (f64::from(i) + 0.5) * 0.1, 4.0 - (f64::from(j) + 0.5) * 0.1)
}

/// Even-odd rule on the host.
fn inside_polygon(p: (f64, f64), poly: &[(f64, f64)]) -> bool {
    let mut inside = false;
    for i in 0..poly.len() {
        let (a, b) = (poly[i], poly[(i + 1) % poly.len()]);
        if (a.1 > p.1) != (b.1 > p.1) && p.0 < a.0 + (b.0 - a.0) * (p.1 - a.1) / (b.1 - a.1) {
            inside = !inside;
        }
    }
    inside
}

#[test]
fn concave_twelve_gon_shows_background_in_its_notch() {
    // A 12-gon: a square with a deep rectangular notch cut into the top, plus
    // a smaller notch on the right.
    let poly = [
        (-3.0, -3.0), (3.0, -3.0), (3.0, -0.5), (1.5, -0.5), (1.5, 0.5), (3.0, 0.5),
        (3.0, 3.0), (1.0, 3.0), (1.0, -1.0), (-1.0, -1.0), (-1.0, 3.0), (-3.0, 3.0),
    ];
    let vertices: Vec<String> = poly.iter().map(|(x, y)| format!("[{x}, {y}, 0]")).collect();
    let scene = parse(&format!(
        "{ORTHO_HEADER}\n[[object]]\ntype = \"polygon\"\nvertices = [{}]\nmaterial = \"white\"\n",
        vertices.join(", ")
    ));
    let (image, _) = render(&scene);
    let covered = assert_matches_mask(&image, |i, j| inside_polygon(world(i, j), &poly), "12-gon");
    assert!(covered > 2000, "{covered}");
    // The notch's centre, (0, 1), is background; the bar below it is covered.
    let (nx, ny) = (40, 30);
    let (wx, wy) = world(nx, ny);
    assert!((wx - 0.05).abs() < 1e-9 && (wy - 0.95).abs() < 1e-9);
    assert!(image.linear_at(nx, ny)[0] < 0.01, "the notch shows background");
    assert!(image.linear_at(40, 55)[0] > 0.99);
}

#[test]
fn cone_and_cylinder_silhouettes_and_normals() {
    // Axis along y, seen from +z: the silhouette of radius r(y) = r0 + k·(y − y0).
    for (r0, r1) in [(1.5, 1.5), (2.0, 0.5), (0.5, 1.8), (1.8, 0.0)] {
        let (y0, y1) = (-3.0, 3.0);
        let k = (r1 - r0) / (y1 - y0);
        let radius = |y: f64| r0 + k * (y - y0);
        let scene_toml = format!(
            "{ORTHO_HEADER}\n[[object]]\ntype = \"cone\"\nbase = [0, {y0}, 0]\nbase_radius = {r0}\napex = [0, {y1}, 0]\napex_radius = {r1}\nmaterial = \"white\"\n"
        );
        let scene = parse(&scene_toml);
        let (image, _) = render(&scene);
        let covered = assert_matches_mask(
            &image,
            |i, j| {
                let (x, y) = world(i, j);
                y > y0 && y < y1 && x.abs() < radius(y)
            },
            &format!("cone {r0}→{r1}"),
        );
        assert!(covered > 500);
        let (normals, _) = render_options(&scene, Acceleration::Bvh, RenderOptions { view: View::Normal, ..Default::default() });
        for (i, j) in [(40, 40), (30, 20), (47, 55), (35, 62)] {
            let (x, y) = world(i, j);
            let r = radius(y);
            if x.abs() > 0.9 * r {
                continue;
            }
            let z = (r * r - x * x).sqrt();
            let radial = DVec3::new(x, 0.0, z) / r;
            let expected = (radial - k * DVec3::Y).normalize();
            assert_close(normals.linear_at(i, j), expected.to_array(), 1e-3, &format!("cone {r0}→{r1} normal at ({i}, {j})"));
        }
    }
}

#[test]
fn open_cylinder_inside_faces_the_viewer() {
    // Looking down into an open tube: the inner wall is hit from inside, and
    // its normal turns towards the viewer (towards the axis).
    let scene = parse(
        r#"
[image]
width = 41
height = 41
[camera]
eye = [0, 10, 0.0001]
look_at = [0, 0, 0]
fov = 20
[[object]]
type = "cylinder"
base = [0, 0, 0]
apex = [0, 3, 0]
base_radius = 1
"#,
    );
    let (normals, _) = render_options(&scene, Acceleration::Bvh, RenderOptions { view: View::Normal, ..Default::default() });
    let (depth, _) = render_options(&scene, Acceleration::Bvh, RenderOptions { view: View::Depth, ..Default::default() });
    assert!(depth.linear_at(20, 20)[0] > 1e30, "the axis sees through the open ends");
    let mut checked = 0;
    for i in 0..41 {
        let n = normals.linear_at(i, 20);
        let d = depth.linear_at(i, 20)[0];
        if d < 1e30 && d > 7.5 {
            // Deep hits are on the inner wall: the normal points back at the axis.
            let ray = scene.camera.ray(41, 41, f64::from(i) + 0.5, 20.5).unwrap();
            let p = ray.origin + f64::from(d) * ray.direction;
            let inward = DVec3::new(-p.x, 0.0, -p.z).normalize();
            assert_close(n, inward.to_array(), 2e-3, &format!("inner wall at column {i}"));
            checked += 1;
        }
    }
    assert!(checked >= 4, "{checked}");
}

#[test]
fn obj_cube_renders_with_its_mtl_colours() {
    let dir = tempfile::tempdir().unwrap();
    std::fs::write(
        dir.path().join("cube.mtl"),
        "newmtl red\nKd 0.8 0.1 0.1\nKs 0 0 0\nillum 1\nnewmtl blue\nKd 0.1 0.2 0.9\nKs 0 0 0\nillum 1\n",
    )
    .unwrap();
    std::fs::write(
        dir.path().join("cube.obj"),
        "mtllib cube.mtl\nv -1 -1 -1\nv 1 -1 -1\nv 1 1 -1\nv -1 1 -1\nv -1 -1 1\nv 1 -1 1\nv 1 1 1\nv -1 1 1\n\
usemtl red\nf 5 6 7 8\nf 1 4 3 2\nusemtl blue\nf 1 2 6 5\nf 4 8 7 3\nf 1 5 8 4\nf 2 3 7 6\n",
    )
    .unwrap();
    let toml = dir.path().join("scene.toml");
    std::fs::write(
        &toml,
        r#"
[image]
width = 60
height = 60
[camera]
eye = [0, 3, 6]
look_at = [0, 0, 0]
fov = 40
[ambient]
intensity = 10
[[object]]
type = "mesh"
path = "cube.obj"
rotate = [0, 0, 0]
"#,
    )
    .unwrap();
    let scene = glint_scene::load(&toml).unwrap();
    assert_eq!(scene.primitive_count(), 12);
    let (image, _) = render(&scene);
    // k_a = 0.1 for MTL materials, I_a = 10: ambient alone gives exactly Kd.
    let front = scene.camera.project(60, 60, DVec3::new(0.2, -0.3, 1.0)).unwrap();
    let top = scene.camera.project(60, 60, DVec3::new(-0.2, 1.0, 0.1)).unwrap();
    assert_close(image.linear_at(front.0 as u32, front.1 as u32), [0.8, 0.1, 0.1], 1e-4, "front face (red)");
    assert_close(image.linear_at(top.0 as u32, top.1 as u32), [0.1, 0.2, 0.9], 1e-4, "top face (blue)");
}
