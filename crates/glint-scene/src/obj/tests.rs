//! The OBJ reader: meshes, MTL mapping, and errors and warnings at their lines.

use super::*;

pub const CUBE_OBJ: &str = "\
# a unit cube, one material per pair of opposite faces
mtllib cube.mtl
v 0 0 0
v 1 0 0
v 1 1 0
v 0 1 0
v 0 0 1
v 1 0 1
v 1 1 1
v 0 1 1
o cube
usemtl red
f 1 4 3 2
f 5 6 7 8
usemtl green
f 1 2 6 5
f 4 8 7 3
usemtl blue
f 1 5 8 4
f 2 3 7 6
";

pub const CUBE_MTL: &str = "\
newmtl red
Ka 1 1 1
Kd 0.8 0.1 0.1
Ks 0.5 0.5 0.5
Ns 50
illum 2

newmtl green
Kd 0.1 0.8 0.1
Ks 0.9 0.9 0.9
Ns 200
illum 3

newmtl blue
Kd 0.1 0.1 0.8
Ks 0.2 0.2 0.2
Ni 1.33
d 0.25
illum 7
";

pub fn write(dir: &Path, name: &str, text: &str) -> PathBuf {
    let p = dir.join(name);
    std::fs::write(&p, text).unwrap();
    p
}

fn triangles(s: &Scene) -> Vec<&Shape> {
    s.objects.iter().flat_map(|o| &o.shapes).collect()
}

#[test]
fn cube_with_mtl() {
    let dir = tempfile::tempdir().unwrap();
    write(dir.path(), "cube.mtl", CUBE_MTL);
    let scene = load(&write(dir.path(), "cube.obj", CUBE_OBJ)).unwrap();
    assert!(scene.warnings.is_empty(), "{:?}", scene.warnings);
    assert_eq!(triangles(&scene).len(), 12);
    assert_eq!(scene.materials.len(), 3, "no default needed");
    let colors: Vec<Vec3> = scene.objects.iter().map(|o| scene.materials[o.material].color).collect();
    assert_eq!(colors, [Vec3::new(0.8, 0.1, 0.1), Vec3::new(0.1, 0.8, 0.1), Vec3::new(0.1, 0.1, 0.8)]);
    for o in &scene.objects {
        assert_eq!(o.shapes.len(), 4);
        assert!(o.shapes.iter().all(|s| matches!(s, Shape::Triangle { normals: None, .. })));
    }

    let red = &scene.materials[0];
    assert_eq!((red.name.as_str(), red.ambient, red.diffuse, red.specular, red.shininess), ("red", 0.1, 1.0, 1.0, 50.0));
    assert_eq!(red.specular_color, Some(Vec3::splat(0.5)));
    assert_eq!(red.specular_model, SpecularModel::BlinnPhong);
    assert_eq!((red.reflect, red.transmit, red.ior, red.fresnel), (Vec3::ZERO, Vec3::ZERO, 1.0, false));
    let green = &scene.materials[1];
    assert_eq!(green.reflect, Vec3::splat(0.9), "illum 3 mirrors with Ks");
    let blue = &scene.materials[2];
    assert_eq!(blue.transmit, Vec3::splat(0.75));
    assert_eq!((blue.diffuse, blue.ior, blue.fresnel), (0.25, 1.33, true));
    assert_eq!(blue.reflect, Vec3::splat(0.2));

    // The default camera sees the whole cube.
    assert_eq!((scene.width, scene.height), (DEFAULT_WIDTH, DEFAULT_HEIGHT));
    assert_eq!(scene.camera.look_at, Vec3::splat(0.5));
    for corner in [Vec3::ZERO, Vec3::ONE, Vec3::X, Vec3::new(1.0, 1.0, 0.0), Vec3::new(0.0, 0.0, 1.0)] {
        let (x, y) = scene.camera.project(scene.width, scene.height, corner.as_dvec3()).unwrap();
        assert!((0.0..640.0).contains(&x) && (0.0..480.0).contains(&y), "{corner}: {x} {y}");
    }
    assert_eq!(scene.lights.len(), 1);
}

#[test]
fn tr_is_the_inverse_of_d_and_glass_uses_tf() {
    let mut m = tobj::Material { name: "g".into(), illumination_model: Some(2), ..Default::default() };
    m.unknown_param.insert("Tr".into(), "0.3".into());
    let g = material_from_mtl(&m);
    assert!((g.transmit - Vec3::splat(0.3)).length() < 1e-6 && (g.diffuse - 0.7).abs() < 1e-6);
    assert_eq!(g.ior, 1.0, "dissolve alone does not refract");
    assert_eq!(g.specular, 0.0, "no Ks, no highlights");

    let mut m = tobj::Material { name: "glass".into(), illumination_model: Some(6), optical_density: None, ..Default::default() };
    m.unknown_param.insert("Tf".into(), "0.9 0.95 1".into());
    let g = material_from_mtl(&m);
    assert_eq!((g.transmit, g.ior, g.diffuse), (Vec3::new(0.9, 0.95, 1.0), 1.5, 1.0));
}

