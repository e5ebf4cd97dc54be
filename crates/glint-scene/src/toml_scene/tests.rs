//! The TOML reader: defaults, every section, and errors and warnings at their positions.

use super::*;
use crate::{Attenuation, LightKind, Projection, RenderSettings, ShadowMode, Shape, SpecularModel};

const MINIMAL: &str = r#"
[image]
width = 32
height = 24

[camera]
eye = [0, 0, 5]
look_at = [0, 0, 0]
fov = 40
"#;

fn parse_str(extra: &str) -> Result<Scene, LoadError> {
    parse(&format!("{MINIMAL}{extra}"), Path::new("test.toml"))
}

fn error(extra: &str) -> String {
    parse_str(extra).unwrap_err().to_string()
}

#[test]
fn minimal_scene_has_defaults() {
    let s = parse_str("").unwrap();
    assert_eq!((s.width, s.height), (32, 24));
    assert_eq!(s.camera.projection, Projection::Perspective { fov_y_degrees: 40.0 });
    assert_eq!(s.camera.up, Vec3::Y);
    assert_eq!(s.materials.len(), 1);
    assert_eq!(s.render, RenderSettings::default());
}

#[test]
fn every_section_parses() {
    let s = parse_str(
        r#"
[ambient]
color = [1, 0.5, 0.25]
intensity = 0.2

[render]
max_depth = 3
cutoff = 0.01
shadow_mode = "tinted"

[depth_cue]
color = [0.5, 0.5, 0.5]
near = 1
far = 11
far_scale = 0.25

[[light]]
type = "point"
position = [1, 2, 3]
color = [1, 1, 0]
intensity = 2
attenuation = "polynomial"
coefficients = [1, 0.1, 0.01]

[[light]]
type = "directional"
direction = [0, -2, 0]

[material.glass]
color = 1
ks = 0.5
model = "phong"
transmit = [0.9, 0.9, 0.9]
ior = 1.5
fresnel = true

[[object]]
type = "sphere"
center = [0, 0, 0]
radius = 1
material = "glass"

[[object]]
type = "polygon"
vertices = [[0, 0, 0], [2, 0, 0], [2, 1, 0], [1, 1, 0], [1, 2, 0], [0, 2, 0]]

[[object]]
type = "cylinder"
base = [0, 0, 0]
apex = [0, 1, 0]
base_radius = 0.5
"#,
    )
    .unwrap();
    assert_eq!(s.ambient, Vec3::new(0.2, 0.1, 0.05));
    assert_eq!(s.render.max_depth, 3);
    assert_eq!(s.render.shadow_mode, ShadowMode::Tinted);
    assert_eq!(s.depth_cue.unwrap().near_scale, 1.0);
    assert_eq!(s.lights[0].attenuation, Attenuation::Polynomial { c1: 1.0, c2: 0.1, c3: 0.01 });
    assert_eq!(s.lights[1].kind, LightKind::Directional { direction: Vec3::NEG_Y });
    assert_eq!(s.materials[1].specular_model, SpecularModel::Phong);
    assert_eq!(s.objects[0].material, 1);
    assert!(matches!(s.objects[2].shapes[0], Shape::Cone { apex_radius: 0.5, .. }));
}

#[test]
fn orthographic_camera() {
    let s = parse(
        "[image]\nwidth = 4\nheight = 4\n[camera]\ntype = \"orthographic\"\neye = [0,0,5]\nlook_at = [0,0,0]\nheight = 3\n",
        Path::new("o.toml"),
    )
    .unwrap();
    assert_eq!(s.camera.projection, Projection::Orthographic { height: 3.0 });
}

#[test]
fn unknown_key_names_file_line_and_key() {
    let e = error("[[object]]\ntype = \"sphere\"\ncenter = [0, 0, 0]\nradus = 1\n");
    assert!(e.starts_with("test.toml:13:"), "{e}");
    assert!(e.contains("radus"), "{e}");
}

#[test]
fn wrong_type_names_line_and_key() {
    let e = error("[[object]]\ntype = \"sphere\"\ncenter = [0, 0, 0]\nradius = \"big\"\n");
    assert!(e.starts_with("test.toml:13:"), "{e}");
    assert!(e.contains("radius"), "{e}");
}

#[test]
fn nan_is_rejected_where_it_stands() {
    let e = error("[[object]]\ntype = \"sphere\"\ncenter = [0, nan, 0]\nradius = 1\n");
    assert!(e.starts_with("test.toml:12:"), "{e}");
    assert!(e.contains("finite"), "{e}");
}

#[test]
fn missing_field_names_the_table_and_field() {
    let e = error("[[object]]\ntype = \"sphere\"\ncenter = [0, 0, 0]\n");
    assert!(e.starts_with("test.toml:1"), "{e}");
    assert!(e.contains("`radius`"), "{e}");
    let e = parse("[image]\nwidth = 3\nheight = 3\n", Path::new("t.toml")).unwrap_err().to_string();
    assert!(e.contains("camera"), "{e}");
}

