//! The NFF reader: every statement, its errors and warnings, and the SPD databases.

use super::*;
use crate::{Attenuation, LightKind, Projection, Shape};
use std::fmt::Write as _;

const VIEW: &str = "v\nfrom 0 0 5\nat 0 0 0\nup 0 1 0\nangle 45\nhither 0.1\nresolution 64 48\n";

fn parse_str(body: &str) -> Result<Scene, LoadError> {
    parse(&format!("{VIEW}{body}"), Path::new("t.nff"), &NffOptions::default())
}

fn error(body: &str) -> String {
    parse_str(body).unwrap_err().to_string()
}

/// The first shape of the only object.
fn only_shape(s: &Scene) -> &Shape {
    assert_eq!(s.objects.len(), 1);
    &s.objects[0].shapes[0]
}

#[test]
fn view_block() {
    let s = parse_str("").unwrap();
    assert_eq!((s.width, s.height), (64, 48));
    assert_eq!(s.camera.eye, Vec3::new(0.0, 0.0, 5.0));
    assert_eq!(s.camera.up, Vec3::Y);
    assert_eq!(s.background, Vec3::ZERO);
    assert_eq!(s.ambient, Vec3::splat(0.5), "no lights: as if there were one");
    assert_eq!(s.render, RenderSettings::default());
    assert!(s.objects.is_empty() && s.lights.is_empty() && s.warnings.is_empty());
}

#[test]
fn an_angle_that_looks_like_radians_warns() {
    let s = parse(&VIEW.replace("angle 45", "angle 0.7"), Path::new("r.nff"), &NffOptions::default()).unwrap();
    let w: Vec<String> = s.warnings.iter().map(ToString::to_string).collect();
    assert_eq!(w, ["r.nff:5:7: angle: 0.7° is a very narrow view; angles are in degrees (0.7 radians is 40.1)"]);
    assert!(parse_str("").unwrap().warnings.is_empty());
}

#[test]
fn angle_conversion_centres_and_edges() {
    // 3 rows, angle 90: the outer row centres are 1 pixel from the middle, the
    // edges 1.5 pixels, so tan(fov/2) = tan(45°) · 3/2 = 1.5 and
    // fov = 2·atan(1.5) = 112.61986494804042°.
    let src = "v from 0 0 5 at 0 0 0 up 0 1 0 angle 90 hither 1 resolution 3 3";
    let fov = |angle| match parse(src, Path::new("a.nff"), &NffOptions { angle }).unwrap().camera.projection {
        Projection::Perspective { fov_y_degrees } => fov_y_degrees,
        p => panic!("{p:?}"),
    };
    assert!((fov(NffAngle::Centers) - 112.619_865).abs() < 1e-4, "{}", fov(NffAngle::Centers));
    assert_eq!(fov(NffAngle::Edges), 90.0);
    // SPD's usual 45° at 512 rows: 2·atan(tan(22.5°)·512/511) = 45.0793…°.
    let f = fov_y_from_angle(45.0, 512, NffAngle::Centers).unwrap();
    assert!((f - 45.079_261_5).abs() < 1e-6, "{f}");
    assert!(fov_y_from_angle(45.0, 1, NffAngle::Centers).is_none());
    let e = parse("v from 0 0 5 at 0 0 0 up 0 1 0 angle 30 resolution 4 1", Path::new("a.nff"), &NffOptions::default())
        .unwrap_err()
        .to_string();
    assert!(e.starts_with("a.nff:1:32:"), "{e}");
}

#[test]
fn background_and_lights() {
    let s = parse_str("b 0.1 0.2 0.3\nl 1 2 3\nl 4 5 6 1 0 0\nl 7 8 9\n").unwrap();
    assert_eq!(s.background, Vec3::new(0.1, 0.2, 0.3));
    assert_eq!(s.lights.len(), 3);
    assert_eq!(s.lights[0].kind, LightKind::Point { position: Vec3::new(1.0, 2.0, 3.0) });
    assert_eq!(s.lights[0].color, Vec3::ONE);
    assert_eq!(s.lights[1].color, Vec3::X);
    assert_eq!(s.lights[2].kind, LightKind::Point { position: Vec3::new(7.0, 8.0, 9.0) });
    // SPD's Readme: √n / (2n) for each light and for the ambient light.
    let readme = 3f32.sqrt() / 6.0;
    assert!((s.ambient - Vec3::splat(readme)).abs().max_element() < 1e-7);
    for l in &s.lights {
        assert!((l.intensity - readme).abs() < 1e-7);
        assert_eq!(l.attenuation, Attenuation::None);
        assert!(l.enabled);
    }
}