#[test]
fn missing_mtl_is_a_warning() {
    let dir = tempfile::tempdir().unwrap();
    let scene = load(&write(dir.path(), "cube.obj", CUBE_OBJ)).unwrap();
    assert_eq!(triangles(&scene).len(), 12);
    assert_eq!(scene.materials.len(), 1);
    assert_eq!(scene.materials[0], Material::default());
    assert_eq!(scene.warnings.len(), 1, "{:?}", scene.warnings);
    let w = scene.warnings[0].to_string();
    assert!(w.contains("cube.obj:2: ") && w.contains("cube.mtl"), "{w}");
}

#[test]
fn unknown_material_is_a_warning() {
    let dir = tempfile::tempdir().unwrap();
    write(dir.path(), "cube.mtl", CUBE_MTL);
    let obj = CUBE_OBJ.replace("usemtl blue", "usemtl purple");
    let scene = load(&write(dir.path(), "cube.obj", &obj)).unwrap();
    assert_eq!(scene.materials.len(), 4);
    assert_eq!(scene.warnings.len(), 1);
    assert!(scene.warnings[0].to_string().contains("cube.obj:18: ") && scene.warnings[0].message.contains("purple"));
    assert_eq!(scene.objects[2].material, 3);
}

#[test]
fn normals_make_smooth_triangles() {
    let dir = tempfile::tempdir().unwrap();
    let obj = "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nvn 0 0 2\nvn 0 0 1\nvn 0 1 1\nvn 1 0 1\nf 1//1 2//2 3//3 4//4\n";
    let scene = load(&write(dir.path(), "quad.obj", obj)).unwrap();
    let tris = triangles(&scene);
    assert_eq!(tris.len(), 2);
    let Shape::Triangle { vertices, normals: Some(n) } = tris[0] else { panic!("{:?}", tris[0]) };
    assert_eq!(vertices[1], Vec3::X);
    assert_eq!(n[0], Vec3::Z);
    assert!((n[2] - Vec3::new(0.0, 1.0, 1.0).normalize()).length() < 1e-6);
    assert_eq!(scene.materials.len(), 1, "no MTL: the default");
    assert!(scene.warnings.is_empty(), "{:?}", scene.warnings);
}

#[test]
fn errors_name_file_and_line() {
    let dir = tempfile::tempdir().unwrap();
    let e = load(&dir.path().join("nope.obj")).unwrap_err().to_string();
    assert!(e.contains("nope.obj: cannot read"), "{e}");
    for (obj, line, needle) in [
        ("v 0 0 0\nv 1 0 0\nv 0 x 0\nf 1 2 3\n", 3, "position"),
        ("v 0 0 0\nv 1 0 0\nv 0 1 0\n\nf 1 2 7\n", 5, "malformed OBJ"),
        ("v 0 0 0\nv nan 0 0\nv 0 1 0\nf 1 2 3\n", 2, "finite"),
    ] {
        let e = load(&write(dir.path(), "bad.obj", obj)).unwrap_err().to_string();
        assert!(e.contains(&format!("bad.obj:{line}: ")) && e.contains(needle), "{e}");
    }
    write(dir.path(), "bad.mtl", "newmtl a\nKd 1 1 1\nNs many\n");
    let e = load(&write(dir.path(), "m.obj", "mtllib bad.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n")).unwrap_err().to_string();
    assert!(e.contains("bad.mtl:3: ") && e.contains("malformed MTL"), "{e}");
    let e = load(&write(dir.path(), "empty.obj", "v 0 0 0\n")).unwrap_err().to_string();
    assert!(e.contains("no faces"), "{e}");
}

#[test]
fn statements_are_checked_before_tobj_sees_them() {
    let dir = tempfile::tempdir().unwrap();
    const TRI: &str = "v 0 0 0\nv 1 0 0\nv 0 1 0\n";
    for (body, line, needle) in [
        ("v 1 0\n", 4, "found 2 value(s)"),
        ("v 1 0 0 1 1\n", 4, "found 5 value(s)"),
        ("v 1 0 0 0\n", 4, "w = `0`"),
        ("v 1 0 0 1e-40\n", 4, "range of 32-bit floats"),
        ("v 1e39 0 0\n", 4, "`1e39` is not a finite number"),
        ("vn 0 1\n", 4, "`vn` takes x y z"),
        ("vt 0.5 0.5 0.5 0.5\n", 4, "`vt` takes u v [w]"),
        ("f 1 2\n", 4, "at least 3 vertices, found 2"),
        ("l 1\n", 4, "at least 2 vertices"),
        ("f 0 1 2\n", 4, "OBJ counts from 1"),
        ("f 1 2 4\n", 4, "only 3 vertices are defined"),
        ("f -1 -2 -4\n", 4, "refers to vertex -4"),
        ("f 1 2 -9223372036854775808\n", 4, "refers to vertex -9223372036854775808"),
        ("f 1 2 99999999999999999999\n", 4, "not a whole number"),
        ("f 1/1 2/1 3/1\n", 4, "no texture coordinates are defined"),
        ("vn 0 0 1\nf 1//1 2//1 3//2\n", 5, "only 1 normal is defined"),
        ("f 1 2 3/1/1/1\n", 4, "not a vertex reference"),
        ("f 1 2 /3\n", 4, "not a vertex reference"),
    ] {
        let e = load(&write(dir.path(), "bad.obj", &format!("{TRI}{body}"))).unwrap_err().to_string();
        assert!(e.contains(&format!("bad.obj:{line}: malformed OBJ: ")) && e.contains(needle), "{body:?}: {e}");
    }
    // Valid forms still load: w, relative indices, texture coordinates, vertex colours.
    let ok = "v 0 0 0 2\nv 2 0 0 2\nv 0 1 0\nvt 0 0\nvt 1 0 0\nvn 0 0 1\nf -3/1/1 -2/2/1 -1//1\n";
    let s = load(&write(dir.path(), "ok.obj", ok)).unwrap();
    assert_eq!(triangles(&s).len(), 1);
    let Shape::Triangle { vertices, .. } = triangles(&s)[0] else { panic!() };
    assert_eq!(vertices[1], Vec3::X, "w divides");
    let colours = "v 0 0 0 1 0 0\nv 1 0 0 0 1 0\nv 0 1 0 0 0 1\nf 1 2 3\n";
    assert_eq!(triangles(&load(&write(dir.path(), "rgb.obj", colours)).unwrap()).len(), 1);
}

