//! `glint bench` reports the Whitted frame's rays by kind: here the counts of
//! tiny scenes are checked against what each scene implies. Rates are
//! reported too, but no time is asserted.

use std::path::Path;
use std::process::Command;

const SIDE: u64 = 32;

/// A sphere that covers part of the image, seen from the first of two point
/// lights; the second is behind it, facing none of what the camera sees (the
/// sphere's points that face it are those below z = -0.2, the visible ones
/// are above z = 0.2).
fn scene(dir: &Path, name: &str, material: &str) -> String {
    let text = format!(
        "[image]\nwidth = {SIDE}\nheight = {SIDE}\n\
         [camera]\neye = [0, 0, 5]\nlook_at = [0, 0, 0]\nfov = 30\n\
         [[light]]\ntype = \"point\"\nposition = [0, 0, 5]\n\
         [[light]]\ntype = \"point\"\nposition = [0, 0, -5]\n\
         [material.m]\ncolor = [0.8, 0.7, 0.6]\nkd = 0.8\n{material}\n\
         [[object]]\ntype = \"sphere\"\ncenter = [0, 0, 0]\nradius = 1\nmaterial = \"m\"\n"
    );
    let path = dir.join(format!("{name}.toml"));
    std::fs::write(&path, text).unwrap();
    path.to_str().unwrap().to_string()
}

/// The JSON report's eye rays that hit, and its rays per kind: eye, shadow,
/// reflected, refracted.
fn kinds(scene: &str, extra: &[&str]) -> (u64, [u64; 4]) {
    let side = SIDE.to_string();
    let args = ["bench", scene, "--width", &side, "--height", &side, "--frames", "1", "--warm-up", "0", "--json"];
    let o = Command::new(env!("CARGO_BIN_EXE_glint")).args(args).args(extra).output().expect("glint runs");
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let report: serde_json::Value = serde_json::from_slice(&o.stdout).expect("--json prints JSON");
    let rays = |kind: &str| {
        let entry = &report["kinds"][kind];
        assert!(entry["mrays_per_s"].as_f64().is_some_and(|r| r >= 0.0), "no rate for {kind}: {report}");
        entry["rays"].as_u64().unwrap_or_else(|| panic!("no {kind} rays: {report}"))
    };
    let eye_hit = report["eye_hit"].as_u64().unwrap();
    assert!(eye_hit > 0 && eye_hit < SIDE * SIDE, "the sphere covers part of the image: {report}");
    let counts = [rays("eye"), rays("shadow"), rays("reflected"), rays("refracted")];
    assert_eq!(counts[0], SIDE * SIDE, "one eye ray a pixel: {report}");
    (eye_hit, counts)
}

#[test]
fn a_matte_sphere_casts_a_shadow_ray_per_hit_towards_the_light_it_faces() {
    let dir = tempfile::tempdir().unwrap();
    let (eye_hit, [_, shadow, reflected, refracted]) = kinds(&scene(dir.path(), "matte", ""), &[]);
    // One towards the light at the eye; none towards the light behind.
    assert_eq!(shadow, eye_hit);
    assert_eq!((reflected, refracted), (0, 0));
}

#[test]
fn a_mirror_sphere_reflects_each_hit_once_and_not_at_depth_one() {
    let dir = tempfile::tempdir().unwrap();
    let mirror = scene(dir.path(), "mirror", "reflect = 0.8");
    // A convex mirror's reflections leave it and hit nothing: one reflected
    // ray per eye hit, and no shadow rays but the eye hits'.
    let (eye_hit, [_, shadow, reflected, refracted]) = kinds(&mirror, &[]);
    assert_eq!((shadow, reflected, refracted), (eye_hit, eye_hit, 0));
    let (eye_hit, [_, shadow, reflected, refracted]) = kinds(&mirror, &["--max-depth", "1"]);
    assert_eq!((shadow, reflected, refracted), (eye_hit, 0, 0));
}

#[test]
fn a_glass_sphere_refracts_in_and_out_and_not_at_depth_one() {
    let dir = tempfile::tempdir().unwrap();
    let glass = scene(dir.path(), "glass", "transmit = 0.9\nior = 1.5");
    // Each eye hit refracts into the sphere, and out again where the ray
    // leaves it: a sphere reflects nothing totally inside, and the glass has
    // no mirror term.
    let (eye_hit, [_, _, reflected, refracted]) = kinds(&glass, &[]);
    assert_eq!((reflected, refracted), (0, 2 * eye_hit));
    let (eye_hit, [_, shadow, reflected, refracted]) = kinds(&glass, &["--max-depth", "1"]);
    assert_eq!((shadow, reflected, refracted), (eye_hit, 0, 0));
}

/// The table says how a kind's rate is taken, since no kind is timed alone.
#[test]
fn the_table_reports_each_kind_and_how_its_rate_is_taken() {
    let dir = tempfile::tempdir().unwrap();
    let matte = scene(dir.path(), "matte", "");
    let side = SIDE.to_string();
    let args = ["bench", &matte, "--width", &side, "--height", &side, "--frames", "1", "--warm-up", "0"];
    let o = Command::new(env!("CARGO_BIN_EXE_glint")).args(args).output().expect("glint runs");
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let stdout = String::from_utf8(o.stdout).unwrap();
    assert!(stdout.contains("that kind's rays / the whole frame's time"), "{stdout}");
    for kind in ["eye rays", "shadow rays", "reflected rays", "refracted rays"] {
        assert!(stdout.contains(kind), "{kind} missing in:\n{stdout}");
    }
    let row = stdout.lines().rfind(|l| l.starts_with("matte")).unwrap();
    let fields: Vec<&str> = row.split_whitespace().collect();
    assert_eq!(fields[3], (SIDE * SIDE).to_string(), "the eye rays in {row}");
}
