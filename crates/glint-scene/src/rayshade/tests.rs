//! The Rayshade reader: each keyword's meaning and defaults, its errors and
//! warnings, and SPD's `.ray` files against their NFF twins.

use super::*;
use crate::nff::{NffAngle, NffOptions};
use crate::{Attenuation, LightKind, Projection, RenderSettings, Scene, ShadowMode, Shape};

fn parse_str(text: &str) -> Result<Scene, LoadError> {
    parse(text, Path::new("t.ray"))
}

fn error(text: &str) -> String {
    parse_str(text).unwrap_err().to_string()
}

fn warnings(s: &Scene) -> Vec<String> {
    s.warnings.iter().map(ToString::to_string).collect()
}

fn fov_of(s: &Scene) -> f32 {
    match s.camera.projection {
        Projection::Perspective { fov_y_degrees } => fov_y_degrees,
        p => panic!("{p:?}"),
    }
}

#[test]
fn an_empty_file_has_rayshades_defaults() {
    let s = parse_str("").unwrap();
    assert_eq!((s.width, s.height), (512, 512));
    assert_eq!((s.camera.eye, s.camera.look_at, s.camera.up), (Vec3::new(0.0, -10.0, 0.0), Vec3::ZERO, Vec3::Z));
    assert_eq!(fov_of(&s), 45.0);
    assert_eq!(s.background, Vec3::ZERO);
    assert_eq!(s.ambient, Vec3::ONE, "the ambient light is white, intensity 1");
    // No light defined: a directional light of intensity 1 from (1, -1, 1).
    assert_eq!(s.lights.len(), 1);
    let LightKind::Directional { direction } = s.lights[0].kind else { panic!("{:?}", s.lights[0]) };
    assert!((direction - Vec3::new(-1.0, 1.0, -1.0).normalize()).length() < 1e-6);
    assert_eq!(s.lights[0].radiance(), Vec3::ONE);
    // maxdepth 5 counts the eye ray as 0; Glint counts it as 1.
    let render = RenderSettings { max_depth: 6, cutoff: 0.002, shadow_mode: ShadowMode::Tinted, ..RenderSettings::default() };
    assert_eq!(s.render, render);
    assert!(s.objects.is_empty() && s.warnings.is_empty());
}

#[test]
fn camera_screen_and_options() {
    let s = parse_str("eyep 1 2 3\nlookp 0 1 0 up 0 1 0\nfov 30 30\nscreen 64 64\nbackground 0.1 0.2 0.3\nsample 1 nojitter\nmaxdepth 2\ncutoff 0.01\n").unwrap();
    assert_eq!((s.camera.eye, s.camera.look_at, s.camera.up), (Vec3::new(1.0, 2.0, 3.0), Vec3::Y, Vec3::Y));
    assert_eq!(fov_of(&s), 30.0, "fov is edge to edge, as Glint's");
    assert_eq!((s.width, s.height, s.background), (64, 64, Vec3::new(0.1, 0.2, 0.3)));
    assert_eq!((s.render.max_depth, s.render.cutoff), (3, 0.01));
    assert!(s.warnings.is_empty(), "{:?}", warnings(&s));
}

#[test]
fn fov_keeps_the_vertical_angle_and_square_pixels() {
    // Rayshade: V = H·height/width when V is left out.
    let s = parse_str("screen 200 100\nfov 60\n").unwrap();
    assert_eq!(fov_of(&s), 30.0);
    let w = warnings(&s);
    assert_eq!(w.len(), 1, "{w:?}");
    assert!(w[0].starts_with("t.ray:2:1: fov 60 30: Glint's pixels are square") && w[0].contains("spans 56.3"), "{w:?}");
    // A consistent pair is silent: tan(V/2)·2 = tan(H/2).
    let h = 2.0 * ((30f64.to_radians() / 2.0).tan() * 2.0).atan().to_degrees();
    let s = parse_str(&format!("screen 200 100\nfov {h} 30\n")).unwrap();
    assert!(s.warnings.is_empty(), "{:?}", warnings(&s));
    assert_eq!(fov_y(h, Some(30.0), 200, 100).0, 30.0);
}