#[test]
fn mtl_colours_take_three_values_or_one_grey() {
    let dir = tempfile::tempdir().unwrap();
    let obj = "mtllib m.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nusemtl a\nf 1 2 3\n";
    // One value is a grey (tobj 4 itself panics on it).
    write(dir.path(), "m.mtl", "newmtl a\nKd 0.5\nKs 0.25\nNs 10\n");
    let s = load(&write(dir.path(), "m.obj", obj)).unwrap();
    assert_eq!(s.materials[0].color, Vec3::splat(0.5));
    assert_eq!(s.materials[0].specular_color, Some(Vec3::splat(0.25)));
    assert_eq!(s.materials[0].shininess, 10.0);
    for (mtl, line, needle) in [
        ("newmtl a\nKd 1 0\n", 2, "found 2 value(s)"),
        ("newmtl a\nKs\n", 2, "found 0 value(s)"),
        ("newmtl a\nKd 1 1 1\nNs 1e39\n", 3, "`1e39` is not a finite number"),
        ("newmtl a\nd -halo 0.5\n", 2, "`d` takes one number"),
        ("newmtl a\nTf 1 nan 1\n", 2, "not a finite number"),
    ] {
        write(dir.path(), "m.mtl", mtl);
        let e = load(&write(dir.path(), "m.obj", obj)).unwrap_err().to_string();
        assert!(e.contains(&format!("m.mtl:{line}: malformed MTL: ")) && e.contains(needle), "{mtl:?}: {e}");
    }
    std::fs::write(dir.path().join("m.mtl"), b"newmtl a\nKd 1 1 1\n\xfe\n").unwrap();
    let e = load(&write(dir.path(), "m.obj", obj)).unwrap_err().to_string();
    assert!(e.contains("m.mtl:3:1: not a text file"), "{e}");
}

#[test]
fn nothing_to_render_names_the_end_of_the_file() {
    let dir = tempfile::tempdir().unwrap();
    let e = load(&write(dir.path(), "flat.obj", "v 0 0 0\nv 1 1 1\nv 2 2 2\nf 1 2 3\n")).unwrap_err().to_string();
    assert!(e.contains("flat.obj:4: ") && e.contains("no faces"), "{e}");
    let e = load(&write(dir.path(), "empty.obj", "")).unwrap_err().to_string();
    assert!(e.contains("empty.obj:1: ") && e.contains("no faces"), "{e}");
}

#[test]
fn huge_and_tiny_normals_normalise() {
    let dir = tempfile::tempdir().unwrap();
    let obj = "v 0 0 0\nv 1 0 0\nv 0 1 0\nvn 0 0 3e38\nvn 0 0 1e-30\nvn 0 0 0\nf 1//1 2//2 3//1\nf 1//1 2//3 3//1\n";
    let s = load(&write(dir.path(), "n.obj", obj)).unwrap();
    let tris = triangles(&s);
    assert!(matches!(tris[0], Shape::Triangle { normals: Some(n), .. } if *n == [Vec3::Z; 3]), "{tris:?}");
    assert!(matches!(tris[1], Shape::Triangle { normals: None, .. }), "a zero normal shades flat: {tris:?}");
    assert_eq!(s.warnings.len(), 1, "{:?}", s.warnings);
}

#[test]
fn degenerate_faces_are_skipped_with_a_warning() {
    let dir = tempfile::tempdir().unwrap();
    let scene = load(&write(dir.path(), "d.obj", "v 0 0 0\nv 1 0 0\nv 2 0 0\nv 0 1 0\nf 1 2 3\nf 1 2 4\n")).unwrap();
    assert_eq!(triangles(&scene).len(), 1);
    assert_eq!(scene.warnings.len(), 1, "{:?}", scene.warnings);
    assert!(scene.warnings[0].to_string().contains("d.obj:5: degenerate triangle"), "{:?}", scene.warnings);
}