#[test]
fn fill_maps_to_phong_mirror_glass() {
    let s = parse_str("f 1 0.5 0.25 0.6 0.3 40 0.2 1.5\ns 0 0 0 1\nf 1 1 1 1 0 0 0 0\ns 0 0 0 1\n").unwrap();
    let m = &s.materials[s.objects[0].material];
    assert_eq!(m.color, Vec3::new(1.0, 0.5, 0.25));
    assert_eq!((m.ambient, m.diffuse, m.specular, m.shininess), (0.6, 0.6, 0.3, 40.0));
    assert_eq!(m.specular_color, None);
    assert_eq!(m.specular_model, SpecularModel::Phong);
    assert_eq!(m.reflect, Vec3::splat(0.3));
    assert_eq!(m.transmit, Vec3::splat(0.2));
    assert_eq!(m.ior, 1.5);
    assert!(m.fresnel, "a transmitter reflects by Fresnel's term");
    let opaque = &s.materials[s.objects[1].material];
    assert!(!opaque.fresnel);
    assert_eq!(opaque.ior, 1.0, "ior 0 on an opaque material reads as 1");
}

#[test]
fn identical_fills_share_a_material() {
    let s = parse_str("f 1 0 0 1 0 0 0 1\ns 0 0 0 1\nf 0 1 0 1 0 0 0 1\ns 0 0 0 1\nf 1 0 0 1 0 0 0 1\ns 0 0 0 1\n").unwrap();
    assert_eq!(s.materials.len(), 2);
    let ids: Vec<usize> = s.objects.iter().map(|o| o.material).collect();
    assert_eq!(ids, [0, 1, 0]);
}

#[test]
fn primitives_before_any_fill_get_a_default_material() {
    let s = parse_str("s 0 0 0 1\n").unwrap();
    assert_eq!(s.materials.len(), 1);
    assert_eq!(s.objects[0].material, 0);
    assert_eq!(s.materials[0].color, Vec3::ONE);
}

#[test]
fn sphere() {
    let s = parse_str("s 1 2 3 0.5\n").unwrap();
    assert_eq!(only_shape(&s), &Shape::Sphere { center: Vec3::new(1.0, 2.0, 3.0), radius: 0.5 });
}

#[test]
fn cone_on_one_line_or_three_is_the_same() {
    let one = parse_str("c 0 0 0 1 0 2 0 0.5\n").unwrap();
    let three = parse_str("c\n0 0 0 1\n0 2 0 0.5\n").unwrap();
    let cone = Shape::Cone { base: Vec3::ZERO, base_radius: 1.0, apex: Vec3::new(0.0, 2.0, 0.0), apex_radius: 0.5 };
    assert_eq!(only_shape(&one), &cone);
    assert_eq!(one.objects, three.objects);
    // A point at the base is stored with the wide end as the base.
    let flipped = parse_str("c 0 2 0 0 0 0 0 1\n").unwrap();
    assert_eq!(only_shape(&flipped), &Shape::Cone { base: Vec3::ZERO, base_radius: 1.0, apex: Vec3::new(0.0, 2.0, 0.0), apex_radius: 0.0 });
}

#[test]
fn concave_twelve_gon_stays_a_polygon() {
    // A plus sign: 12 vertices, concave at four corners.
    let pts = [(1, 0), (2, 0), (2, 1), (3, 1), (3, 2), (2, 2), (2, 3), (1, 3), (1, 2), (0, 2), (0, 1), (1, 1)];
    let mut src = String::from("p 12\n");
    for (x, y) in pts {
        writeln!(src, "{x} {y} 4").unwrap();
    }
    let s = parse_str(&src).unwrap();
    let Shape::Polygon { vertices } = only_shape(&s) else { panic!() };
    assert_eq!(vertices.len(), 12);
    assert_eq!(vertices[3], Vec3::new(3.0, 1.0, 4.0));
    assert!(s.warnings.is_empty());
}