#[test]
fn semantic_errors_point_at_the_value() {
    for (extra, line, needle) in [
        ("[[object]]\ntype = \"sphere\"\ncenter = [0, 0, 0]\nradius = -1\n", 13, "must not be negative"),
        ("[[object]]\ntype = \"sphere\"\ncenter = [0, 0, 0]\nradius = 1\nmaterial = \"nope\"\n", 14, "nope"),
        ("[[object]]\ntype = \"polygon\"\nvertices = [[0,0,0],[1,0,0]]\n", 12, "at least 3"),
        ("[render]\nmax_depth = 1000\n", 11, "max_depth"),
        ("[[light]]\ntype = \"spotlight\"\nposition = [0,0,0]\n", 11, "spotlight"),
        ("[[light]]\ntype = \"directional\"\ndirection = [0,-1,0]\nattenuation = \"inverse_square\"\n", 13, "directional"),
    ] {
        let e = error(extra);
        assert!(e.starts_with(&format!("test.toml:{line}:")), "{e}");
        assert!(e.contains(needle), "{e}");
    }
}

#[test]
fn points_need_exactly_three_numbers() {
    for (center, needle) in [("[0, 0, 0, 1]", "array of 3 numbers, found 4 values"), ("[0, 0]", "found 2 values"), ("[0, 0, 1e39]", "32-bit")] {
        let e = error(&format!("[[object]]\ntype = \"sphere\"\ncenter = {center}\nradius = 1\n"));
        assert!(e.starts_with("test.toml:12:10:") && e.contains(needle), "{center}: {e}");
    }
    let e = error("[[object]]\ntype = \"polygon\"\nvertices = [[0, 0, 0], [1, 0, 0], [0, 1, 0, 7]]\n");
    assert!(e.starts_with("test.toml:12:") && e.contains("found 4 values"), "{e}");
}

#[test]
fn geometry_and_views_that_overflow_f32_are_errors() {
    let e = error("[[object]]\ntype = \"sphere\"\ncenter = [3e38, 0, 0]\nradius = 3e38\n");
    assert!(e.starts_with("test.toml:10:1:") && e.contains("32-bit floats"), "{e}");
    let e = error("[[object]]\ntype = \"cylinder\"\nbase = [3e38, 0, 0]\napex = [3e38, 1, 0]\nbase_radius = 3e38\n");
    assert!(e.starts_with("test.toml:10:1:") && e.contains("32-bit floats"), "{e}");
    let src = MINIMAL.replace("eye = [0, 0, 5]", "eye = [0, 0, 3e38]").replace("look_at = [0, 0, 0]", "look_at = [0, 0, -3e38]");
    let e = parse(&src, Path::new("p.toml")).unwrap_err().to_string();
    assert!(e.starts_with("p.toml:6:1:") && e.contains("too far apart"), "{e}");
}

#[test]
fn directions_and_normals_of_any_finite_size_normalise() {
    let s = parse_str(
        "[[light]]\ntype = \"directional\"\ndirection = [3e38, 0, 0]\n[[object]]\ntype = \"triangle\"\n\
         vertices = [[0, 0, 0], [1, 0, 0], [0, 1, 0]]\nnormals = [[0, 0, 3e38], [0, 0, 1e-30], [0, 0, 1]]\n",
    )
    .unwrap();
    assert_eq!(s.lights[0].kind, LightKind::Directional { direction: Vec3::X });
    assert!(matches!(&s.objects[0].shapes[0], Shape::Triangle { normals: Some(n), .. } if *n == [Vec3::Z; 3]));
}

#[test]
fn light_that_overflows_f32_is_an_error() {
    let e = error("[[light]]\ntype = \"point\"\nposition = [0, 0, 0]\ncolor = [3e38, 0, 0]\nintensity = 10\n");
    assert!(e.starts_with("test.toml:14:13:") && e.contains("overflows"), "{e}");
    let e = error("[ambient]\ncolor = 3e38\nintensity = 3e38\n");
    assert!(e.starts_with("test.toml:12:13:") && e.contains("overflows"), "{e}");
}

#[test]
fn type_errors_are_in_plain_words() {
    for (extra, want) in [
        ("[[object]]\ntype = \"sphere\"\ncenter = [0, 0, 0]\nradius = \"big\"\n", "test.toml:13:10: radius: expected a number, found the string \"big\""),
        ("[render]\nmax_depth = 3.0\n", "test.toml:11:13: max_depth: expected a whole number, found 3.0 (write 3, without the decimal point)"),
        ("[render]\nshadows = 1\n", "test.toml:11:11: shadows: expected `true` or `false`, found 1"),
        ("[[object]]\ntype = 3\n", "test.toml:11:8: type: expected a string in quotes, found 3"),
        ("[[object]]\ntype = \"sphere\"\ncenter = 1\nradius = 1\n", "test.toml:12:10: center: expected an array, found 1"),
    ] {
        let e = error(extra);
        assert_eq!(e, want);
        assert!(!e.contains("f64") && !e.contains("i64") && !e.contains("invalid type"), "{e}");
    }
}

