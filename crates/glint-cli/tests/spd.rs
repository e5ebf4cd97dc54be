//! `glint spd` and `spd:NAME[:SIZE]` scene arguments, end to end.

use std::process::{Command, Output};

fn glint(args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_glint")).args(args).output().expect("glint runs")
}

fn stderr(o: &Output) -> String {
    String::from_utf8_lossy(&o.stderr).into_owned()
}

#[test]
fn spd_writes_a_database_as_nff() {
    let o = glint(&["spd", "tetra", "--size", "2"]);
    assert!(o.status.success(), "{}", stderr(&o));
    let nff = String::from_utf8(o.stdout).unwrap();
    assert!(nff.starts_with("b ") && nff.contains("\nv\nfrom "), "{nff}");
    assert_eq!(nff.lines().filter(|l| l.starts_with("p ")).count(), 16, "tetra size 2: 4² polygons");

    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("balls.nff");
    let o = glint(&["spd", "balls", "-o", out.to_str().unwrap()]);
    assert!(o.status.success(), "{}", stderr(&o));
    let balls = std::fs::read_to_string(&out).unwrap();
    assert_eq!(balls.lines().filter(|l| l.starts_with("s ")).count(), 7381, "balls at its benchmark size, 4");
}

/// `glint spd NAME -o F.ray` writes SPD's `-r 8` text, which `glint check`
/// and `glint render` read by its extension.
#[test]
fn spd_writes_rayshade_that_check_and_render_read() {
    let dir = tempfile::tempdir().unwrap();
    let scene = dir.path().join("tetra_s3.ray");
    let o = glint(&["spd", "tetra", "--size", "3", "-o", scene.to_str().unwrap()]);
    assert!(o.status.success(), "{}", stderr(&o));
    let text = std::fs::read_to_string(&scene).unwrap();
    assert!(text.starts_with("background 0.078 0.361 0.753\neyep "), "{text}");
    assert_eq!(text.lines().filter(|l| l.starts_with("polygon txt001 ")).count(), 64, "tetra size 3: 4³ polygons");
    let o = glint(&["spd", "tetra", "--size", "3", "--format", "rayshade"]);
    assert_eq!(String::from_utf8(o.stdout).unwrap(), text, "--format rayshade on standard output");

    let o = glint(&["check", scene.to_str().unwrap()]);
    assert!(o.status.success(), "{}", stderr(&o));
    let png = dir.path().join("t.png");
    let o = glint(&["render", scene.to_str().unwrap(), "-o", png.to_str().unwrap(), "--width", "64", "--height", "64", "--quiet"]);
    assert!(o.status.success(), "{}", stderr(&o));
    assert_eq!(image::open(&png).unwrap().to_rgb8().dimensions(), (64, 64));

    let o = glint(&["spd", "jacks", "--format", "rayshade"]);
    assert_eq!(o.status.code(), Some(2), "{}", stderr(&o));
    assert!(stderr(&o).contains("Glint writes SPD jacks as NFF only"), "{}", stderr(&o));
}

#[test]
fn spd_scenes_render_without_any_file() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("tetra.png");
    let o = glint(&["render", "spd:tetra:3", "-o", out.to_str().unwrap(), "--width", "64", "--height", "64", "--stats", "--json", "--quiet"]);
    assert!(o.status.success(), "{}", stderr(&o));
    let stats: serde_json::Value = serde_json::from_str(&String::from_utf8(o.stdout).unwrap()).unwrap();
    assert!(stats["eye_hit"].as_u64().unwrap() > 0);
    assert_eq!(image::open(&out).unwrap().to_rgb8().dimensions(), (64, 64));
}