#[test]
fn patches_are_smooth_triangles_and_fans() {
    let s = parse_str("pp 3\n0 0 0 0 0 2\n1 0 0 0 0 1\n0 1 0 0 1 1\n").unwrap();
    let Shape::Triangle { vertices, normals: Some(n) } = only_shape(&s) else { panic!() };
    assert_eq!(vertices[1], Vec3::X);
    assert_eq!(n[0], Vec3::Z, "normals are normalised");
    assert!((n[2] - Vec3::new(0.0, 1.0, 1.0).normalize()).length() < 1e-7);

    let s = parse_str("pp 5\n0 0 0 0 0 1\n1 0 0 0 0 1\n2 1 0 0 0 1\n1 2 0 0 0 1\n0 1 0 0 0 1\n").unwrap();
    assert_eq!(s.objects.len(), 1);
    assert_eq!(s.objects[0].shapes.len(), 3);
    let Shape::Triangle { vertices, normals: Some(_) } = &s.objects[0].shapes[2] else { panic!() };
    assert_eq!(*vertices, [Vec3::ZERO, Vec3::new(1.0, 2.0, 0.0), Vec3::Y]);
}

#[test]
fn patch_normals_of_any_finite_size_normalise() {
    // In f32, (3e38, 0, 0) has an infinite length and (1e-30, 0, 0) a zero one.
    let s = parse_str("pp 3\n0 0 0 3e38 0 0\n0 0 -7 1e-30 0 0\n0 8 0 0 0 1\n").unwrap();
    let Shape::Triangle { normals: Some(n), .. } = only_shape(&s) else { panic!("{s:?}") };
    assert_eq!(*n, [Vec3::X, Vec3::X, Vec3::Z]);
    assert!(s.warnings.is_empty(), "{:?}", s.warnings);
}

#[test]
fn comments_are_skipped() {
    let s = parse(
        "# a scene\nv # the view\nfrom 0 0 5 at 0 0 0 up 0 1 0 angle 45 resolution 8 8\n# s 0 0 0 1\ns 0 0 0 1 # trailing\n#s 1 1 1 1",
        Path::new("c.nff"),
        &NffOptions::default(),
    )
    .unwrap();
    assert_eq!(s.objects.len(), 1);
}

#[test]
fn degenerate_primitives_warn_and_are_skipped() {
    let s = parse_str("p 3\n0 0 0\n1 0 0\n2 0 0\npp 3\n0 0 0 0 0 1\n0 0 0 0 0 1\n1 1 1 0 0 1\ns 0 0 0 0\nc 0 0 0 1 0 0 0 1\ns 0 0 0 1\n").unwrap();
    assert_eq!(s.objects.len(), 1);
    assert_eq!(s.warnings.len(), 4);
    let w: Vec<String> = s.warnings.iter().map(ToString::to_string).collect();
    assert!(w[0].starts_with("t.nff:8:1:") && w[0].contains("degenerate polygon"), "{w:?}");
    assert!(w[1].starts_with("t.nff:12:1:") && w[1].contains("degenerate patch"), "{w:?}");
    assert!(w[2].starts_with("t.nff:16:") && w[2].contains("radius 0"), "{w:?}");
    assert!(w[3].starts_with("t.nff:17:") && w[3].contains("cone"), "{w:?}");
}

#[test]
fn non_planar_polygon_warns_and_is_kept() {
    let s = parse_str("p 4\n0 0 0\n1 0 0\n1 1 0\n0 1 0.5\n").unwrap();
    assert_eq!(s.objects.len(), 1);
    assert_eq!(s.warnings.len(), 1);
    assert!(s.warnings[0].to_string().contains("not planar"));
}

#[test]
fn malformed_lines_name_file_line_and_problem() {
    // VIEW is 7 lines, so the body starts on line 8.
    for (body, at, needle) in [
        ("s 0 0 0 1\nq 1 2 3\n", "t.nff:9:1:", "unknown keyword `q`"),
        ("s 0 0 0 1 7\n", "t.nff:8:11:", "too many values for `s` (line 8)"),
        ("s 0 0 zero 1\n", "t.nff:8:7:", "found `zero`"),
        ("s 0 0 0\ns 1 1 1 1\n", "t.nff:9:1:", "expected a number (radius)"),
        ("s 0 0 0 -1\n", "t.nff:8:9:", "radius must not be negative"),
        ("c 0 0 0 1 0 1 0 -0.5\n", "t.nff:8:17:", "apex radius must not be negative"),
        ("s 0 nan 0 1\n", "t.nff:8:5:", "not a finite number"),
        ("s 0 inf 0 1\n", "t.nff:8:5:", "not a finite number"),
        ("s 0 1e39 0 1\n", "t.nff:8:5:", "not a finite number"),
        ("p 2\n0 0 0\n1 0 0\n", "t.nff:8:3:", "at least 3"),
        ("p 3.5\n", "t.nff:8:3:", "whole number"),
        ("p 3\n0 0 0\n1 0 0\n", "t.nff:8:1:", "end of file"),
        ("pp 3\n0 0 0 0 0 1\n1 0 0 0 0 1\n0 1 0\n", "t.nff:8:1:", "normal 3"),
        ("f 1 1 1 0.5 0.5 10 0.5 0\n", "t.nff:8:24:", "index of refraction"),
        ("f 1 1 1 0.5 0.5 10 0\n", "t.nff:8:1:", "end of file"),
        ("l 1 2 3 1 1\n", "t.nff:8:1:", "light colour blue"),
        ("b 0.1 -0.2 0.3\n", "t.nff:8:7:", "must not be negative"),
        ("v from 0 0 1 at 0 0 0 up 0 1 0 angle 45 resolution 8 8\n", "t.nff:8:1:", "second `v`"),
    ] {
        let e = error(body);
        assert!(e.starts_with(at), "{body:?}: {e}");
        assert!(e.contains(needle), "{body:?}: {e}");
    }
}