#[test]
fn a_table_of_the_wrong_kind_is_explained() {
    let e = error("[object]\ntype = \"sphere\"\ncenter = [0, 0, 0]\nradius = 1\n");
    assert_eq!(e, "test.toml:10:2: [object] is a single table: write [[object]] (an array of tables) for each object");
    let e = error("[light]\ntype = \"point\"\nposition = [0, 0, 0]\n");
    assert!(e.starts_with("test.toml:10:") && e.contains("write [[light]]"), "{e}");
    let src = MINIMAL.replace("[camera]", "[[camera]]");
    let e = parse(&src, Path::new("t.toml")).unwrap_err().to_string();
    assert!(e.starts_with("t.toml:6:") && e.contains("a scene has one camera: write [camera]"), "{e}");
    let e = error("[material]\ncolor = [1, 0, 0]\n");
    assert!(e.starts_with("test.toml:11:1:") && e.contains("write [material.NAME]"), "{e}");
    let e = error("[[material]]\ncolor = [1, 0, 0]\n");
    assert!(e.starts_with("test.toml:10:") && e.contains("[material.red]"), "{e}");
}

#[test]
fn an_unclosed_array_is_reported_where_it_opens() {
    let e = error("[[object]]\ntype = \"sphere\"\ncenter = [0, 0, 0\nradius = 1\n");
    assert_eq!(e, "test.toml:12:10: center: this array is not closed: a `]` is missing");
    // At the end of the file too.
    let e = error("[[object]]\ntype = \"sphere\"\ncenter = [0, 0,\n");
    assert!(e.starts_with("test.toml:12:10:") && e.contains("not closed"), "{e}");
    // A comma missing inside a multi-line array is a missing comma, where it is.
    let e = error("[[object]]\ntype = \"polygon\"\nvertices = [\n  [0, 0, 0]\n  [1, 0, 0],\n  [0, 1, 0],\n]\n");
    assert!(e.starts_with("test.toml:14:") && e.contains("missing comma"), "{e}");
    let e = error("[[object]]\ntype = \"sphere\"\ncenter = [0 0 0]\nradius = 1\n");
    assert_eq!(e, "test.toml:12:10: center: the values of an array are separated by commas: write [0, 0, 0]");
}

#[test]
fn unknown_keys_name_the_first_in_the_file_and_the_nearest_valid_key() {
    // `zenter` comes before `radus` in the file, though not in the alphabet.
    let e = error("[[object]]\ntype = \"sphere\"\nzenter = [0, 0, 0]\nradus = 1\n");
    assert_eq!(e, "test.toml:12:1: unknown key `zenter` in a sphere object; did you mean `center`?");
    let e = error("[[object]]\ntype = \"sphere\"\ncenter = [0, 0, 0]\nradus = 1\n");
    assert_eq!(e, "test.toml:13:1: unknown key `radus` in a sphere object; did you mean `radius`?");
    // The keys of that type of object only, not all seventeen.
    let e = error("[[object]]\ntype = \"sphere\"\ncenter = [0, 0, 0]\nradius = 1\nwobble = 2\n");
    assert_eq!(e, "test.toml:14:1: unknown key `wobble` in a sphere object, which takes `type`, `material`, `center`, `radius`");
    // Across tables: [image] comes first in the file, [camera] in the alphabet.
    let src = MINIMAL.replace("height = 24", "heigth = 24").replace("fov = 40", "fov = 40\nfvo = 3");
    let e = parse(&src, Path::new("t.toml")).unwrap_err().to_string();
    assert_eq!(e, "t.toml:4:1: unknown key `heigth` in [image]; did you mean `height`?");
    for (extra, want) in [
        ("[[objects]]\ntype = \"sphere\"\n", "test.toml:10:3: unknown table [[objects]]; did you mean [[object]]?"),
        ("[render]\nspp = 4\n", "test.toml:11:1: unknown key `spp` in [render]: `spp` is a command-line option (glint render --spp …), not a scene key"),
        (
            "[[object]]\ntype = \"sphere\"\ncenter = [0, 0, 0]\nradius = 1\ncolor = [1, 0, 0]\n",
            "test.toml:14:1: unknown key `color` in a sphere object: `color` belongs to a material; define it in [material.NAME] and give the object `material = \"NAME\"`",
        ),
        ("[ambient]\nfov = 3\n", "test.toml:11:1: unknown key `fov` in [ambient]: `fov` belongs in [camera]"),
        ("[[light]]\ntype = \"point\"\npostion = [0, 0, 0]\n", "test.toml:12:1: unknown key `postion` in a point light; did you mean `position`?"),
        ("[material.red]\ncolour = 1\n", "test.toml:11:1: unknown key `colour` in [material.red]; did you mean `color`?"),
        (
            "[[object]]\ntype = \"torus\"\n",
            "test.toml:11:8: type: unknown object type `torus`, expected sphere, triangle, polygon, plane, cone, cylinder, mesh or icosphere",
        ),
    ] {
        assert_eq!(error(extra), want);
    }
}