#[test]
fn lights_point_directional_and_ambient() {
    let s = parse_str("light 0.5 point 1 2 3\nlight 0.2 0.4 0.6 directional 0 0 2\nlight 0.25 ambient\n").unwrap();
    assert_eq!(s.lights.len(), 2);
    assert_eq!(s.lights[0].kind, LightKind::Point { position: Vec3::new(1.0, 2.0, 3.0) });
    assert_eq!(s.lights[0].radiance(), Vec3::splat(0.5), "`light I` is the light's whole intensity");
    assert_eq!(s.lights[0].attenuation, Attenuation::None, "Rayshade's lights do not fall off");
    // The vector points towards the light; Glint's direction is the way light travels.
    assert_eq!(s.lights[1].kind, LightKind::Directional { direction: -Vec3::Z });
    assert_eq!(s.lights[1].radiance(), Vec3::new(0.2, 0.4, 0.6));
    assert_eq!(s.ambient, Vec3::splat(0.25));
}

#[test]
fn surfaces_map_to_glint_materials_exactly() {
    let s = parse_str(
        "surface a\n    ambient 0.2 0.15 0.066\n    diffuse 0.8 0.6 0.264\n\
         surface b ambient 0 0 0 diffuse 0.5 0.45 0.35 specular 0.5 0.4 0.3 specpow 3.0827 reflect 0.5\n\
         surface c diffuse 0.2 0.1 0.1 transp 0.8 index 1.1 body 1 0.5 0.25\n\
         surface d ambient 0.3 0.2 0.1\n",
    )
    .unwrap();
    assert!(s.warnings.is_empty(), "{:?}", warnings(&s));
    let [a, b, c, d] = &s.materials[..] else { panic!("{:?}", s.materials) };
    // ambient = k_a·O_d with O_d = diffuse and k_d = 1.
    assert_eq!((a.color, a.diffuse), (Vec3::new(0.8, 0.6, 0.264), 1.0));
    assert!((a.ambient - 0.25).abs() < 1e-6, "{}", a.ambient);
    assert_eq!((a.specular, a.reflect, a.transmit), (0.0, Vec3::ZERO, Vec3::ZERO));
    // Highlights: k_s·O_s = specular, Phong (R·L), n = specpow; the mirror is reflect·specular.
    assert_eq!((b.ambient, b.specular, b.specular_color, b.shininess), (0.0, 1.0, Some(Vec3::new(0.5, 0.4, 0.3)), 3.0827));
    assert_eq!(b.specular_model, SpecularModel::Phong);
    assert_eq!(b.reflect, Vec3::new(0.25, 0.2, 0.15));
    assert!(!b.fresnel);
    // Transmission is transp·body; no Fresnel term.
    assert_eq!((c.transmit, c.ior, c.fresnel), (Vec3::new(0.8, 0.4, 0.2), 1.1, false));
    assert_eq!(c.specular, 0.0, "specular defaults to black: no highlight");
    // No diffuse colour: the ambient colour is O_d.
    assert_eq!((d.color, d.ambient, d.diffuse), (Vec3::new(0.3, 0.2, 0.1), 1.0, 0.0));
}

#[test]
fn a_zero_specpow_turns_highlights_off_but_keeps_the_mirror() {
    // What SPD writes for a mirror without highlights.
    let s = parse_str("surface m diffuse 1 1 1 specular 1.0 1.0 1.0 specpow 0.0 reflect 0.5\n").unwrap();
    let m = &s.materials[0];
    assert_eq!((m.specular, m.specular_color, m.reflect), (0.0, None, Vec3::splat(0.5)));
    // Rayshade's default exponent is 15.
    let s = parse_str("surface m specular 1 1 1\n").unwrap();
    assert_eq!((s.materials[0].specular, s.materials[0].shininess), (1.0, 15.0));
}

