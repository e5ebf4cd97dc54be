//! The device profile on lavapipe, opened by name so that these tests pass on
//! a machine with a GPU too: the renderer makes lavapipe's choices and a
//! scene's kernels are tuned by them, or by the plain profile's where that
//! is forced; the device is opened with WebGPU's default limits and raised to
//! the adapter's only for a scene that needs it. And the boundary: only
//! glint-gpu chooses a tuning or touches the driver's environment.

mod support;

use glint_gpu::shaders::{SceneArrays, ShaderSource};
use glint_gpu::{Acceleration, Gpu, GpuError, ProfileName, Renderer, Tuning, PACKET_EYE_RAYS};

fn lavapipe() -> &'static Gpu {
    static GPU: std::sync::OnceLock<Gpu> = std::sync::OnceLock::new();
    GPU.get_or_init(|| Gpu::named("llvmpipe").unwrap_or_else(|e| panic!("these tests need lavapipe (`bash .ci/setup`): {e}")))
}

#[test]
fn lavapipe_gets_its_own_profile_and_a_scene_its_tuning() {
    let gpu = lavapipe();
    let renderer = Renderer::new(gpu.device.clone(), gpu.queue.clone(), &ShaderSource::Embedded).unwrap();
    let profile = *renderer.profile();
    assert_eq!(profile, gpu.profile());
    assert_eq!((profile.name, profile.forced), (ProfileName::Lavapipe, false), "{profile:?}");
    let kernels = profile.kernels.expect("lavapipe's kernels are described");
    assert!(!kernels.quick && kernels.vector_bits.is_some(), "{kernels:?}");
    assert_eq!(profile.scene_arrays, SceneArrays::Buffers);
    assert!(profile.packets && profile.uniform_tree && profile.eye_tiles && profile.resolves_on_host && profile.spread && profile.one_walk_tree && profile.mask_loops,
        "{profile:?}");
    assert_eq!(profile.packet_eye_rays, PACKET_EYE_RAYS);
    assert!(profile.describe().starts_with("lavapipe profile"), "{}", profile.describe());

    let scene = glint_scene::load(std::path::Path::new("spd:tetra:2")).unwrap();
    let prepared = renderer.prepare(&scene, 32, 32, Acceleration::Bvh).unwrap();
    assert_eq!(prepared.buffers.tuning(), Tuning::LAVAPIPE);
}

/// The plain profile forced on the test device tunes every scene's kernels
/// as every GPU's: the suites' second renderer (tests/support).
#[test]
fn the_forced_plain_profile_tunes_kernels_as_every_gpus() {
    let renderer = support::plain_renderer();
    assert_eq!((renderer.profile().name, renderer.profile().forced), (ProfileName::Plain, true));
    for name in ["spd:tetra:2", "spd:balls:1"] {
        let scene = glint_scene::load(std::path::Path::new(name)).unwrap();
        let prepared = renderer.prepare(&scene, 32, 32, Acceleration::Bvh).unwrap();
        assert_eq!(prepared.buffers.tuning(), Tuning::PLAIN, "{name}");
        assert!(prepared.eye_tiles_build.is_none(), "{name}: the plain profile bins no eye tiles");
    }
}

