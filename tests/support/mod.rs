//! Shared by the GPU tests: one device for the whole test binary, a renderer
//! under the device's own profile and one under the plain profile, and
//! scenes written inline as TOML.
//!
//! The behavioural suites render and probe through [`render_options`] and
//! [`Probing`], which do it under both profiles and hold the plain profile's
//! pixels, ray counts and ray trees to the device profile's bit for bit. On
//! lavapipe the plain profile runs about 5× slower, so an image larger than
//! [`PLAIN_PIXELS`] is checked over a band of its rows that many pixels large,
//! and a suite may check a subset of its scenes ([`render_device_profile`]).
#![allow(dead_code)] // each test binary uses a different part of this module

use std::path::Path;
use std::sync::OnceLock;

use glint_encoding::gpu_types::View;
use glint_gpu::probe::{Prober, RayTree};
use glint_gpu::shaders::ShaderSource;
use glint_gpu::{Acceleration, DeviceProfile, Gpu, Image, Prepared, ProfileName, RayStats, Region, RenderOptions, Renderer};
use glint_scene::Scene;

/// The most pixels of one image the plain profile renders again.
pub const PLAIN_PIXELS: u64 = 48 * 48;

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

/// The test device under the plain profile, `Tuning::PLAIN`: what every GPU
/// and browser runs (GLINT_PROFILE=plain).
pub fn plain_renderer() -> &'static Renderer {
    static RENDERER: OnceLock<Renderer> = OnceLock::new();
    RENDERER.get_or_init(|| {
        let gpu = gpu();
        let profile = DeviceProfile::of_device_forced(&gpu.device, Some(ProfileName::Plain));
        Renderer::with_profile(gpu.device.clone(), gpu.queue.clone(), &ShaderSource::Embedded, profile).unwrap_or_else(|e| panic!("{e}"))
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

/// Renders with `options` under the device's profile, and again under the
/// plain profile (see the module's comment), which must give the same bits;
/// the view scale is chosen for the scene when left at 1. The heat map is
/// rendered once: it counts the nodes of the BVH, whose build is the profile's.
pub fn render_options(scene: &Scene, acceleration: Acceleration, options: RenderOptions) -> (Image, RayStats) {
    render_profiles(scene, acceleration, options, true)
}

/// [`render_options`] under the device's profile alone (for suites that hold
/// a subset of their scenes to the plain profile).
pub fn render_device_profile(scene: &Scene, acceleration: Acceleration, options: RenderOptions) -> (Image, RayStats) {
    render_profiles(scene, acceleration, options, false)
}

fn render_profiles(scene: &Scene, acceleration: Acceleration, options: RenderOptions, plain_too: bool) -> (Image, RayStats) {
    let render = |r: &Renderer, region: Option<Region>| {
        let prepared = r.prepare(scene, scene.width, scene.height, acceleration).unwrap_or_else(|e| panic!("{e}"));
        let options = RenderOptions { view_scale: prepared.view_scale(options.view), ..options };
        let region = region.unwrap_or(Region::whole(scene.width, scene.height));
        r.render_region(&prepared.buffers, region, &options, &mut |_, _| {}).unwrap_or_else(|e| panic!("{e}"))
    };
    let (image, stats) = render(renderer(), None);
    if plain_too && options.view != View::Heatmap {
        let band = plain_band(scene.width, scene.height);
        let (plain, plain_stats) = render(plain_renderer(), Some(band));
        let rows = (band.y0 * scene.width) as usize..(band.y1 * scene.width) as usize;
        let what = format!("the plain profile's {:?} view, rows {}..{}", options.view, band.y0, band.y1);
        assert_images_equal(&plain.linear, &image.linear[rows.clone()], 0, &what);
        assert_images_equal(&plain.display, &image.display[rows], 0, &what);
        if band == Region::whole(scene.width, scene.height) {
            assert_eq!(plain_stats, stats, "{what}: the rays traced");
        }
    }
    (image, stats)
}

/// The rows of a `width` × `height` image the plain profile renders again: all
/// of them, or a band of [`PLAIN_PIXELS`] through the middle.
fn plain_band(width: u32, height: u32) -> Region {
    let rows = (PLAIN_PIXELS / u64::from(width)).clamp(1, u64::from(height)) as u32;
    let y0 = (height - rows) / 2;
    Region { x0: 0, y0, x1: width, y1: y0 + rows }
}

/// A scene prepared for probing under both profiles: each probe is taken
/// under each, and the plain profile's tree must be the device profile's.
pub struct Probing {
    prepared: Vec<(&'static Renderer, &'static Prober, Prepared)>,
}

impl Probing {
    pub fn new(scene: &Scene) -> Probing {
        let prepared = [(renderer(), prober()), (plain_renderer(), plain_prober())]
            .map(|(r, p)| (r, p, r.prepare(scene, scene.width, scene.height, Acceleration::Bvh).unwrap_or_else(|e| panic!("{e}"))));
        Probing { prepared: prepared.into() }
    }

    /// The scene as the device's profile prepared it.
    pub fn prepared(&self) -> &Prepared {
        &self.prepared[0].2
    }

    pub fn probe(&self, x: u32, y: u32) -> RayTree {
        let mut trees = self.prepared.iter().map(|(renderer, prober, prepared)| {
            prober.probe(renderer, &prepared.buffers, x, y, &RenderOptions::default()).unwrap_or_else(|e| panic!("{e}"))
        });
        let tree = trees.next().expect("the device's profile");
        for plain in trees {
            assert_eq!(plain, tree, "the plain profile's probe of ({x}, {y})");
        }
        tree
    }
}

fn prober() -> &'static Prober {
    static PROBER: OnceLock<Prober> = OnceLock::new();
    PROBER.get_or_init(|| Prober::new(renderer(), &ShaderSource::Embedded).unwrap_or_else(|e| panic!("{e}")))
}

fn plain_prober() -> &'static Prober {
    static PROBER: OnceLock<Prober> = OnceLock::new();
    PROBER.get_or_init(|| Prober::new(plain_renderer(), &ShaderSource::Embedded).unwrap_or_else(|e| panic!("{e}")))
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