#[test]
fn an_ambient_colour_off_the_diffuse_hue_warns() {
    let s = parse_str("surface odd\n  ambient 0.1 0.2 0.3\n  diffuse 1 0 0\n").unwrap();
    let w = warnings(&s);
    assert_eq!(w.len(), 1);
    assert!(w[0].starts_with("t.ray:1:9: surface odd: its ambient colour is not a multiple of its diffuse colour"), "{w:?}");
    assert!((s.materials[0].ambient - 0.1).abs() < 1e-6);
}

#[test]
fn primitives() {
    let s = parse_str(
        "surface s diffuse 1 1 1\n\
         sphere s 0.5 1 2 3\n\
         cone s 1 0 0 0 0.5 0 0 2\n\
         cylinder s 0.25 0 0 0 1 0 0\n\
         polygon s\n0 0 0 1 0 0 1 1 0\n0 1 0\n\
         triangle s 0 0 0 1 0 0 0 1 0\n\
         triangle s 0 0 0 0 0 2  1 0 0 0 0 1  0 1 0 0 0 1\n\
         plane s 0 0 -1 0 0 3\n",
    )
    .unwrap();
    let shapes: Vec<&Shape> = s.objects.iter().map(|o| &o.shapes[0]).collect();
    assert_eq!(shapes.len(), 7);
    assert_eq!(*shapes[0], Shape::sphere(Vec3::new(1.0, 2.0, 3.0), 0.5).unwrap(), "radius first, then centre");
    assert_eq!(*shapes[1], Shape::cone(Vec3::ZERO, 1.0, Vec3::new(0.0, 0.0, 2.0), 0.5).unwrap());
    assert_eq!(*shapes[2], Shape::cone(Vec3::ZERO, 0.25, Vec3::X, 0.25).unwrap());
    let square = vec![Vec3::ZERO, Vec3::X, Vec3::new(1.0, 1.0, 0.0), Vec3::Y];
    assert_eq!(*shapes[3], Shape::polygon(square).unwrap().0);
    assert_eq!(*shapes[4], Shape::triangle([Vec3::ZERO, Vec3::X, Vec3::Y], None).unwrap());
    assert_eq!(*shapes[5], Shape::triangle([Vec3::ZERO, Vec3::X, Vec3::Y], Some([Vec3::Z; 3])).unwrap(), "normals made unit");
    assert_eq!(*shapes[6], Shape::plane(-Vec3::Z, Vec3::Z).unwrap(), "the normal made unit");
    assert!(s.objects.iter().all(|o| o.material == 0));
}

#[test]
fn comments_are_skipped_and_lines_still_count() {
    let s = parse_str("/* a\n comment */ surface s // another\n diffuse 1 1 1\nsphere s 1 0 0 0 /* inline */\n").unwrap();
    assert_eq!(s.objects.len(), 1);
    assert_eq!(error("/* two\nlines */\nsphere s 1 0 0 0\n"), "t.ray:3:8: undefined surface `s`");
    assert_eq!(error("sphere /* never closed\n"), "t.ray:1:8: a `/*` comment is never closed");
}

#[test]
fn degenerate_primitives_warn_and_are_skipped() {
    let s = parse_str("surface s diffuse 1 1 1\nsphere s 0 0 0 0\npolygon s 0 0 0 1 0 0 2 0 0\ntriangle s 0 0 0 0 0 0 1 0 0 0 0 1 0 1 0 0 0 1\n").unwrap();
    let w = warnings(&s);
    assert_eq!(s.objects.len(), 1, "{w:?}");
    assert!(w[0].starts_with("t.ray:2:1:") && w[1].starts_with("t.ray:3:1:"), "{w:?}");
    assert_eq!(w[2], "t.ray:4:1: triangle has a zero-length vertex normal; shaded flat");
}

