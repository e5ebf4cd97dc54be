//! One policy for degenerate and non-planar shapes in every format
//! (docs/scene-format.md, "Errors and warnings"): the same shape written in
//! TOML, NFF and OBJ loads to the same outcome, with the same warning at the
//! line that describes it.

use std::path::Path;

use glint_scene::{LoadError, Scene};

const TOML_HEAD: &str = "[image]\nwidth = 8\nheight = 8\n\n[camera]\neye = [0, 0, 5]\nlook_at = [0, 0, 0]\nfov = 40\n\n";
const NFF_HEAD: &str = "v\nfrom 0 0 5\nat 0 0 0\nup 0 1 0\nangle 40\nhither 0.1\nresolution 8 8\n";
/// A shape every file also holds, so that each loads with something to render.
const TOML_KEPT: &str = "[[object]]\ntype = \"sphere\"\ncenter = [0, 0, -3]\nradius = 1\n\n";
const NFF_KEPT: &str = "s 0 0 -3 1\n";
const OBJ_KEPT: &str = "v 0 0 -3\nv 1 0 -3\nv 0 1 -3\nf 1 2 3\n";

/// How a file with one shape in question loaded: the primitives beyond the
/// one every file holds, and its only warning as (line, message).
#[derive(Debug, PartialEq)]
struct Outcome {
    extra_primitives: usize,
    warning: (usize, String),
}

fn outcome(dir: &Path, name: &str, text: &str) -> Outcome {
    let path = dir.join(name);
    std::fs::write(&path, text).unwrap();
    let scene: Scene = glint_scene::load(&path).unwrap_or_else(|e| panic!("{name} does not load: {e}"));
    let [warning]: [LoadError; 1] = scene.warnings.clone().try_into().unwrap_or_else(|w| panic!("{name}: {w:?}"));
    assert_eq!(warning.path, path, "the warning names the file");
    let line = warning.location.as_ref().unwrap_or_else(|| panic!("{name}: the warning names no line: {warning}")).line;
    Outcome { extra_primitives: scene.primitive_count() - 1, warning: (line, warning.message) }
}

/// Loads the shape as TOML (its table on line 15) and as NFF (on line 9), and
/// checks both against `expected`.
fn toml_and_nff(dir: &Path, toml_object: &str, nff_statement: &str, expected: &Outcome) {
    let toml = outcome(dir, "shape.toml", &format!("{TOML_HEAD}{TOML_KEPT}{toml_object}"));
    let nff = outcome(dir, "shape.nff", &format!("{NFF_HEAD}{NFF_KEPT}{nff_statement}"));
    assert_eq!(&toml, expected, "TOML");
    assert_eq!(&nff, &Outcome { warning: (9, expected.warning.1.clone()), ..*expected }, "NFF");
}

#[test]
fn a_zero_radius_sphere_is_skipped_with_a_warning_in_every_format() {
    let dir = tempfile::tempdir().unwrap();
    let expected = Outcome { extra_primitives: 0, warning: (18, "sphere of radius 0 skipped".into()) };
    toml_and_nff(dir.path(), "[[object]]\ntype = \"sphere\"\ncenter = [0, 0, 0]\nradius = 0\n", "s 0 0 0 0\n", &expected);
}

#[test]
fn a_cone_with_equal_ends_or_no_radius_is_skipped_with_a_warning_in_every_format() {
    let dir = tempfile::tempdir().unwrap();
    let message = "degenerate cone (base equals apex, or both radii 0) skipped";
    let expected = Outcome { extra_primitives: 0, warning: (15, message.into()) };
    let toml = |base, apex, r0, r1| format!("[[object]]\ntype = \"cone\"\nbase = {base}\nbase_radius = {r0}\napex = {apex}\napex_radius = {r1}\n");
    toml_and_nff(dir.path(), &toml("[0, 0, 0]", "[0, 0, 0]", 1, 0), "c 0 0 0 1 0 0 0 0\n", &expected);
    toml_and_nff(dir.path(), &toml("[0, 0, 0]", "[0, 1, 0]", 0, 0), "c 0 0 0 0 0 1 0 0\n", &expected);
}