fn warnings(src: &str) -> Vec<String> {
    parse(src, Path::new("w.toml")).unwrap().warnings.iter().map(ToString::to_string).collect()
}

#[test]
fn colours_written_0_to_255_and_radian_angles_warn() {
    let w = warnings(&format!("{MINIMAL}[material.red]\ncolor = [230, 50, 25]\n"));
    assert_eq!(
        w,
        ["w.toml:11:9: color: [230, 50, 25] looks like 0–255 values, but colours are 0 to 1, so what this material colours renders white; did you mean [0.9, 0.2, 0.1]?"]
    );
    let w = warnings(&format!("{MINIMAL}[material.white]\ncolor = 1.5\nreflect = [0.5, 0.5, 2]\n"));
    assert_eq!(w.len(), 2, "{w:?}");
    assert!(w[0].starts_with("w.toml:11:9: color: 1.5 is above 1"), "{w:?}");
    assert!(w[1].starts_with("w.toml:12:11: reflect: [0.5, 0.5, 2] is above 1"), "{w:?}");
    // Light may be brighter than 1; only 0–255 values are suspicious there.
    let light = |c: &str| format!("{MINIMAL}[[light]]\ntype = \"point\"\nposition = [0, 0, 0]\ncolor = {c}\n");
    assert!(warnings(&light("[1.0, 0.9, 2.5]")).is_empty());
    let w = warnings(&light("[255, 255, 255]"));
    assert_eq!(
        w,
        ["w.toml:13:9: color: 255 looks like 0–255 values, but colours are 0 to 1 (set the brightness with `intensity`), so this light washes the image out to white; did you mean 1?"]
    );
    let w = warnings(&MINIMAL.replace("fov = 40", "fov = 0.5"));
    assert_eq!(w, ["w.toml:9:7: fov: 0.5° is a very narrow view; angles are in degrees (0.5 radians is 28.6)"]);
    assert!(warnings(MINIMAL).is_empty());
    assert!(warnings(&MINIMAL.replace("fov = 40", "fov = 3.5")).is_empty());
    // In file order, whatever the order of checking.
    let src = format!("{}[material.a]\ncolor = [0, 0, 9]\n", MINIMAL.replace("[image]", "[image]\nbackground = [200, 200, 200]").replace("fov = 40", "fov = 1"));
    let lines: Vec<String> = warnings(&src).iter().map(|w| w.split(':').nth(1).unwrap().to_string()).collect();
    assert_eq!(lines, ["3", "10", "12"]);
}

#[test]
fn planes_are_infinite_or_rectangles() {
    let s = parse_str(
        "[[object]]\ntype = \"plane\"\npoint = [0, -1, 0]\nnormal = [0, 2, 0]\n\n\
         [[object]]\ntype = \"plane\"\npoint = [0, 0, -3]\nnormal = [0, 0, 1]\nsize = [4, 2]\n",
    )
    .unwrap();
    assert_eq!(s.objects[0].shapes, [Shape::Plane { point: Vec3::new(0.0, -1.0, 0.0), normal: Vec3::Y }], "the normal is normalised");
    assert_eq!(s.objects[1].shapes, [Shape::rectangle(Vec3::new(0.0, 0.0, -3.0), Vec3::Z, [4.0, 2.0]).unwrap()]);
}

#[test]
fn plane_errors_and_warnings_point_at_the_value() {
    let plane = |keys: &str| format!("[[object]]\ntype = \"plane\"\npoint = [0, 0, 0]\n{keys}");
    for (keys, want) in [
        ("", "test.toml:10:1: object: a plane needs `normal`"),
        ("normal = [0, 0, 0]\n", "test.toml:13:10: normal: must not be zero"),
        ("normal = [0, 1, 0]\nsize = [1, -2]\n", "test.toml:14:8: size: must not be negative, found -2"),
        ("normal = [0, 1, 0]\nsize = [1, 2, 3]\n", "test.toml:14:8: size: expected an array of 2 numbers, found 3 values"),
        ("normal = [0, 1, 0]\nradius = 1\n", "test.toml:10:1: object: `radius` does not apply to a plane"),
        ("nomral = [0, 1, 0]\n", "test.toml:13:1: unknown key `nomral` in a plane object; did you mean `normal`?"),
    ] {
        assert_eq!(error(&plane(keys)), want);
    }
    let e = error("[[object]]\ntype = \"plane\"\npoint = [3e38, 3e38, 0]\nnormal = [1, 1, 0]\n");
    assert_eq!(e, "test.toml:10:1: object: the plane reaches beyond the range of 32-bit floats");
    let w = warnings(&format!("{MINIMAL}{}", plane("normal = [0, 1, 0]\nsize = [0, 2]\n")));
    assert_eq!(w, ["w.toml:14:8: degenerate rectangle (no area) skipped"]);
}