#[test]
fn values_beyond_f32_and_odd_tokens() {
    for (body, at, needle) in [
        ("s 3e38 0 0 3e38\n", "t.nff:8:1:", "beyond the range of 32-bit floats"),
        ("c 3e38 0 0 3e38 3e38 1 0 3e38\n", "t.nff:8:1:", "beyond the range of 32-bit floats"),
        ("\u{1b}[2J 0 0 0 1\n", "t.nff:8:1:", "unknown keyword `\\u{1b}[2J`"),
        ("s 0 0 0 1 2xxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxx\n", "t.nff:8:11:", "xxx…`"),
    ] {
        let e = error(body);
        assert!(e.starts_with(at) && e.contains(needle), "{body:?}: {e}");
        assert_eq!(e.lines().count(), 1, "{e}");
    }
    let e = parse("v from 0 0 3e38 at 0 0 -3e38 up 0 1 0 angle 45 resolution 8 8", Path::new("f.nff"), &NffOptions::default())
        .unwrap_err()
        .to_string();
    assert!(e.starts_with("f.nff:1:1:") && e.contains("too far apart"), "{e}");
}

#[test]
fn bad_view_blocks() {
    let p = |src: &str| parse(src, Path::new("v.nff"), &NffOptions::default()).unwrap_err().to_string();
    let e = p("s 0 0 0 1\n");
    assert!(e.starts_with("v.nff:1: ") && e.contains("`v`"), "{e}");
    let e = p("s 0 0 0 1\n# no view\n\n");
    assert!(e.starts_with("v.nff:3: ") && e.contains("no viewpoint"), "{e}");
    let e = p("");
    assert!(e.starts_with("v.nff:1: ") && e.contains("no viewpoint"), "{e}");
    let e = p("v\nfrom 0 0 5\nat 0 0 0\nangle 45\nresolution 8 8\n");
    assert!(e.starts_with("v.nff:1:1:") && e.contains("no `up`"), "{e}");
    let e = p("v\nfrom 0 0 5\nat 0 0 0\nup 0 0 1\nangle 45\nresolution 8 8\n");
    assert!(e.starts_with("v.nff:1:1:") && e.contains("parallel"), "{e}");
    let e = p("v\nfrom 0 0 5\nat 0 0 0\nup 0 1 0\nangle 180\nresolution 8 8\n");
    assert!(e.starts_with("v.nff:5:7:") && e.contains("angle"), "{e}");
    let e = p("v\nfrom 0 0 5\nat 0 0 0\nup 0 1 0\nangle 45\nresolution 8 0\n");
    assert!(e.starts_with("v.nff:6:14:") && e.contains("height"), "{e}");
    let e = p("v\nfrom 0 0 5\nat 0 0 0\nup 0 1 0\nup 0 1 0\n");
    assert!(e.starts_with("v.nff:5:1:") && e.contains("twice"), "{e}");
}