#[test]
fn a_zero_area_triangle_is_skipped_with_a_warning_in_every_format() {
    let dir = tempfile::tempdir().unwrap();
    let toml = "[[object]]\ntype = \"triangle\"\nvertices = [[0, 0, 0], [1, 1, 1], [2, 2, 2]]\n";
    let expected = Outcome { extra_primitives: 0, warning: (17, "degenerate triangle (no area) skipped".into()) };
    assert_eq!(outcome(dir.path(), "shape.toml", &format!("{TOML_HEAD}{TOML_KEPT}{toml}")), expected, "TOML");
    let obj = format!("{OBJ_KEPT}v 0 0 0\nv 1 1 1\nv 2 2 2\nf 4 5 6\n");
    assert_eq!(outcome(dir.path(), "shape.obj", &obj), Outcome { warning: (8, expected.warning.1.clone()), ..expected }, "OBJ");
}

#[test]
fn a_zero_area_polygon_is_skipped_with_a_warning_in_every_format() {
    let dir = tempfile::tempdir().unwrap();
    let toml = "[[object]]\ntype = \"polygon\"\nvertices = [[0, 0, 0], [1, 0, 0], [2, 0, 0], [3, 0, 0]]\n";
    let message = "degenerate polygon (4 vertices, no area) skipped";
    let expected = Outcome { extra_primitives: 0, warning: (17, message.into()) };
    let toml = outcome(dir.path(), "shape.toml", &format!("{TOML_HEAD}{TOML_KEPT}{toml}"));
    assert_eq!(toml, expected, "TOML");
    let nff = outcome(dir.path(), "shape.nff", &format!("{NFF_HEAD}{NFF_KEPT}p 4\n0 0 0\n1 0 0\n2 0 0\n3 0 0\n"));
    assert_eq!(nff, Outcome { warning: (9, message.into()), ..expected }, "NFF");
    let obj = outcome(dir.path(), "shape.obj", &format!("{OBJ_KEPT}v 0 0 0\nv 1 0 0\nv 2 0 0\nv 3 0 0\nf 4 5 6 7\n"));
    assert_eq!(obj, Outcome { warning: (9, message.into()), ..expected }, "OBJ");
}

#[test]
fn a_non_planar_polygon_is_kept_with_a_warning_in_every_format() {
    let dir = tempfile::tempdir().unwrap();
    let toml = "[[object]]\ntype = \"polygon\"\nvertices = [[0, 0, 0], [1, 0, 0], [1, 1, 0], [0, 1, 1]]\n";
    let toml = outcome(dir.path(), "shape.toml", &format!("{TOML_HEAD}{TOML_KEPT}{toml}"));
    let nff = outcome(dir.path(), "shape.nff", &format!("{NFF_HEAD}{NFF_KEPT}p 4\n0 0 0\n1 0 0\n1 1 0\n0 1 1\n"));
    let obj = outcome(dir.path(), "shape.obj", &format!("{OBJ_KEPT}v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 1\nf 4 5 6 7\n"));
    let message = &toml.warning.1;
    assert!(message.starts_with("polygon is not planar") && message.ends_with("; kept"), "{message}");
    assert_eq!((toml.extra_primitives, toml.warning.0), (1, 17), "TOML keeps the polygon");
    assert_eq!(nff, Outcome { extra_primitives: 1, warning: (9, message.clone()) }, "NFF keeps the polygon");
    // An OBJ mesh holds triangles: the face is kept as a fan of two.
    assert_eq!(obj, Outcome { extra_primitives: 2, warning: (9, message.clone()) }, "OBJ keeps the face");
}

#[test]
fn many_degenerate_obj_faces_make_one_warning_at_the_first() {
    let dir = tempfile::tempdir().unwrap();
    let obj = format!("{OBJ_KEPT}v 0 0 0\nv 1 0 0\nv 2 0 0\nf 4 5 6\nf 6 5 4\nf 4 6 5\n");
    let expected = Outcome { extra_primitives: 0, warning: (8, "degenerate triangle (no area) skipped (and 2 more degenerate faces)".into()) };
    assert_eq!(outcome(dir.path(), "shape.obj", &obj), expected);
}