#[test]
fn a_checker_on_any_material() {
    let s = parse_str("[material.board]\ncolor = [1, 0, 0]\nchecker = { color = [1, 1, 0], size = 2 }\n").unwrap();
    assert_eq!(s.materials[1].color, Vec3::X);
    assert_eq!(s.materials[1].checker, Some(crate::Checker { color: Vec3::new(1.0, 1.0, 0.0), size: 2.0 }));
    assert_eq!(s.materials[0].checker, None);
    let board = |checker: &str| format!("[material.board]\ncolor = 1\nchecker = {checker}\n");
    for (checker, want) in [
        ("{ color = 1 }", "test.toml:12:11: checker: missing key `size`"),
        ("{ color = 1, size = 0 }", "test.toml:12:31: size: a checker's tiles must be larger than 0, found 0"),
        ("{ colour = 1, size = 1 }", "test.toml:12:13: unknown key `colour` in the checker of [material.board]; did you mean `color`?"),
        ("{ color = 1, size = 1, ior = 2 }", "test.toml:12:34: unknown key `ior` in the checker of [material.board], which takes `color`, `size`"),
        ("[1, 1, 0]", "test.toml:12:11: checker: expected a table, found an array"),
    ] {
        assert_eq!(error(&board(checker)), want, "{checker}");
    }
    let w = warnings(&format!("{MINIMAL}{}", board("{ color = [1.5, 0, 0], size = 1 }")));
    assert_eq!(w.len(), 1);
    assert!(w[0].starts_with("w.toml:12:21: color: [1.5, 0, 0] is above 1"), "{w:?}");
}

#[test]
fn each_colour_written_0_to_255_is_named_once() {
    let sky = MINIMAL.replace("[image]", "[image]\nbackground = [135, 206, 235]");
    let w = warnings(&format!("{sky}[material.red]\ncolor = [230, 50, 25]\n[material.rust]\ncolor = [230, 50, 25]\n"));
    assert_eq!(
        w,
        [
            "w.toml:3:14: background: [135, 206, 235] looks like 0–255 values, but colours are 0 to 1, so the background renders white; did you mean [0.53, 0.81, 0.92]?",
            "w.toml:12:9: color: [230, 50, 25] looks like 0–255 values, but colours are 0 to 1, so what this material colours renders white; did you mean [0.9, 0.2, 0.1]?",
        ]
    );
}

#[test]
fn a_misspelt_material_suggests_the_nearest_name() {
    let scene = |name: &str| format!("[material.mirror]\ncolor = 0.9\nreflect = 0.9\n[[object]]\ntype = \"sphere\"\ncenter = [0, 0, 0]\nradius = 1\nmaterial = \"{name}\"\n");
    assert_eq!(error(&scene("mirorr")), "test.toml:17:12: material: no material named `mirorr`; did you mean `mirror`?");
    assert_eq!(error(&scene("glass")), "test.toml:17:12: material: no material named `glass`");
}

#[test]
fn up_parallel_to_view_says_the_default_and_suggests_one_that_works() {
    let looking_down = MINIMAL.replace("eye = [0, 0, 5]", "eye = [0, 5, 0]");
    let e = parse(&looking_down, Path::new("p.toml")).unwrap_err().to_string();
    assert_eq!(
        e,
        "p.toml:6:1: camera: `up` is not set, and its default [0, 1, 0] is parallel to the view direction [0, -1, 0], from eye to look_at; add up = [0, 0, -1]"
    );
    let src = MINIMAL.replace("fov = 40", "fov = 40\nup = [0, 0, 1]");
    let e = parse(&src, Path::new("p.toml")).unwrap_err().to_string();
    assert_eq!(e, "p.toml:10:6: up: [0, 0, 1] is parallel to the view direction [0, 0, -1], from eye to look_at; try up = [0, 1, 0]");
    let src = MINIMAL.replace("eye = [0, 0, 5]", "eye = [0, 0, 0]");
    let e = parse(&src, Path::new("p.toml")).unwrap_err().to_string();
    assert_eq!(e, "p.toml:6:1: camera: eye and look_at are the same point, so the camera looks nowhere");
    // The suggestion works.
    let fixed = looking_down.replace("fov = 40", "fov = 40\nup = [0, 0, -1]");
    assert!(parse(&fixed, Path::new("p.toml")).is_ok());
}

