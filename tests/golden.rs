//! Golden images: every scene in `scenes/` (not `scenes/bench/`) rendered small
//! and compared with its committed image in `tests/golden/` by FLIP.
//!
//! `GLINT_BLESS=1 cargo test --release --test golden` rewrites the goldens;
//! review them as described in tests/golden/README.md before committing. On a
//! mismatch the actual image and a FLIP heat map are written to
//! `target/golden-diff/` and named in the failure.

mod support;

use std::io::Write;
use std::path::{Path, PathBuf};

use glint_gpu::{Acceleration, PngBits, RenderOptions};
use glint_scene::gpu_types::Filter;

const WIDTH: u32 = 160;
const HEIGHT: u32 = 120;
/// Mean FLIP error above this fails.
const MAX_MEAN_FLIP: f32 = 0.01;
/// A pixel whose FLIP error exceeds this is "bad" ...
const BAD_PIXEL_FLIP: f32 = 0.2;
/// ... and at most this fraction of pixels may be bad.
const MAX_BAD_FRACTION: f64 = 0.005;
/// Goldens must stay small in the repository.
const MAX_GOLDEN_BYTES: u64 = 30_000;

fn root() -> &'static Path {
    Path::new(env!("CARGO_MANIFEST_DIR"))
}

fn scene_files(dir: &Path, out: &mut Vec<PathBuf>) {
    let mut entries: Vec<_> = std::fs::read_dir(dir).unwrap().map(|e| e.unwrap().path()).collect();
    entries.sort();
    for path in entries {
        if path.is_dir() {
            if path.file_name().is_some_and(|n| n != "bench") {
                scene_files(&path, out);
            }
        } else if matches!(path.extension().and_then(|e| e.to_str()), Some("toml" | "nff" | "obj")) {
            out.push(path);
        }
    }
}

/// `scenes/gallery/mirror.toml` → `gallery-mirror`.
fn golden_name(scene: &Path) -> String {
    let rel = scene.strip_prefix(root().join("scenes")).unwrap().with_extension("");
    rel.to_string_lossy().replace(['/', '\\'], "-")
}

fn target_dir() -> PathBuf {
    std::env::var_os("CARGO_TARGET_DIR").map(PathBuf::from).unwrap_or_else(|| root().join("target"))
}

fn render_small(scene_path: &Path) -> image::RgbImage {
    let mut scene = glint_scene::load(scene_path).unwrap_or_else(|e| panic!("{e}"));
    // Keep the scene's aspect ratio inside WIDTH × HEIGHT.
    let scale = (f64::from(WIDTH) / f64::from(scene.width)).min(f64::from(HEIGHT) / f64::from(scene.height));
    scene.width = ((f64::from(scene.width) * scale).round() as u32).max(1);
    scene.height = ((f64::from(scene.height) * scale).round() as u32).max(1);
    let options = RenderOptions { spp: 4, seed: 1, filter: Filter::Tent, ..RenderOptions::default() };
    let (image, _) = support::render_options(&scene, Acceleration::Bvh, options);
    image.to_rgb8()
}

#[test]
fn every_scene_matches_its_golden_image() {
    let bless = std::env::var_os("GLINT_BLESS").is_some_and(|v| v == "1");
    let mut scenes = Vec::new();
    scene_files(&root().join("scenes"), &mut scenes);
    assert!(scenes.len() >= 2, "no scenes found");
    let diff_dir = target_dir().join("golden-diff");
    let mut failures = Vec::new();
    let mut worst = 0.0f32;
    for scene in &scenes {
        let name = golden_name(scene);
        let golden = root().join("tests/golden").join(format!("{name}.png"));
        let actual = render_small(scene);
        if bless {
            let image = glint_gpu::Image {
                width: actual.width(),
                height: actual.height(),
                display: actual.pixels().map(|p| [0, 1, 2, 3].map(|c| if c < 3 { f32::from(p[c]) / 255.0 } else { 1.0 })).collect(),
                linear: Vec::new(),
            };
            glint_gpu::write_image(&image, &golden, PngBits::Eight).unwrap();
            println!("blessed {}", golden.display());
            continue;
        }
        let Ok(expected) = image::open(&golden) else {
            failures.push(format!("{name}: no golden at {} (run GLINT_BLESS=1 cargo test --release --test golden)", golden.display()));
            continue;
        };
        let expected = expected.to_rgb8();
        let size = std::fs::metadata(&golden).unwrap().len();
        assert!(size <= MAX_GOLDEN_BYTES, "{}: {size} bytes, over {MAX_GOLDEN_BYTES}", golden.display());
        if expected.dimensions() != actual.dimensions() {
            failures.push(format!("{name}: size {:?}, golden {:?}", actual.dimensions(), expected.dimensions()));
            continue;
        }
        let (w, h) = actual.dimensions();
        let error = nv_flip::flip(
            nv_flip::FlipImageRgb8::with_data(w, h, expected.as_raw()),
            nv_flip::FlipImageRgb8::with_data(w, h, actual.as_raw()),
            nv_flip::DEFAULT_PIXELS_PER_DEGREE,
        );
        let mean = nv_flip::FlipPool::from_image(&error).mean();
        let values = error.to_vec();
        let bad = values.iter().filter(|v| **v > BAD_PIXEL_FLIP).count() as f64 / values.len() as f64;
        worst = worst.max(mean);
        if mean > MAX_MEAN_FLIP || bad > MAX_BAD_FRACTION {
            std::fs::create_dir_all(&diff_dir).unwrap();
            let actual_path = diff_dir.join(format!("{name}-actual.png"));
            let flip_path = diff_dir.join(format!("{name}-flip.png"));
            actual.save(&actual_path).unwrap();
            let heat = error.apply_color_lut(&nv_flip::magma_lut());
            image::RgbImage::from_raw(w, h, heat.to_vec()).unwrap().save(&flip_path).unwrap();
            failures.push(format!(
                "{name}: mean FLIP {mean:.4} (max {MAX_MEAN_FLIP}), {:.2}% bad pixels (max {:.2}%); see {} and {}",
                bad * 100.0,
                MAX_BAD_FRACTION * 100.0,
                actual_path.display(),
                flip_path.display()
            ));
        }
    }
    // Written past the test harness's capture, so every run shows the summary.
    let _ = writeln!(std::io::stderr(), "golden: {} images compared, worst mean FLIP {worst:.5}, {} failed", scenes.len(), failures.len());
    assert!(failures.is_empty(), "golden images differ:\n{}", failures.join("\n"));
}