/// Writes shapes as NFF text, the way the SPD generators do (one material).
fn generate(shapes: &[Shape]) -> String {
    let mut out = String::from("b 0 0 0\nv\nfrom 0 0 10\nat 0 0 0\nup 0 1 0\nangle 40\nhither 1\nresolution 32 32\nl 5 5 5\nf 1 0 0 1 0 0 0 1\n");
    let v3 = |v: Vec3| format!("{} {} {}", v.x, v.y, v.z);
    for shape in shapes {
        match shape {
            Shape::Sphere { center, radius } => writeln!(out, "s {} {radius}", v3(*center)),
            Shape::Cone { base, base_radius, apex, apex_radius } => {
                writeln!(out, "c {} {base_radius} {} {apex_radius}", v3(*base), v3(*apex))
            }
            Shape::Polygon { vertices } => {
                writeln!(out, "p {}", vertices.len()).unwrap();
                vertices.iter().try_for_each(|v| writeln!(out, "{}", v3(*v)))
            }
            Shape::Triangle { vertices, normals } => {
                let normals = normals.expect("generated patches have normals");
                writeln!(out, "pp 3").unwrap();
                (0..3).try_for_each(|i| writeln!(out, "{} {}", v3(vertices[i]), v3(normals[i])))
            }
            other => unreachable!("NFF has no {}", other.name()),
        }
        .unwrap();
    }
    out
}

#[test]
fn generated_files_round_trip() {
    let mut shapes = Vec::new();
    for i in 0..20 {
        let f = i as f32;
        let o = Vec3::new(f * 0.37 - 3.0, (f * 1.3).sin(), f / 7.0);
        shapes.push(Shape::Sphere { center: o, radius: 0.1 + f / 100.0 });
        shapes.push(Shape::Cone { base: o, base_radius: 0.3, apex: o + Vec3::new(0.1, 1.0, f / 3.0), apex_radius: f / 40.0 });
        // At least four vertices: a polygon of three is loaded as a triangle.
        let ring: Vec<Vec3> = (0..(4 + i % 8))
            .map(|k| {
                let a = k as f32 * std::f32::consts::TAU / (4 + i % 8) as f32;
                let r = if k % 2 == 1 { 0.5 } else { 1.0 };
                o + Vec3::new(r * a.cos(), r * a.sin(), 0.0)
            })
            .collect();
        shapes.push(Shape::Polygon { vertices: ring });
        let n = [Vec3::Z, Vec3::new(0.6, 0.0, 0.8), Vec3::new(0.0, 0.6, 0.8)];
        shapes.push(Shape::Triangle { vertices: [o, o + Vec3::X, o + Vec3::Y * 1.5], normals: Some(n) });
    }
    let text = generate(&shapes);
    let scene = parse(&text, Path::new("gen.nff"), &NffOptions::default()).unwrap();
    assert!(scene.warnings.is_empty(), "{:?}", scene.warnings);
    assert_eq!(scene.objects.len(), shapes.len());
    for (object, expected) in scene.objects.iter().zip(&shapes) {
        assert_eq!(object.shapes.len(), 1);
        match (&object.shapes[0], expected) {
            (Shape::Triangle { vertices: a, normals: Some(na) }, Shape::Triangle { vertices: b, normals: Some(nb) }) => {
                assert_eq!(a, b);
                for (x, y) in na.iter().zip(nb) {
                    assert!((*x - *y).length() < 1e-6);
                }
            }
            (got, want) => assert_eq!(got, want),
        }
    }
    assert_eq!(scene.lights.len(), 1);
    assert_eq!(scene.lights[0].intensity, 0.5);
}

/// A Standard Procedural Database scene, generated.
fn spd(spec: &str) -> Scene {
    crate::load(Path::new(&format!("spd:{spec}"))).unwrap_or_else(|e| panic!("{e}"))
}

#[derive(Debug, Default, PartialEq)]
struct Counts {
    spheres: usize,
    cones: usize,
    polygons: usize,
    triangles: usize,
    lights: usize,
    warnings: usize,
}

fn counts(s: &Scene) -> Counts {
    let mut c = Counts { lights: s.lights.len(), warnings: s.warnings.len(), ..Counts::default() };
    for shape in s.objects.iter().flat_map(|o| &o.shapes) {
        match shape {
            Shape::Sphere { .. } => c.spheres += 1,
            Shape::Cone { .. } => c.cones += 1,
            Shape::Polygon { .. } => c.polygons += 1,
            Shape::Triangle { .. } => c.triangles += 1,
            other => unreachable!("NFF has no {}", other.name()),
        }
    }
    c
}

