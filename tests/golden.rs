//! Golden images: every scene in `scenes/` (not `scenes/bench/`) rendered small
//! and compared with its committed image in `tests/golden/` by FLIP, through
//! the same code as `glint test tests/golden/manifest.toml`.
//!
//! `GLINT_BLESS=1 cargo test --release --test golden` writes the goldens that
//! are missing or failing; review them as described in tests/golden/README.md
//! before committing. On a failure the report in `target/golden-diff/`
//! (index.html, with each failing case's golden, render and FLIP map) is named
//! in the message.
//!
//! The goldens are rendered under the device's profile; every scene is
//! rendered again under the plain profile too, smaller, to the same bits
//! (`every_scene_renders_the_same_bits_under_the_plain_profile`).

mod support;

use std::io::Write;
use std::path::{Path, PathBuf};

use glint_encoding::gpu_types::Filter;
use glint_golden::{Bless, RunOptions, Suite, Summary};
use glint_gpu::{Acceleration, RenderOptions};

/// Goldens must stay small in the repository.
const MAX_GOLDEN_BYTES: u64 = 30_000;

fn root() -> &'static Path {
    Path::new(env!("CARGO_MANIFEST_DIR"))
}

fn target_dir() -> PathBuf {
    std::env::var_os("CARGO_TARGET_DIR").map(PathBuf::from).unwrap_or_else(|| root().join("target"))
}

#[test]
fn every_scene_matches_its_golden_image() {
    let suite = Suite::load(&root().join("tests/golden/manifest.toml")).unwrap_or_else(|e| panic!("{e}"));
    assert!(suite.cases.len() >= 2, "no scenes found");
    let bless = if std::env::var_os("GLINT_BLESS").is_some_and(|v| v == "1") { Bless::MissingOrFailing } else { Bless::No };
    let cases: Vec<_> = suite.cases.iter().collect();
    let options = RunOptions { bless, report_images: true };
    let outcomes = glint_golden::run(&cases, support::renderer(), options, &mut |outcome| println!("{}", outcome.line()));

    for case in &suite.cases {
        if let Ok(meta) = std::fs::metadata(&case.golden) {
            assert!(meta.len() <= MAX_GOLDEN_BYTES, "{}: {} bytes, over {MAX_GOLDEN_BYTES}", case.golden.display(), meta.len());
        }
    }
    let summary = Summary::of(&outcomes);
    // Written past the test harness's capture, so every run shows the summary.
    let _ = writeln!(std::io::stderr(), "golden: {summary}");
    if summary.failed > 0 {
        let report = glint_golden::write_report(&target_dir().join("golden-diff"), &suite.name, &outcomes).unwrap_or_else(|e| panic!("{e}"));
        let failures: Vec<String> = outcomes.iter().filter(|o| o.status.failed()).map(|o| o.line()).collect();
        panic!(
            "golden images differ ({summary}); see {} (run GLINT_BLESS=1 cargo test --release --test golden to bless):\n{}",
            report.display(),
            failures.join("\n")
        );
    }
}

/// The plain profile, what every GPU runs, renders each golden scene as the
/// device's profile does, bit for bit: with the suite's samples, filter and
/// seed, at 48×36 (`support::PLAIN_PIXELS`), where lavapipe takes about 5×
/// as long under it as under its own.
#[test]
fn every_scene_renders_the_same_bits_under_the_plain_profile() {
    let suite = Suite::load(&root().join("tests/golden/manifest.toml")).unwrap_or_else(|e| panic!("{e}"));
    assert!(suite.cases.len() >= 2, "no scenes found");
    for case in &suite.cases {
        let mut scene = glint_scene::load(&case.scene).unwrap_or_else(|e| panic!("{}: {e}", case.scene.display()));
        (scene.width, scene.height) = (48, 36);
        let options = RenderOptions { spp: 4, filter: Filter::Tent, seed: 1, ..RenderOptions::default() };
        // Renders under both profiles and compares them.
        let (image, stats) = support::render_options(&scene, Acceleration::Bvh, options);
        assert!(stats.eye_hit > 0 && image.linear.len() == 48 * 36, "{}: nothing rendered", case.name);
    }
}
