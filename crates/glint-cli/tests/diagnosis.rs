//! Grading says what a failed submission got wrong. A class of students,
//! each with one bug of the lecture, is rendered by a tracer independent of
//! Glint's kernels: `glint-reference` (f64 on the CPU) with the scene's own
//! switches, its camera rays written here from the equations, and the bytes
//! written here. `glint test --submissions` must name each student's bug in
//! its output, its JUnit and Gradescope's results, and nothing for the
//! correct student. On the GPU (lavapipe in CI; no adapter is a failure).

mod suite;

use std::path::Path;

use glam::DVec3;
use glint_scene::{Projection, Scene, SpecularModel};

use suite::{arg, glint, stderr, stdout};

/// A red plastic sphere with a Phong highlight (every material Phong's, not
/// the default Blinn-Phong) and its shadow on a floor, a mirror sphere, a
/// glass one, and a wall whose vertices wind away from the eye: every effect
/// the diagnosis knows shows.
const SCENE: &str = r#"
[image]
width = 96
height = 48
background = [0.3, 0.45, 0.7]

[camera]
eye = [0, 1.6, 6]
look_at = [0, 0.6, 0]
fov = 40

[[light]]
type = "point"
position = [-3, 6, 4]

[material.red]
color = [0.9, 0.15, 0.1]
kd = 0.7
ks = 0.5
shininess = 30
model = "phong"

[material.mirror]
color = [0.2, 0.2, 0.2]
kd = 0.2
reflect = 0.8
model = "phong"

[material.glass]
color = [0.1, 0.1, 0.1]
kd = 0.1
transmit = [0.9, 0.9, 0.9]
ior = 1.5
model = "phong"

[material.floor]
color = [0.8, 0.8, 0.8]
kd = 0.9
checker = { color = [0.2, 0.2, 0.2], size = 1 }
model = "phong"

[[object]]
type = "sphere"
center = [0, 0.8, 0]
radius = 0.8
material = "red"

[[object]]
type = "sphere"
center = [-2, 0.7, -1]
radius = 0.7
material = "mirror"

[[object]]
type = "sphere"
center = [1.9, 0.7, 0.8]
radius = 0.7
material = "glass"

[material.wall]
color = [0.5, 0.7, 0.4]
kd = 0.8
model = "phong"

[[object]]
type = "polygon"
vertices = [[-8, 0, -8], [-8, 0, 8], [8, 0, 8], [8, 0, -8]]
material = "floor"

[[object]]
type = "polygon"
vertices = [[-8, 0, -4], [-8, 5, -4], [8, 5, -4], [8, 0, -4]]
material = "wall"
"#;

const MANIFEST: &str = r#"
name = "diagnosis"

[[case]]
name = "scene"
image = "scene.png"
scene = "scene.toml"
points = 10
compare = { threshold = 0.01 }
"#;

/// How a student's tracer turns the right linear value into a byte.
fn srgb(c: f64) -> f64 {
    if c <= 0.003_130_8 { 12.92 * c } else { 1.055 * c.powf(1.0 / 2.4) - 0.055 }
}

fn byte(c: f64) -> u8 {
    (c.clamp(0.0, 1.0) * 255.0).round() as u8
}

/// A student's image: the pixels' linear colours, written by `write`.
fn png(width: u32, height: u32, rgb: &[[f64; 3]], write: fn(f64) -> u8, path: &Path) {
    let bytes = rgb.iter().flat_map(|p| p.map(write)).collect();
    image::RgbImage::from_raw(width, height, bytes).unwrap().save(path).unwrap();
}

fn right(c: f64) -> u8 {
    byte(srgb(c))
}

/// The camera of a student, written from the lecture's equations: pixel
/// (i, j)'s ray goes through u_s = −r + 2r·x, v_s = t − 2t·y on a window of
/// half extents r = `aspect`·t and t = tan(fov/2), at (x, y) = `at(i, j)`.
fn students_camera(scene: &Scene, width: u32, height: u32, aspect: f64, at: impl Fn(f64, f64) -> (f64, f64)) -> Vec<[f64; 3]> {
    let camera = &scene.camera;
    let Projection::Perspective { fov_y_degrees } = camera.projection else { panic!("a perspective camera") };
    let w = (camera.eye - camera.look_at).as_dvec3().normalize();
    let u = camera.up.as_dvec3().cross(w).normalize();
    let v = w.cross(u);
    let t = (f64::from(fov_y_degrees).to_radians() / 2.0).tan();
    let r = t * aspect;
    let mut rgb = Vec::new();
    for j in 0..height {
        for i in 0..width {
            let (x, y) = at(f64::from(i), f64::from(j));
            let (us, vs) = (-r + 2.0 * r * x, t - 2.0 * t * y);
            let dir: DVec3 = (-w + us * u + vs * v).normalize();
            rgb.push(glint_reference::trace_ray(scene, camera.eye.as_dvec3(), dir));
        }
    }
    rgb
}