#[test]
fn a_bad_spd_name_or_size_is_one_line_and_a_usage_error() {
    for (args, needle) in [
        (vec!["render", "spd:teapots", "-o", "x.png"], "no SPD database named `teapots`"),
        (vec!["render", "spd:teapot:0", "-o", "x.png"], "SPD teapot has no size `0`"),
        (vec!["bench", "spd:balls:big"], "SPD balls has no size `big`"),
        (vec!["view", "spd:mount:8"], "SPD mount has no size `8`: a whole number from 1 to 7"),
        (vec!["spd", "tree", "--size", "0"], "SPD tree has no size `0`"),
        (vec!["spd", "gear"], "no SPD database named `gear`"),
    ] {
        let o = glint(&args);
        assert_eq!(o.status.code(), Some(2), "{args:?}: {}", stderr(&o));
        let message = stderr(&o);
        assert!(message.contains(needle), "{args:?}: {message}");
        assert!(!message.contains("panicked"), "{args:?}: {message}");
    }
}

#[test]
fn probe_prints_the_camera_frame_and_the_ray_tree() {
    let o = glint(&["probe", "spd:balls:1", "256", "256", "--width", "512", "--height", "512"]);
    assert!(o.status.success(), "{}", stderr(&o));
    let text = String::from_utf8(o.stdout).unwrap();
    for needle in ["e = (2.1, 1.3, 1.7)", "u = ", "v = ", "w = ", "screen point s = ", "#0 eye ray, depth 1", "shadow ray to light", "reflect ray, depth 2"] {
        assert!(text.contains(needle), "{needle} missing in:\n{text}");
    }

    let o = glint(&["probe", "spd:balls:1", "256", "256", "--json"]);
    assert!(o.status.success(), "{}", stderr(&o));
    let v: serde_json::Value = serde_json::from_str(&String::from_utf8(o.stdout).unwrap()).unwrap();
    assert_eq!(v["pixel"], serde_json::json!([256, 256]));
    for key in ["e", "u", "v", "w"] {
        assert_eq!(v["camera"][key].as_array().map(Vec::len), Some(3), "camera.{key}");
    }
    let rays = v["rays"].as_array().unwrap();
    assert!(rays[0]["parent"].is_null() && rays[0]["kind"] == "eye");
    let sum = (0..3).map(|c| rays.iter().map(|r| r["contribution"][c].as_f64().unwrap()).sum::<f64>());
    for (c, total) in sum.enumerate() {
        let color = v["color"][c].as_f64().unwrap();
        assert!((total - color).abs() <= 1e-5 * color.abs().max(1e-2), "channel {c}: {total} vs {color}");
    }
    for key in ["id", "parent", "kind", "depth", "origin", "dir", "t", "object", "weight", "contribution"] {
        assert!(rays.iter().all(|r| r.get(key).is_some()), "rays lack `{key}`");
    }
}

#[test]
fn probe_outside_the_image_is_one_clear_usage_error() {
    let o = glint(&["probe", "spd:tetra:1", "512", "3"]);
    assert_eq!(o.status.code(), Some(2), "{}", stderr(&o));
    let message = stderr(&o);
    assert_eq!(message.lines().count(), 1, "{message}");
    assert!(message.contains("pixel (512, 3) is outside the 512 x 512 image: X is 0 to 511"), "{message}");
}

#[test]
fn bench_cold_reports_each_kernels_compile() {
    let o = glint(&["bench", "--cold", "--json", "spd:tetra:2", "--width", "32", "--height", "32"]);
    assert!(o.status.success(), "{}", stderr(&o));
    let report: serde_json::Value = serde_json::from_str(String::from_utf8(o.stdout).unwrap().trim()).unwrap();
    // What a one-off render of 32×32 compiles: eye rays one by one.
    assert_eq!(report["kinds"], "triangles, eye rays only, single eye rays");
    for kernel in ["trace_compile_ms", "primary_compile_ms"] {
        assert!(report[kernel].as_f64().unwrap() > 0.0, "{report}");
    }
    // The tests run on a CPU adapter in CI, which resolves on the host.
    assert!(report["resolve_compile_ms"].is_null(), "{report}");
}