#[test]
fn absurd_image_size_is_an_error() {
    let src = MINIMAL.replace("width = 32", "width = 100000");
    let e = parse(&src, Path::new("p.toml")).unwrap_err().to_string();
    assert!(e.starts_with("p.toml:3:"), "{e}");
    let src = MINIMAL.replace("width = 32", "width = 0");
    assert!(parse(&src, Path::new("p.toml")).is_err());
}

mod files {
    use super::*;
    use crate::obj::tests::{write, CUBE_MTL, CUBE_OBJ};

    fn scene_file(dir: &Path, extra: &str) -> Result<Scene, LoadError> {
        crate::load(&write(dir, "scene.toml", &format!("{MINIMAL}{extra}")))
    }

    fn bounds(shapes: &[Shape]) -> (Vec3, Vec3) {
        shapes.iter().filter_map(Shape::bounds).reduce(|(a, b), (c, d)| (a.min(c), b.max(d))).unwrap()
    }

    fn close(a: Vec3, b: Vec3) -> bool {
        (a - b).abs().max_element() < 1e-5
    }

    #[test]
    fn mirroring_transforms_keep_faces_and_vertex_normals_on_one_side() {
        let dir = tempfile::tempdir().unwrap();
        write(dir.path(), "tri.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nvn 0 0 1\nvn 0 0 1\nvn 0 0 1\nf 1//1 2//2 3//3\n");
        for transform in ["scale = [-1, 1, 1]", "scale = [1, 1, 1]", "matrix = [[1, 0, 0, 0], [0, 1, 0, 0], [0, 0, -1, 0], [0, 0, 0, 1]]"] {
            let s = scene_file(dir.path(), &format!("[[object]]\ntype = \"mesh\"\npath = \"tri.obj\"\n{transform}\n")).unwrap();
            let Shape::Triangle { vertices: [a, b, c], normals: Some(n) } = &s.objects[0].shapes[0] else { panic!() };
            let face = (*b - *a).cross(*c - *a);
            assert!(n.iter().all(|n| face.dot(*n) > 0.0), "{transform}: face {face} against normals {n:?}");
        }
    }

    #[test]
    fn mesh_instances_with_transforms() {
        let dir = tempfile::tempdir().unwrap();
        write(dir.path(), "cube.obj", CUBE_OBJ);
        write(dir.path(), "cube.mtl", CUBE_MTL);
        let s = scene_file(
            dir.path(),
            r#"
[material.gold]
color = [1, 0.8, 0.2]

[[object]]
type = "mesh"
path = "cube.obj"
scale = 2
rotate = [0, 90, 0]
translate = [10, 0, 0]

[[object]]
type = "mesh"
path = "./cube.obj"
material = "gold"
matrix = [[1, 0, 0, 0], [0, 1, 0, 5], [0, 0, 1, 0], [0, 0, 0, 1]]

[[object]]
type = "mesh"
path = "cube.obj"
"#,
        )
        .unwrap();
        assert!(s.warnings.is_empty(), "{:?}", s.warnings);
        // Each instance is three objects (one per material) of four triangles.
        assert_eq!(s.objects.len(), 9);
        assert_eq!(s.primitive_count(), 36);
        // default, gold, then the MTL's three, added once.
        let names: Vec<&str> = s.materials.iter().map(|m| m.name.as_str()).collect();
        assert_eq!(names, ["default", "gold", "red", "green", "blue"]);
        let ids: Vec<usize> = s.objects.iter().map(|o| o.material).collect();
        assert_eq!(ids, [2, 3, 4, 1, 1, 1, 2, 3, 4]);

        let first: Vec<Shape> = s.objects[..3].iter().flat_map(|o| o.shapes.clone()).collect();
        let (lo, hi) = bounds(&first);
        assert!(close(lo, Vec3::new(10.0, 0.0, -2.0)) && close(hi, Vec3::new(12.0, 2.0, 0.0)), "{lo} {hi}");
        let second: Vec<Shape> = s.objects[3..6].iter().flat_map(|o| o.shapes.clone()).collect();
        let (lo, hi) = bounds(&second);
        assert!(close(lo, Vec3::new(0.0, 5.0, 0.0)) && close(hi, Vec3::new(1.0, 6.0, 1.0)), "{lo} {hi}");
        let third: Vec<Shape> = s.objects[6..].iter().flat_map(|o| o.shapes.clone()).collect();
        assert!(close(bounds(&third).1, Vec3::ONE));
    }