#[test]
fn each_students_bug_is_named_and_the_right_image_gets_none() {
    let dir = tempfile::tempdir().unwrap();
    let root = dir.path();
    std::fs::write(root.join("scene.toml"), SCENE).unwrap();
    std::fs::write(root.join("course.toml"), MANIFEST).unwrap();
    let scene = glint_scene::load(&root.join("scene.toml")).unwrap();
    let (width, height) = (scene.width, scene.height);
    let (w, h) = (f64::from(width), f64::from(height));
    let render = |scene: &Scene| glint_reference::render(scene, width, height).rgb;
    let with = |change: fn(&mut Scene)| {
        let mut changed = scene.clone();
        change(&mut changed);
        render(&changed)
    };

    // Each student: what their tracer rendered, how it wrote bytes, and the
    // words the diagnosis must use (None: no diagnosis).
    let class: Vec<(&str, Vec<[f64; 3]>, fn(f64) -> u8, Option<&str>)> = vec![
        ("ann", render(&scene), right, None),
        ("bob", with(|s| s.render.shadows = false), right, Some("without shadow rays")),
        ("cat", with(|s| s.render.reflections = false), right, Some("without reflected rays")),
        ("dan", with(|s| s.render.refractions = false), right, Some("without refracted rays")),
        ("eve", with(|s| s.materials.iter_mut().for_each(|m| m.specular = 0.0)), right, Some("without specular highlights")),
        ("fay", with(|s| s.materials.iter_mut().for_each(|m| m.specular_model = SpecularModel::BlinnPhong)), right, Some("Blinn-Phong's N·H in place of Phong's")),
        ("gus", render(&scene), byte, Some("linear values written as bytes")),
        ("hal", render(&scene), |c| byte(srgb(srgb(c))), Some("sRGB encoding applied twice")),
        // The field of view between the top and bottom rows' centres.
        ("ida", students_camera(&scene, width, height, (w - 1.0) / (h - 1.0), |i, j| (i / (w - 1.0), j / (h - 1.0))), right, Some("field of view measured between the outer pixels' centres")),
        // Rays through (i, j), without the + 0.5.
        ("jon", students_camera(&scene, width, height, w / h, |i, j| (i / w, j / h)), right, Some("through its pixel's corner")),
        ("kim", with(|s| s.render.turn_normals = false), right, Some("normals not turned towards the eye")),
    ];
    for (name, rgb, write, _) in &class {
        std::fs::create_dir_all(root.join("subs").join(name)).unwrap();
        png(width, height, rgb, *write, &root.join("subs").join(name).join("scene.png"));
    }

    let (junit, report) = (root.join("junit.xml"), root.join("report"));
    let o = glint(&["test", arg(&root.join("course.toml")), "--submissions", arg(&root.join("subs")), "--junit", arg(&junit), "--report", arg(&report)]);
    let out = stdout(&o);
    assert!(o.status.success(), "{out}{}", stderr(&o));
    let junit = std::fs::read_to_string(junit).unwrap().replace("&apos;", "'").replace("&#39;", "'").replace("&quot;", "\"").replace("&amp;", "&");
    for (name, _, _, bug) in &class {
        let line = out.lines().find(|l| l.contains(&format!(" {name}/scene: "))).unwrap_or_else(|| panic!("no line for {name}:\n{out}"));
        let results = std::fs::read_to_string(report.join(name).join("results.json")).unwrap();
        match bug {
            None => assert!(line.starts_with("ok ") && !line.contains("closest to") && !results.contains("closest to"), "{name}: {line}"),
            Some(words) => {
                assert!(line.starts_with("FAIL ") && line.contains("closest to Glint's render ") && line.contains(words), "{name}: {line}");
                assert!(results.contains(words), "{name}: {words} not in results.json");
            }
        }
    }
    for words in class.iter().filter_map(|student| student.3) {
        assert!(junit.contains(words), "{words} not in the JUnit:\n{junit}");
    }
}

/// `--no-shadows`, `--no-reflection` and `--no-refraction` render what the
/// scene's own `[render]` switches do, and each changes the image.
#[test]
fn the_switches_on_the_command_line_are_the_scenes_own() {
    let dir = tempfile::tempdir().unwrap();
    let render = |scene: &str, name: &str, extra: &[&str]| {
        let (file, out) = (dir.path().join(format!("{name}.toml")), dir.path().join(format!("{name}.png")));
        std::fs::write(&file, scene).unwrap();
        let mut args = vec!["render", arg(&file), "-o", arg(&out), "-q"];
        args.extend(extra);
        let o = glint(&args);
        assert!(o.status.success(), "{}", stderr(&o));
        std::fs::read(out).unwrap()
    };
    let full = render(SCENE, "full", &[]);
    for (option, key) in [("--no-shadows", "shadows"), ("--no-reflection", "reflections"), ("--no-refraction", "refractions")] {
        let switched = render(SCENE, key, &[option]);
        let in_scene = render(&format!("{SCENE}\n[render]\n{key} = false\n"), &format!("{key}_in_scene"), &[]);
        assert!(switched == in_scene && switched != full, "{option}");
    }
}
