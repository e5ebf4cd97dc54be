//! Shared by the GPU tests: one device for the whole test binary, and scenes
//! written inline as TOML.
#![allow(dead_code)] // each test binary uses a different part of this module

use std::path::Path;
use std::sync::OnceLock;

use glint_gpu::shaders::ShaderSource;
use glint_gpu::{Acceleration, Gpu, Image, RayStats, RenderOptions, Renderer};
use glint_scene::Scene;

/// The device every GPU test uses. No adapter is a failure, never a skip.
pub fn gpu() -> &'static Gpu {
    static GPU: OnceLock<Gpu> = OnceLock::new();
    GPU.get_or_init(|| Gpu::new().unwrap_or_else(|e| panic!("GPU tests need an adapter (lavapipe in CI): {e}")))
}

pub fn renderer() -> &'static Renderer {
    static RENDERER: OnceLock<Renderer> = OnceLock::new();
    RENDERER.get_or_init(|| {
        let gpu = gpu();
        Renderer::new(gpu.device.clone(), gpu.queue.clone(), &ShaderSource::Embedded)
            .unwrap_or_else(|e| panic!("{e}"))
    })
}

pub fn parse(toml: &str) -> Scene {
    glint_scene::toml_scene::parse(toml, Path::new("inline.toml")).unwrap_or_else(|e| panic!("{e}"))
}

pub fn render(scene: &Scene) -> (Image, RayStats) {
    render_with(scene, Acceleration::Bvh)
}

pub fn render_with(scene: &Scene, acceleration: Acceleration) -> (Image, RayStats) {
    render_options(scene, acceleration, RenderOptions::default())
}

/// Renders with `options`; the view scale is chosen for the scene when left at 1.
pub fn render_options(scene: &Scene, acceleration: Acceleration, options: RenderOptions) -> (Image, RayStats) {
    let r = renderer();
    let prepared = r.prepare(scene, scene.width, scene.height, acceleration).unwrap_or_else(|e| panic!("{e}"));
    let options = RenderOptions { view_scale: prepared.view_scale(options.view), ..options };
    r.render(&prepared.buffers, &options, &mut |_, _| {}).unwrap_or_else(|e| panic!("{e}"))
}

/// Asserts two colours agree per channel within `tol`.
#[track_caller]
pub fn assert_close(actual: [f32; 3], expected: [f64; 3], tol: f64, what: &str) {
    for c in 0..3 {
        assert!(
            (f64::from(actual[c]) - expected[c]).abs() <= tol,
            "{what}: got {actual:?}, expected {expected:?} (±{tol})"
        );
    }
}

/// Asserts two images are equal in all but at most `allowed` pixels, reporting
/// the first differences (not the whole image).
#[track_caller]
pub fn assert_images_equal(a: &[[f32; 4]], b: &[[f32; 4]], allowed: usize, what: &str) {
    assert_eq!(a.len(), b.len(), "{what}: sizes differ");
    let differing: Vec<(usize, [f32; 4], [f32; 4])> =
        a.iter().zip(b).enumerate().filter(|(_, (p, q))| p != q).map(|(i, (p, q))| (i, *p, *q)).collect();
    assert!(
        differing.len() <= allowed,
        "{what}: {} pixels differ (allowed {allowed}); first: {:?}",
        differing.len(),
        &differing[..differing.len().min(3)]
    );
}

/// The files under `dir` with one of `extensions`, at any depth, build output left out.
pub fn source_files(dir: &Path, extensions: &[&str], out: &mut Vec<std::path::PathBuf>) {
    for entry in std::fs::read_dir(dir).unwrap_or_else(|e| panic!("{}: {e}", dir.display())) {
        let path = entry.unwrap().path();
        if path.is_dir() {
            if !["target", "node_modules", ".git"].iter().any(|skip| path.ends_with(skip)) {
                source_files(&path, extensions, out);
            }
        } else if path.extension().is_some_and(|e| extensions.iter().any(|x| e == *x)) {
            out.push(path);
        }
    }
}
