//! The device profile on CI's adapter, lavapipe: the renderer makes
//! lavapipe's choices and a scene's kernels are tuned by them; the device is
//! opened with WebGPU's default limits and raised to the adapter's only for a
//! scene that needs it.

mod support;

use glint_gpu::shaders::SceneArrays;
use glint_gpu::{Acceleration, GpuError, Tuning, PACKET_EYE_RAYS};

#[test]
fn lavapipe_gets_its_own_profile_and_a_scene_its_tuning() {
    let gpu = support::gpu();
    assert!(gpu.info().name.contains("llvmpipe"), "the tests run on lavapipe: {}", gpu.info().name);
    let profile = *support::renderer().profile();
    assert_eq!(profile, gpu.profile());
    let kernels = profile.kernels.expect("lavapipe's kernels are described");
    assert!(!kernels.quick && kernels.vector_bits.is_some(), "{kernels:?}");
    assert_eq!(profile.scene_arrays, SceneArrays::Buffers);
    assert!(profile.packets && profile.uniform_tree && profile.eye_tiles && profile.resolves_on_host && profile.spread && profile.one_walk_tree,
        "{profile:?}");
    assert_eq!(profile.packet_eye_rays, PACKET_EYE_RAYS);
    assert!(profile.describe().starts_with("lavapipe profile"), "{}", profile.describe());

    let scene = glint_scene::load(std::path::Path::new("spd:tetra:2")).unwrap();
    let prepared = support::renderer().prepare(&scene, 32, 32, Acceleration::Bvh).unwrap();
    let tuned = Tuning::LAVAPIPE;
    assert_eq!(prepared.buffers.tuning, tuned);
}

#[test]
fn devices_open_with_webgpus_default_limits_and_raise_one_a_scene_needs() {
    let gpu = support::gpu();
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
/// scene crate never name a driver or its environment.
#[test]
fn the_front_ends_and_the_scene_crate_name_no_driver() {
    let words = ["lavapipe", "GALLIVM", "LP_NATIVE"];
    let mut files = Vec::new();
    for krate in ["glint-cli", "glint-viewer", "glint-scene"] {
        let dir = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("crates").join(krate);
        support::source_files(&dir, &["rs", "toml", "md"], &mut files);
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