#[test]
fn errors_name_the_place_and_the_problem() {
    let cases = [
        ("bogus 1 2 3\n", "t.ray:1:1: unknown keyword `bogus`"),
        ("eyep 0 zero 5\n", "t.ray:1:8: expected a number (eyep y) for `eyep` (line 1), found `zero`"),
        ("surface s diffuse 1 1 1\nsphere s 1 0 0\n", "t.ray:2:1: unexpected end of file: `sphere` (line 2) needs centre z"),
        ("surface s diffuse 1 1 1\nsphere s 1 0 0 0 7\n", "t.ray:2:18: unexpected number `7`: too many values for `sphere` (line 2)"),
        ("sphere 1 0 0 0\n", "t.ray:1:1: `sphere` names no surface: Glint needs a surface defined with `surface NAME`"),
        ("surface s\nsurface s\n", "t.ray:2:9: surface `s` is defined twice"),
        ("surface s diffuse 1 1 1\nsphere s 1 0 0 0 translate 1 0 0\n", "t.ray:2:18: Glint does not read Rayshade's `translate`"),
        ("surface s\npolygon s 0 0 0 1 0 0\n", "t.ray:2:1: polygon needs at least three vertices, found 2"),
        ("surface s\npolygon s 0 0 0 1 0 0 1\n", "t.ray:2:1: `polygon` has 7 numbers, not whole x y z triples"),
        ("surface s\ntriangle s 0 0 0 1 0 0 0 1 0 0 0 1\n", "t.ray:2:1: triangle needs three vertices, or three vertices each with a normal, found 4 points"),
        ("light 1 spot 0 0 0 0 0 1 30\n", "t.ray:1:9: Glint does not read Rayshade's spot lights (only point, directional and ambient)"),
        ("light 1 1 point 0 0 0\n", "t.ray:1:7: light: the intensity is one number or three (r g b), found 2"),
        ("screen 0 0\n", "t.ray:1:8: screen width: `0` is not a whole number in 1..=16384"),
        ("fov 0\n", "t.ray:1:1: fov: the field of view must be between 0 and 180 degrees, found 0 (horizontal) and 0 (vertical)"),
        ("eyep 0 0 5\nlookp 0 0 0\nup 0 0 1\n", "t.ray:3:1: `up` is parallel to the view direction (or `eyep` equals `lookp`)"),
        ("surface s diffuse 1 1 1\nsphere s (1/2) 0 0 0\n", "t.ray:2:10: radius: Glint does not evaluate Rayshade's expressions in parentheses; write the number"),
        ("surface s transp 0.5 index 0\n", "t.ray:1:28: index must be positive, found 0"),
        ("surface s translu 1 1 1 1 2\n", "t.ray:1:11: Glint does not read Rayshade's `translu` (diffuse transmission)"),
        ("maxdepth 16\n", "t.ray:1:10: maxdepth: `16` is not a whole number in 0..=15"),
        ("screen 1 16\n", "t.ray:1:1: fov: the field of view must be between 0 and 180 degrees, found 45 (horizontal) and 720 (vertical)"),
        ("surface s\nplane s 0 0 0 0 0 0\n", "t.ray:2:1: plane: the normal is a zero vector"),
    ];
    for (text, want) in cases {
        assert_eq!(error(text), want, "{text}");
    }
}

#[test]
fn terms_glint_cannot_express_warn() {
    let s = parse_str("light 1 point 0 0 9 noshadow\nsurface s diffuse 1 1 1 noshadow extinct 0.5\nsample 3 jitter\n").unwrap();
    let w = warnings(&s);
    assert_eq!(w.len(), 4, "{w:?}");
    assert!(w[0].starts_with("t.ray:1:21: noshadow"), "{w:?}");
    assert!(w[1].starts_with("t.ray:2:25: noshadow") && w[2].starts_with("t.ray:2:34: extinct"), "{w:?}");
    assert!(w[3].starts_with("t.ray:3:1: sample 3: Glint traces one sample per pixel"), "{w:?}");
}