#[test]
fn every_spd_database_loads() {
    let c = |spheres, cones, polygons, triangles, lights, warnings| Counts { spheres, cones, polygons, triangles, lights, warnings };
    let expected: Vec<(&str, Counts)> = vec![
        ("balls:1", c(10, 0, 1, 0, 3, 0)),
        ("balls:4", c(7381, 0, 1, 0, 3, 0)),
        ("gears:1", c(0, 0, 147, 0, 5, 0)),
        ("gears:4", c(0, 0, 9345, 0, 5, 0)),
        ("mount:1", c(4, 0, 0, 8, 1, 0)),
        ("mount:6", c(4, 0, 0, 8192, 1, 0)),
        ("rings:1", c(30, 30, 1, 0, 3, 0)),
        ("rings:7", c(4200, 4200, 1, 0, 3, 0)),
        // Two degenerate patches, each written as two triangles: 4 warnings.
        ("teapot:1", c(0, 0, 1, 52, 2, 4)),
        ("teapot:6", c(0, 0, 36, 2256, 2, 0)),
        ("tetra:1", c(0, 0, 0, 4, 1, 0)),
        ("tetra:6", c(0, 0, 0, 4096, 1, 0)),
        ("tree:1", c(3, 3, 1, 0, 7, 0)),
        ("tree:11", c(4095, 4095, 1, 0, 7, 0)),
        ("jacks:3", c(438, 219, 0, 0, 1, 0)),
        ("shells:5", c(5761, 0, 0, 0, 1, 0)),
        ("lattice:12", c(2197, 6084, 0, 0, 6, 0)),
        ("sombrero:2", c(0, 0, 0, 7938, 1, 0)),
        ("nurbtst:1", c(0, 0, 0, 1500, 1, 0)),
    ]
    .into_iter()
    .collect();
    for (spec, want) in &expected {
        let scene = spd(spec);
        if *spec != "teapot:1" {
            assert!(scene.warnings.is_empty(), "{spec}: {:?}", scene.warnings);
        }
        assert_eq!(&counts(&scene), want, "{spec}");
    }
    for database in crate::spd::DATABASES {
        for size in 1..=database.max_size.min(2) {
            assert!(spd(&format!("{}:{size}", database.name)).primitive_count() > 0, "{} size {size}", database.name);
        }
    }
}

#[test]
fn spd_details() {
    let teapot = spd("teapot:1");
    for w in &teapot.warnings {
        assert!(w.to_string().contains("spd:teapot:1:") && w.to_string().contains("degenerate patch"), "{w}");
    }
    let jacks = spd("jacks:1");
    assert_eq!((jacks.width, jacks.height), (256, 256));
    let Projection::Perspective { fov_y_degrees } = jacks.camera.projection else { panic!() };
    let want = fov_y_from_angle(25.0, 256, NffAngle::Centers).unwrap() as f32;
    assert_eq!(fov_y_degrees, want);
    assert!(fov_y_degrees > 25.0 && fov_y_degrees < 25.2);
    assert_eq!(jacks.background, Vec3::new(0.2, 0.05, 0.2));

    let lattice = spd("lattice:12");
    assert_eq!(lattice.materials.len(), 4, "8281 `f` lines, 4 distinct");

    let mount = spd("mount:1");
    let glass = &mount.materials[mount.objects[0].material];
    assert_eq!((glass.transmit, glass.ior), (Vec3::splat(0.9), 1.5));

    let gears = spd("gears:1");
    let big = gears.objects.iter().flat_map(|o| &o.shapes).filter(|s| matches!(s, Shape::Polygon { vertices } if vertices.len() == 144));
    assert!(big.count() > 0);

    // The crate's entry points pick this reader by extension and pass the angle option.
    let balls = spd("balls:1");
    let edges = crate::load_with(Path::new("spd:balls:1"), &crate::LoadOptions { nff_angle: NffAngle::Edges }).unwrap();
    assert_eq!(edges.camera.projection, Projection::Perspective { fov_y_degrees: 45.0 });
    assert_ne!(balls.camera.projection, edges.camera.projection);
    assert_eq!(balls.objects, edges.objects);
    let e = crate::load(Path::new("README.md")).unwrap_err().to_string();
    assert!(e.contains("README.md: unknown scene format"), "{e}");
    for (spec, problem) in [("spd:teapots", "no SPD database named `teapots`"), ("spd:balls:0", "no size `0`"), ("spd:balls:x", "no size `x`")] {
        let e = crate::load(Path::new(spec)).unwrap_err().to_string();
        assert!(e.starts_with(&format!("{spec}: ")) && e.contains(problem), "{e}");
    }

    let tree = spd("tree:1");
    assert!(tree.objects.iter().flat_map(|o| &o.shapes).any(|s| matches!(s, Shape::Cone { base_radius, apex_radius, .. } if base_radius != apex_radius)));
}