    #[test]
    fn normals_use_the_inverse_transpose() {
        let dir = tempfile::tempdir().unwrap();
        // A triangle in the plane x + y = 1 with its true normal.
        write(dir.path(), "slope.obj", "v 1 0 0\nv 0 1 0\nv 1 0 1\nvn 1 1 0\nf 1//1 2//1 3//1\n");
        let s = scene_file(dir.path(), "[[object]]\ntype = \"mesh\"\npath = \"slope.obj\"\nscale = [2, 1, 1]\n").unwrap();
        let Shape::Triangle { vertices, normals: Some(n) } = &s.objects[0].shapes[0] else { panic!() };
        assert_eq!(vertices[0], Vec3::new(2.0, 0.0, 0.0));
        // The plane is now x/2 + y = 1, normal ∝ (1/2, 1, 0).
        let want = Vec3::new(0.5, 1.0, 0.0).normalize();
        assert!(n.iter().all(|v| close(*v, want)), "{n:?}");
        let face = (vertices[1] - vertices[0]).cross(vertices[2] - vertices[0]).normalize();
        assert!(face.dot(want).abs() > 0.99999);
    }

    #[test]
    fn a_mesh_read_twice_warns_once() {
        let dir = tempfile::tempdir().unwrap();
        write(dir.path(), "cube.obj", CUBE_OBJ);
        let mesh = "[[object]]\ntype = \"mesh\"\npath = \"cube.obj\"\n";
        let s = scene_file(dir.path(), &format!("{mesh}{mesh}translate = [3, 0, 0]\n")).unwrap();
        assert_eq!(s.warnings.len(), 1, "{:?}", s.warnings);
        assert!(s.warnings[0].to_string().contains("cube.mtl"));
        assert_eq!(s.materials.len(), 2, "the TOML default, then the OBJ's default once");
        assert!(s.objects.iter().all(|o| o.material == 1));
        assert_eq!(s.primitive_count(), 24);
    }

    #[test]
    fn mesh_errors() {
        let dir = tempfile::tempdir().unwrap();
        write(dir.path(), "cube.obj", CUBE_OBJ);
        write(dir.path(), "bad.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 9\n");
        for (extra, at, needle) in [
            ("[[object]]\ntype = \"mesh\"\npath = \"missing.obj\"\n", "scene.toml:12:", "cannot open"),
            ("[[object]]\ntype = \"mesh\"\npath = \"bad.obj\"\n", "bad.obj:4: ", "malformed OBJ"),
            ("[[object]]\ntype = \"mesh\"\n", "scene.toml:10:", "needs `path`"),
            (
                "[[object]]\ntype = \"mesh\"\npath = \"cube.obj\"\ntranslate = [1, 0, 0]\nmatrix = [[1,0,0,0],[0,1,0,0],[0,0,1,0],[0,0,0,1]]\n",
                "scene.toml:14:",
                "cannot be combined",
            ),
            ("[[object]]\ntype = \"mesh\"\npath = \"cube.obj\"\nmatrix = [[1,0,0,0],[0,1,0,0],[0,0,1,0],[0,0,1,1]]\n", "scene.toml:13:", "last row"),
            ("[[object]]\ntype = \"mesh\"\npath = \"cube.obj\"\nmatrix = [[1,0,0,0],[0,1,0,0],[0,0,0,0],[0,0,0,1]]\n", "scene.toml:13:", "singular"),
            ("[[object]]\ntype = \"mesh\"\npath = \"cube.obj\"\nmatrix = [[1,0,0],[0,1,0],[0,0,1]]\n", "scene.toml:13:", "matrix"),
            ("[[object]]\ntype = \"mesh\"\npath = \"cube.obj\"\nscale = [1, 0, 1]\n", "scene.toml:13:", "zero"),
            ("[[object]]\ntype = \"mesh\"\npath = \"cube.obj\"\nrotate = [1, 0]\n", "scene.toml:13:", "rotate"),
            ("[[object]]\ntype = \"mesh\"\npath = \"cube.obj\"\nmaterial = \"nope\"\n", "scene.toml:13:", "nope"),
            ("[[object]]\ntype = \"sphere\"\ncenter = [0, 0, 0]\nradius = 1\ntranslate = [1, 0, 0]\n", "scene.toml:10:", "`translate` does not apply"),
            ("[[object]]\ntype = \"mesh\"\npath = \"cube.obj\"\nradius = 1\n", "scene.toml:10:", "`radius` does not apply"),
        ] {
            let e = scene_file(dir.path(), extra).unwrap_err().to_string();
            assert!(e.contains(at) && e.contains(needle), "{extra}: {e}");
        }
    }