#[test]
fn devices_open_with_webgpus_default_limits_and_raise_one_a_scene_needs() {
    let gpu = lavapipe();
    let (limits, defaults, offered) = (gpu.device.limits(), wgpu::Limits::default(), gpu.adapter.limits());
    assert_eq!(limits.max_storage_buffers_per_shader_stage, defaults.max_storage_buffers_per_shader_stage);
    assert_eq!(limits.max_storage_buffer_binding_size, defaults.max_storage_buffer_binding_size);
    assert_eq!(limits.max_texture_dimension_2d, defaults.max_texture_dimension_2d);

    let need = |limit| GpuError::Limit { what: "primitives".into(), limit, need: 1 << 40, have: 0 };
    assert!(offered.max_texture_dimension_2d > defaults.max_texture_dimension_2d, "lavapipe offers more than the default");
    let raised = gpu.raised_for(&need("max_texture_dimension_2d")).expect("a limit the adapter has more of").unwrap();
    assert_eq!(raised.device.limits().max_texture_dimension_2d, offered.max_texture_dimension_2d);
    assert_eq!(raised.device.limits().max_storage_buffers_per_shader_stage, defaults.max_storage_buffers_per_shader_stage);
    match gpu.raised_for(&need("max_storage_buffer_binding_size")) {
        None => assert_eq!(offered.max_storage_buffer_binding_size, limits.max_storage_buffer_binding_size, "the adapter has more"),
        Some(raised) => assert_eq!(raised.unwrap().device.limits().max_storage_buffer_binding_size, offered.max_storage_buffer_binding_size),
    }
    assert!(raised.raised_for(&need("max_texture_dimension_2d")).is_none(), "raised once, the error stands");
    assert!(gpu.raised_for(&GpuError::Runtime("lost".into())).is_none());
}

/// The profile is the one owner of driver decisions: the front ends and the
/// scene crate never name a driver, its environment or Mesa's shader cache,
/// nor change the process environment, which only glint-gpu's lavapipe.rs
/// does (only it calls `set_var`, an `unsafe` function).
#[test]
fn the_front_ends_and_the_scene_crate_name_no_driver() {
    let words = ["lavapipe", "llvmpipe", "MESA_", "GALLIVM_", "LP_", "set_var", "remove_var", "shader cache", "shader_cache"];
    let mut files = Vec::new();
    for krate in ["glint-cli", "glint-viewer", "glint-web", "glint-scene"] {
        let dir = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("crates").join(krate);
        support::source_files(&dir.join("src"), &["rs", "toml", "md"], &mut files);
        files.push(dir.join("Cargo.toml"));
    }
    assert!(files.iter().any(|f| f.ends_with("glint-cli/src/main.rs")), "the walk found the front ends");
    let mut found = Vec::new();
    for file in &files {
        let text = std::fs::read_to_string(file).unwrap_or_else(|e| panic!("{}: {e}", file.display()));
        for (i, line) in text.lines().enumerate() {
            if words.iter().any(|w| line.contains(w)) {
                found.push(format!("{}:{}: {}", file.display(), i + 1, line.trim()));
            }
        }
    }
    assert!(found.is_empty(), "driver decisions outside the device profile:\n{}", found.join("\n"));
}

/// Only tests set a tuning's choices: no crate but the workspace's tests
/// enables glint-gpu's `variants` feature, without which a `Tuning`'s fields
/// and a scene's tuning are private (glint-gpu's compile_fail doc-tests).
#[test]
fn no_front_end_enables_the_feature_that_sets_a_tuning() {
    let root = std::path::Path::new(env!("CARGO_MANIFEST_DIR"));
    for krate in std::fs::read_dir(root.join("crates")).unwrap() {
        let manifest = krate.unwrap().path().join("Cargo.toml");
        let text = std::fs::read_to_string(&manifest).unwrap_or_else(|e| panic!("{}: {e}", manifest.display()));
        let table: toml::Table = text.parse().unwrap_or_else(|e| panic!("{}: {e}", manifest.display()));
        for section in ["dependencies", "dev-dependencies", "build-dependencies"] {
            let gpu = table.get(section).and_then(|deps| deps.get("glint-gpu"));
            let features = gpu.and_then(|dep| dep.get("features")).and_then(|f| f.as_array()).cloned().unwrap_or_default();
            assert!(!features.iter().any(|f| f.as_str() == Some("variants")), "{} enables `variants` in [{section}]", manifest.display());
        }
    }
    let own: toml::Table = std::fs::read_to_string(root.join("Cargo.toml")).unwrap().parse().unwrap();
    let features = &own["dev-dependencies"]["glint-gpu"]["features"];
    assert_eq!(features.as_array().map(Vec::len), Some(1), "the workspace's tests enable `variants` alone: {features}");
}