/// SPD's `.ray` output of each classic database at sizes 1 to 3 loads into
/// the scene of its NFF twin read edge to edge (Rayshade's `fov` spans the
/// image edges): the same image, camera, lights and shapes, in the same order.
#[test]
fn spd_rayshade_scenes_have_the_shapes_of_their_nff_twins() {
    for name in crate::spd::CLASSIC {
        let db = crate::spd::database(name).unwrap();
        for size in 1..=3 {
            let what = format!("{name} size {size}");
            let ray = parse(&db.generate_as(Some(size), crate::spd::Format::Rayshade).unwrap(), Path::new("spd.ray")).unwrap();
            let options = NffOptions { angle: NffAngle::Edges };
            let nff = crate::nff::parse(&db.generate(Some(size)).unwrap(), Path::new("spd.nff"), &options).unwrap();
            assert_same_geometry(&ray, &nff, &what);
        }
    }
}

fn assert_same_geometry(ray: &Scene, nff: &Scene, what: &str) {
    assert_eq!((ray.width, ray.height, ray.background, &ray.camera), (nff.width, nff.height, nff.background, &nff.camera), "{what}");
    let positions = |s: &Scene| s.lights.iter().map(|l| l.kind).collect::<Vec<_>>();
    assert_eq!(positions(ray), positions(nff), "{what}");
    assert_eq!(ray.objects.len(), nff.objects.len(), "{what}");
    for (i, (r, n)) in ray.objects.iter().zip(&nff.objects).enumerate() {
        assert_eq!(r.shapes, n.shapes, "{what}: object {i}");
    }
    assert_eq!(ray.warnings.len(), nff.warnings.len(), "{what}: {:?}", ray.warnings);
}

/// Every file in `$GLINT_SPD_RAYSHADE_DIR` (SPD 3.14's own `-r 8` output)
/// loads, with the geometry of its twin in `$GLINT_SPD_DIR` where that exists.
#[test]
fn every_reference_rayshade_file_loads_like_its_nff_twin() {
    let Some(dir) = std::env::var_os("GLINT_SPD_RAYSHADE_DIR") else {
        eprintln!("skipped: GLINT_SPD_RAYSHADE_DIR is not set (SPD 3.14's .ray files exist only in Glint's CI)");
        return;
    };
    let nff_dir = std::env::var_os("GLINT_SPD_DIR").map(std::path::PathBuf::from);
    let mut loaded = 0;
    for entry in std::fs::read_dir(&dir).unwrap() {
        let path = entry.unwrap().path();
        if path.extension().is_none_or(|e| e != "ray") {
            continue;
        }
        let ray = crate::load(&path).unwrap_or_else(|e| panic!("{e}"));
        let twin = nff_dir.as_ref().map(|d| d.join(path.with_extension("nff").file_name().unwrap()));
        if let Some(twin) = twin.filter(|t| t.exists()) {
            let nff = crate::load_with(&twin, &crate::LoadOptions { nff_angle: NffAngle::Edges }).unwrap();
            assert_same_geometry(&ray, &nff, &path.display().to_string());
        }
        loaded += 1;
    }
    assert_eq!(loaded, 28, "SPD's 28 .ray files");
}

/// docs/scene-format.md's example with every keyword loads without a warning.
#[test]
fn the_documented_example_loads() {
    let page = std::fs::read_to_string(Path::new(env!("CARGO_MANIFEST_DIR")).join("../../docs/scene-format.md")).unwrap();
    let start = page.find("```ray\n").expect("a ```ray block") + "```ray\n".len();
    let example = &page[start..start + page[start..].find("```").unwrap()];
    let s = parse(example, Path::new("example.ray")).unwrap_or_else(|e| panic!("{e}"));
    assert!(s.warnings.is_empty(), "{:?}", warnings(&s));
    assert_eq!((s.objects.len(), s.lights.len(), s.materials.len(), s.width), (7, 2, 3, 320));
    assert_eq!(s.ambient, Vec3::splat(0.2));
}
