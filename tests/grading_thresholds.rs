//! The example thresholds and bands docs/golden-ci.md gives a course, held
//! against what they must tell apart (decision record 055). Glint's render is
//! the reference, as when grading; the independent CPU tracer
//! (glint-reference, f64, written from the equations) plays the students: a
//! correct one, one whose camera is shifted by half a pixel (samples at pixel
//! corners), and ones with a wrong highlight model, no shadows or no
//! reflections. Every metric is computed here, none is written down.

mod support;

use std::io::Write;
use std::path::Path;

use glint_golden::{judge, measure, Criteria, GradedCase, LinearImage, Suite, Verdict};
use glint_gpu::{Format, RenderOptions};
use glint_reference::{RayStats, Tracer};
use glint_scene::{Scene, SpecularModel};

/// Scenes a course might give, at their own sizes; the last is the
/// documented case's.
const SCENES: [&str; 3] = ["scenes/gallery/shadows.toml", "scenes/gallery/mirror.toml", "spd:balls:1"];

/// The documented course manifest's first graded case: its criteria and bands.
fn documented_case() -> GradedCase {
    let doc = include_str!("../docs/golden-ci.md");
    let section = &doc[doc.find("## Autograding").expect("the autograding section")..];
    let start = section.find("```toml\n").expect("its manifest") + 8;
    let text = &section[start..start + section[start..].find("```").unwrap()];
    let dir = tempfile::tempdir().unwrap();
    let manifest = dir.path().join("course.toml");
    std::fs::write(&manifest, text).unwrap();
    let suite = Suite::from_manifest(&manifest).unwrap_or_else(|e| panic!("{e}"));
    suite.graded[0].clone()
}

fn load(name: &str) -> Scene {
    let path = if name.starts_with("spd:") { Path::new(name).to_path_buf() } else { Path::new(env!("CARGO_MANIFEST_DIR")).join(name) };
    glint_scene::load(&path).unwrap_or_else(|e| panic!("{e}"))
}

/// The CPU tracer's image of `scene`, one ray per pixel at (i + offset, j +
/// offset), as an 8-bit PNG of it reads back.
fn student(scene: &Scene, offset: f64) -> LinearImage {
    let (w, h) = (scene.width, scene.height);
    let tracer = Tracer::new(scene);
    let mut stats = RayStats::default();
    let samples: Vec<[f32; 4]> = (0..h)
        .flat_map(|j| (0..w).map(move |i| (i, j)))
        .map(|(i, j)| {
            let ray = scene.camera.ray(w, h, f64::from(i) + offset, f64::from(j) + offset).expect("a camera with a basis");
            let [r, g, b] = tracer.trace(ray.origin, ray.direction, &mut stats);
            [r as f32, g as f32, b as f32, 1.0]
        })
        .collect();
    LinearImage::from_render(&glint_gpu::display::resolve(&samples, w, h, &RenderOptions::default()), Format::Png)
}

/// The students, each a way to change the scene and where the samples are.
fn students() -> [(&'static str, fn(&mut Scene), f64); 5] {
    fn right(_: &mut Scene) {}
    fn other_highlights(scene: &mut Scene) {
        for m in &mut scene.materials {
            m.specular_model = match m.specular_model {
                SpecularModel::Phong => SpecularModel::BlinnPhong,
                SpecularModel::BlinnPhong => SpecularModel::Phong,
            };
        }
    }
    fn no_shadows(scene: &mut Scene) {
        scene.render.shadows = false;
    }
    fn no_reflections(scene: &mut Scene) {
        scene.render.reflections = false;
    }
    [
        ("correct", right, 0.5),
        ("half-pixel shift", right, 0.0),
        ("other highlight model", other_highlights, 0.5),
        ("no shadows", no_shadows, 0.5),
        ("no reflections", no_reflections, 0.5),
    ]
}

#[test]
fn the_documented_thresholds_pass_a_correct_tracer_and_fail_a_half_pixel_shift() {
    let case = documented_case();
    let criteria: Criteria = case.criteria;
    let mut table = String::from("scene, student: mean FLIP, pixels above 0.2, points\n");
    let mut wrong = Vec::new();
    let mut balls = Vec::new();
    for name in SCENES {
        let mut scene = load(name);
        if let Some(depth) = case.render.max_depth {
            scene.render.max_depth = depth.0;
        }
        let (glint, _) = support::render(&scene);
        let reference = LinearImage::from_render(&glint, Format::Png);
        for (who, change, offset) in students() {
            let mut changed = scene.clone();
            change(&mut changed);
            let verdict: Verdict = judge(&measure(&reference, &student(&changed, offset)).unwrap(), &criteria);
            let points = case.scoring.award(Some(&verdict)).points;
            table += &format!("{name}, {who}: {:.6}, {:.3}%, {points}\n", verdict.value, 100.0 * verdict.fraction_above());
            if name == "spd:balls:1" {
                balls.push(points);
            }
            if verdict.passed() != (who == "correct") {
                wrong.push(format!("{name}, {who}: {}", verdict.summary()));
            }
        }
    }
    // Written past the test harness's capture: the numbers record 055 gives.
    let _ = writeln!(std::io::stderr(), "{table}");
    assert!(wrong.is_empty(), "judged wrongly:\n{}", wrong.join("\n"));
    // The bands rank the documented case's students: a near miss above a
    // wrong effect, above a missing one, above nothing.
    let [correct, shift, highlights, no_shadows, no_reflections] = balls[..] else { panic!("{balls:?}") };
    assert_eq!(correct, case.scoring.points);
    assert!(correct > shift && shift > highlights && highlights > no_shadows && no_shadows > 0.0, "{balls:?}");
    assert_eq!(no_shadows, no_reflections, "{balls:?}");
}
