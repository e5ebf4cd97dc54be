//! WGSL checks that need no device: every kernel parses and validates with naga,
//! and every struct the host uploads has the layout of its WGSL twin.

use std::mem::{offset_of, size_of};

use glint_gpu::shaders::{ShaderSource, PRESENT_FILES, RESOLVE_FILES, TRACE_FILES};
use glint_scene::gpu_bvh::{GpuGrid, GpuNode};
use glint_scene::gpu_types::{GpuCamera, GpuLight, GpuMaterial, GpuPrim, Globals, ResolveParams};

fn trace_module() -> naga::Module {
    ShaderSource::Embedded.compose(TRACE_FILES).unwrap().validate().unwrap()
}

#[test]
fn every_kernel_validates() {
    for files in [TRACE_FILES, RESOLVE_FILES, PRESENT_FILES] {
        let composed = ShaderSource::Embedded.compose(files).unwrap();
        if let Err(e) = composed.validate() {
            panic!("{e}");
        }
    }
}

#[test]
fn every_shader_file_is_part_of_a_kernel() {
    let dir = ShaderSource::source_dir();
    for entry in std::fs::read_dir(&dir).unwrap() {
        let name = entry.unwrap().file_name().into_string().unwrap();
        assert!(
            [TRACE_FILES, RESOLVE_FILES, PRESENT_FILES].iter().any(|files| files.contains(&name.as_str())),
            "shaders/{name} is in no kernel"
        );
    }
}

#[test]
fn errors_name_the_file_and_line() {
    let dir = tempfile::tempdir().unwrap();
    for name in TRACE_FILES {
        std::fs::copy(ShaderSource::source_dir().join(name), dir.path().join(name)).unwrap();
    }
    let broken = std::fs::read_to_string(dir.path().join("sphere.wgsl")).unwrap().replacen("let b =", "let b = undefined_name +", 1);
    std::fs::write(dir.path().join("sphere.wgsl"), &broken).unwrap();
    let line = broken.lines().position(|l| l.contains("undefined_name")).unwrap() + 1;
    let err = ShaderSource::Dir(dir.path().into()).compose(TRACE_FILES).unwrap().validate().unwrap_err().to_string();
    assert!(err.contains(&format!("shaders/sphere.wgsl:{line}")), "{err}");
}

/// Asserts the WGSL struct `name` has exactly the given members at the host's
/// offsets and the host's size.
fn check_layout(module: &naga::Module, name: &str, size: usize, members: &[(&str, usize)]) {
    let (handle, ty) = module
        .types
        .iter()
        .find(|(_, t)| t.name.as_deref() == Some(name))
        .unwrap_or_else(|| panic!("no WGSL struct {name}"));
    let naga::TypeInner::Struct { members: wgsl_members, span } = &ty.inner else {
        panic!("{name} is not a struct");
    };
    let mut layouter = naga::proc::Layouter::default();
    layouter.update(module.to_ctx()).unwrap();
    assert_eq!(*span as usize, size, "{name}: WGSL size {span} vs host {size}");
    assert_eq!(layouter[handle].size as usize, size, "{name}");
    let wgsl: Vec<(String, usize)> =
        wgsl_members.iter().map(|m| (m.name.clone().unwrap_or_default(), m.offset as usize)).collect();
    let host: Vec<(String, usize)> = members.iter().map(|(n, o)| (n.to_string(), *o)).collect();
    assert_eq!(wgsl, host, "{name}: members and offsets differ");
}

macro_rules! layout {
    ($module:expr, $ty:ident { $($field:ident),* $(,)? }) => {
        check_layout(&$module, stringify!($ty), size_of::<$ty>(), &[$((stringify!($field), offset_of!($ty, $field))),*])
    };
}

#[test]
fn host_structs_match_wgsl() {
    let m = trace_module();
    layout!(m, GpuCamera { eye, projection, u, half_width, v, half_height, w, _pad });
    layout!(
        m,
        Globals {
            camera, background, width, ambient, height, depth_cue_color, light_count, depth_cue,
            max_depth, cutoff, flags, view, tile_origin, sample_index, seed, sample_count, pixel_filter,
            row_end, bvh_root
        }
    );
    layout!(m, GpuLight { position, kind, radiance, attenuation, coefficients });
    layout!(
        m,
        GpuMaterial {
            color, ka, specular_color, kd, reflect, ks, transmit, shininess, f0, ior, flags, _pad0, _pad1, _pad2
        }
    );
    layout!(m, GpuPrim { a, b, c, kind_material, object, first, count });
    layout!(m, GpuNode { quantized, children });
    layout!(m, GpuGrid { origin, exponents });
    for files in [RESOLVE_FILES, PRESENT_FILES] {
        let m = ShaderSource::Embedded.compose(files).unwrap().validate().unwrap();
        layout!(m, ResolveParams { pixel_count, tone_map, exposure, view, scale, _pad0, _pad1, _pad2 });
    }
}

/// The constants host and kernels share reach every kernel from Rust, with
/// Rust's values; no shader file declares one of them again.
#[test]
fn shared_constants_come_from_the_host() {
    use glint_scene::gpu_types as g;
    let module = trace_module();
    let value = |name: &str| {
        let (_, c) = module.constants.iter().find(|(_, c)| c.name.as_deref() == Some(name)).unwrap_or_else(|| panic!("no WGSL constant {name}"));
        match module.global_expressions[c.init] {
            naga::Expression::Literal(naga::Literal::U32(v)) => f64::from(v),
            naga::Expression::Literal(naga::Literal::F32(v)) => f64::from(v),
            ref e => panic!("{name} = {e:?}"),
        }
    };
    for (name, host) in [
        ("PRIM_POLYGON", f64::from(g::PRIM_POLYGON)),
        ("VIEW_HEATMAP", f64::from(g::VIEW_HEATMAP)),
        ("RAY_STACK", f64::from(glint_scene::scene::MAX_DEPTH_LIMIT + 1)),
        ("BVH_STACK", glint_scene::bvh::MAX_DEPTH as f64),
        ("LEAF", f64::from(g::LEAF)),
        ("MISS", f64::from(g::MISS)),
        ("STAT_COUNT", f64::from(g::STAT_COUNT)),
    ] {
        assert_eq!(value(name), host, "{name}");
    }
    let prelude = g::wgsl_prelude();
    let shared: Vec<&str> = prelude.lines().filter_map(|l| l.strip_prefix("const ")?.split(':').next()).collect();
    for entry in std::fs::read_dir(ShaderSource::source_dir()).unwrap() {
        let path = entry.unwrap().path();
        let text = std::fs::read_to_string(&path).unwrap();
        for name in &shared {
            assert!(!text.contains(&format!("const {name}:")), "{} declares the shared constant {name} again", path.display());
        }
    }
}