    #[test]
    fn unreadable_references_name_the_right_file() {
        let dir = tempfile::tempdir().unwrap();
        std::fs::create_dir(dir.path().join("folder.obj")).unwrap();
        write(dir.path(), "part.nff", "s 0 0 0 1\n");
        std::fs::write(dir.path().join("binary.obj"), b"v 0 0 0\nv 1 \xff 0\n").unwrap();
        std::fs::write(dir.path().join("binary.nff"), b"s 0 0 0 1\n\x80").unwrap();
        write(dir.path(), "cube.obj", CUBE_OBJ);
        for (extra, at, needle) in [
            // A directory canonicalises but cannot be read: the TOML line says so.
            ("[[object]]\ntype = \"mesh\"\npath = \"folder.obj\"\n", "scene.toml:12:8:", "cannot read"),
            ("[[object]]\ntype = \"mesh\"\npath = \"binary.obj\"\n", "binary.obj:2:5:", "not a text file"),
            ("[[include]]\npath = \"binary.nff\"\n", "binary.nff:2:1:", "not a text file"),
            // An NFF read as an OBJ would fail on its first line, naming the wrong problem.
            ("[[object]]\ntype = \"mesh\"\npath = \"part.nff\"\n", "scene.toml:12:8:", "[[include]]"),
            (
                "[[object]]\ntype = \"mesh\"\npath = \"cube.obj\"\nmatrix = [[1,0,0,0],[0,1,0,0],[0,0,1,0,5],[0,0,0,1]]\n",
                "scene.toml:13:",
                "row length 5",
            ),
            ("[[object]]\ntype = \"mesh\"\npath = \"cube.obj\"\nscale = 1e38\ntranslate = [0, 0, 3e38]\n", "scene.toml:10:1:", "32-bit floats"),
        ] {
            let e = scene_file(dir.path(), extra).unwrap_err().to_string();
            assert!(e.contains(at) && e.contains(needle), "{extra}: {e}");
        }
    }

    #[test]
    fn include_merges_an_nff() {
        let dir = tempfile::tempdir().unwrap();
        // No `v` block: an included NFF may be geometry only.
        write(dir.path(), "part.nff", "b 1 0 0\nl 1 2 3\nl 4 5 6 0 1 0\nf 0 1 0 1 0 0 0 1\ns 0 0 0 1\np 3\n0 0 0\n1 0 0\n0 1 0\n");
        let s = scene_file(
            dir.path(),
            r#"
[[light]]
type = "point"
position = [0, 9, 0]

[material.red]
color = [1, 0, 0]

[[object]]
type = "sphere"
center = [5, 0, 0]
radius = 1
material = "red"

[[include]]
path = "part.nff"
"#,
        )
        .unwrap();
        assert_eq!(s.background, Vec3::ZERO, "the TOML file's image settings apply");
        assert_eq!(s.objects.len(), 3);
        assert_eq!(s.objects[0].material, 1);
        assert_eq!(s.materials.len(), 3);
        assert!(s.objects[1..].iter().all(|o| s.materials[o.material].color == Vec3::Y));
        assert_eq!(s.objects[1].shapes[0], Shape::Sphere { center: Vec3::ZERO, radius: 1.0 });
        assert_eq!(s.lights.len(), 3);
        assert_eq!(s.lights[2].color, Vec3::Y);
        assert!((s.lights[1].intensity - 2f32.sqrt() / 4.0).abs() < 1e-7, "SPD's √n / (2n) for the file's 2 lights");
        assert_eq!(s.camera.eye, Vec3::new(0.0, 0.0, 5.0));

        // A generated SPD database is included like a file.
        let s = scene_file(dir.path(), "[[include]]\npath = \"spd:tetra:1\"\n").unwrap();
        assert_eq!((s.objects.len(), s.lights.len()), (4, 1));
    }

    #[test]
    fn include_errors() {
        let dir = tempfile::tempdir().unwrap();
        write(dir.path(), "bad.nff", "s 0 0 0 1\ns 0 0\n");
        write(dir.path(), "cube.obj", CUBE_OBJ);
        for (extra, at, needle) in [
            ("[[include]]\npath = \"nope.nff\"\n", "scene.toml:11:", "cannot read"),
            ("[[include]]\npath = \"cube.obj\"\n", "scene.toml:11:", "only .nff"),
            ("[[include]]\npath = \"bad.nff\"\n", "bad.nff:2:1:", "end of file"),
            ("[[include]]\npath = \"bad.nff\"\ndepth = 2\n", "scene.toml:12:", "depth"),
            ("[[include]]\npath = \"spd:tetras\"\n", "scene.toml:11:", "no SPD database named `tetras`"),
            ("[[include]]\npath = \"spd:tetra:99\"\n", "scene.toml:11:", "a whole number from 1 to 10"),
        ] {
            let e = scene_file(dir.path(), extra).unwrap_err().to_string();
            assert!(e.contains(at) && e.contains(needle), "{extra}: {e}");
        }
    }
}
