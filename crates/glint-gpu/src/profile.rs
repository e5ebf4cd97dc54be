//! The device profile: every device-dependent choice Glint makes, made once
//! from the opened adapter. Lavapipe (Mesa's software Vulkan driver) gets the
//! choices tuned for it; every other device gets the plain ones, the code as
//! the lecture reads it. Every choice traces the same bits.

use glint_encoding::gpu_types::GpuScene;

use crate::lavapipe;
use crate::shaders::SceneArrays;
use crate::tuning::{fits_uniform_tree, Tuning, WorkgroupSizes};

/// Eye rays from which a one-off render on lavapipe traces packets: fewer
/// trace sooner one at a time, whose kernel lavapipe compiles faster
/// (docs/decisions/021-packets.md).
pub const PACKET_EYE_RAYS: u64 = 2_000_000;

/// SIMD group sizes whose lanes the primary kernel hands blocks of one eye
/// tile (`spread_invocation`), four of them to load a primitive's words.
const TILE_SIMD_SIZES: [u32; 2] = [4, 8];

/// What lavapipe compiles this process's kernels to, as its environment asked
/// (lavapipe.rs sets it before the driver loads).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct CompiledKernels {
    /// Without LLVM's optimisation passes: sooner compiled, slower run.
    pub quick: bool,
    /// The SIMD width, in bits, from the adapter's name.
    pub vector_bits: Option<u32>,
}

impl CompiledKernels {
    /// On a lavapipe adapter, the kernels this process compiles there.
    pub fn on(info: &wgpu::AdapterInfo) -> Option<CompiledKernels> {
        is_lavapipe(info).then(|| CompiledKernels { quick: lavapipe::kernels_compile_quickly(), vector_bits: lavapipe::vector_bits(info) })
    }
}

impl std::fmt::Display for CompiledKernels {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(if self.quick { "quick kernels" } else { "optimised kernels" })?;
        match self.vector_bits {
            Some(bits) => write!(f, ", {bits} bits"),
            None => Ok(()),
        }
    }
}

#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct DeviceProfile {
    /// On lavapipe, the kernels it compiles: the one choice the process
    /// environment makes, and it counts on lavapipe alone.
    pub kernels: Option<CompiledKernels>,
    /// How the kernels read the scene's arrays.
    pub scene_arrays: SceneArrays,
    /// Whether the primary kernel traces 2×2 ray packets at all.
    pub packets: bool,
    /// Eye rays from which a one-off render traces packets (see `packets_for`).
    pub packet_eye_rays: u64,
    /// Whether kernels read a BVH that fits uniform buffers from there:
    /// lavapipe loads from them per lane without a branch, but a GPU's
    /// constant cache serialises lanes that read different records.
    pub uniform_tree: bool,
    /// Whether the renderer bins eye tiles for a view: subgroup operations on
    /// SIMD groups of 4 or 8 lanes, with the scene in storage buffers.
    pub eye_tiles: bool,
    /// Whether the host resolves read-backs instead of the resolve kernel: on
    /// a CPU adapter its compile costs more than the host's pass over a tile
    /// (outside a browser).
    pub resolves_on_host: bool,
    /// Whether dispatches deal their places in spread order (`Tuning::spread`):
    /// lavapipe hands each thread a run of workgroups and runs SIMD groups of
    /// consecutive invocations; eye tiles need a SIMD group in one tile.
    pub spread: bool,
    /// Whether the ray tree is walked through one call of the BVH walk
    /// (`Tuning::one_walk_tree`): lavapipe inlines each call, and compiles
    /// each copy (docs/decisions/024-one-walk-in-the-trace-kernel.md).
    pub one_walk_tree: bool,
    /// The workgroups of the kernels that trace row bands.
    pub workgroups: WorkgroupSizes,
}

impl DeviceProfile {
    /// The profile of the adapter `info` describes, whose device has
    /// `features`; `quick_kernels` is what the process environment asked
    /// lavapipe for, which no other adapter reads.
    pub fn of(info: &wgpu::AdapterInfo, features: wgpu::Features, quick_kernels: bool) -> DeviceProfile {
        let kernels = is_lavapipe(info).then(|| CompiledKernels { quick: quick_kernels, vector_bits: lavapipe::vector_bits(info) });
        // Kernels compiled without optimisation passes keep every value in
        // memory anyway, and lavapipe fetches a texel without the per-lane
        // bounds branch a storage buffer's load takes.
        let scene_arrays = if kernels.is_some_and(|k| k.quick) { SceneArrays::Textures } else { SceneArrays::Buffers };
        let subgroups_fit = features.contains(wgpu::Features::SUBGROUP)
            && TILE_SIMD_SIZES.contains(&info.subgroup_min_size)
            && TILE_SIMD_SIZES.contains(&info.subgroup_max_size);
        let eye_tiles = scene_arrays == SceneArrays::Buffers && subgroups_fit;
        DeviceProfile {
            kernels,
            scene_arrays,
            // Eye tiles are walked by packets; otherwise packets are lavapipe's.
            packets: kernels.is_some() || eye_tiles,
            packet_eye_rays: if kernels.is_some() { PACKET_EYE_RAYS } else { 0 },
            uniform_tree: kernels.is_some(),
            eye_tiles,
            // A browser's page may not wait for a read-back, and its resolve
            // kernel compiles in the GPU process, off the page's thread.
            resolves_on_host: info.device_type == wgpu::DeviceType::Cpu && info.backend != wgpu::Backend::BrowserWebGpu,
            spread: kernels.is_some() || eye_tiles,
            one_walk_tree: kernels.is_some(),
            workgroups: if kernels.is_some() { WorkgroupSizes::LAVAPIPE } else { WorkgroupSizes::PLAIN },
        }
    }

    /// The profile of an open device, with what this process asked lavapipe for.
    pub fn of_device(device: &wgpu::Device) -> DeviceProfile {
        DeviceProfile::of(&device.adapter_info(), device.features(), lavapipe::kernels_compile_quickly())
    }

    /// This profile with the scene's arrays read as `arrays` says (tests that
    /// compare the ways); eye tiles need storage buffers.
    pub fn reading(self, arrays: SceneArrays) -> DeviceProfile {
        DeviceProfile { scene_arrays: arrays, eye_tiles: self.eye_tiles && arrays == SceneArrays::Buffers, ..self }
    }

    /// How `scene`'s kernels are tuned here before any view is binned into
    /// eye tiles: packets wherever the profile traces them (the viewer's,
    /// whose frames repay any compile).
    pub fn tuning(&self, scene: &GpuScene) -> Tuning {
        Tuning {
            arrays: self.scene_arrays,
            packets: self.packets,
            uniform_tree: self.uniform_tree && fits_uniform_tree(scene),
            eye_tiles: false,
            spread: self.spread,
            one_walk_tree: self.one_walk_tree,
            workgroups: self.workgroups,
        }
    }

    /// Whether a one-off command that traces `eye_rays` eye rays in all
    /// traces packets: only once they repay their compile.
    pub fn packets_for(&self, eye_rays: u64) -> bool {
        self.packets && eye_rays >= self.packet_eye_rays
    }

    /// One line for users: which profile, and on lavapipe which kernels.
    pub fn describe(&self) -> String {
        match self.kernels {
            Some(kernels) => format!("lavapipe profile ({kernels})"),
            None => "plain profile".to_string(),
        }
    }
}

fn is_lavapipe(info: &wgpu::AdapterInfo) -> bool {
    info.name.contains("llvmpipe")
}

#[cfg(test)]
pub(crate) mod tests {
    use super::*;

    pub(crate) fn adapter(name: &str, device_type: wgpu::DeviceType, subgroups: u32) -> wgpu::AdapterInfo {
        let mut info = wgpu::AdapterInfo::new(device_type, wgpu::Backend::Vulkan);
        info.name = name.into();
        (info.subgroup_min_size, info.subgroup_max_size) = (subgroups, subgroups);
        info
    }

    pub(crate) fn lavapipe(bits: u32) -> wgpu::AdapterInfo {
        adapter(&format!("llvmpipe (LLVM 19.1.7, {bits} bits)"), wgpu::DeviceType::Cpu, bits / 32)
    }

    fn empty_scene() -> GpuScene {
        GpuScene {
            prims: Vec::new(),
            nodes: Vec::new(),
            grids: Vec::new(),
            bvh_root: 0,
            materials: Vec::new(),
            lights: Vec::new(),
            points: Vec::new(),
            light_count: 0,
        }
    }

    const GPUS: [(&str, wgpu::DeviceType, u32); 3] = [
        ("NVIDIA GeForce RTX 4090", wgpu::DeviceType::DiscreteGpu, 32),
        ("AMD Radeon RX 7900 XTX (RADV NAVI31)", wgpu::DeviceType::DiscreteGpu, 64),
        ("Intel(R) Graphics (ADL GT2)", wgpu::DeviceType::IntegratedGpu, 16),
    ];

    #[test]
    fn lavapipe_gets_the_choices_tuned_for_it() {
        for bits in [128, 256] {
            let optimised = DeviceProfile::of(&lavapipe(bits), wgpu::Features::SUBGROUP, false);
            let want = DeviceProfile {
                kernels: Some(CompiledKernels { quick: false, vector_bits: Some(bits) }),
                scene_arrays: SceneArrays::Buffers,
                packets: true,
                packet_eye_rays: PACKET_EYE_RAYS,
                uniform_tree: true,
                eye_tiles: true,
                resolves_on_host: true,
                spread: true,
                one_walk_tree: true,
                workgroups: WorkgroupSizes::LAVAPIPE,
            };
            assert_eq!(optimised, want);
            assert!(optimised.tuning(&empty_scene()).one_walk_tree, "lavapipe walks the ray tree in one walk");
            let quick = DeviceProfile::of(&lavapipe(bits), wgpu::Features::SUBGROUP, true);
            let want = DeviceProfile {
                kernels: Some(CompiledKernels { quick: true, vector_bits: Some(bits) }),
                scene_arrays: SceneArrays::Textures,
                eye_tiles: false,
                ..want
            };
            assert_eq!(quick, want);
            assert!(!optimised.packets_for(512 * 512) && optimised.packets_for(PACKET_EYE_RAYS));
            assert_eq!(quick.describe(), format!("lavapipe profile (quick kernels, {bits} bits)"));
        }
        let without_subgroups = DeviceProfile::of(&lavapipe(128), wgpu::Features::empty(), false);
        assert!(!without_subgroups.eye_tiles && without_subgroups.packets);
    }

    #[test]
    fn gpus_get_the_plain_choices_whatever_the_environment_asks_of_lavapipe() {
        for (name, device_type, subgroups) in GPUS {
            for quick_kernels in [false, true] {
                let profile = DeviceProfile::of(&adapter(name, device_type, subgroups), wgpu::Features::SUBGROUP, quick_kernels);
                let plain = DeviceProfile {
                    kernels: None,
                    scene_arrays: SceneArrays::Buffers,
                    packets: false,
                    packet_eye_rays: 0,
                    uniform_tree: false,
                    eye_tiles: false,
                    resolves_on_host: false,
                    spread: false,
                    one_walk_tree: false,
                    workgroups: WorkgroupSizes::PLAIN,
                };
                assert_eq!(profile, plain, "{name}, quick kernels asked: {quick_kernels}");
                assert_eq!(profile.tuning(&empty_scene()), Tuning::PLAIN, "{name}: the lecture's code, one ray at a time");
                assert_eq!(profile.describe(), "plain profile");
                assert!(!profile.packets_for(u64::MAX));
            }
        }
    }

    #[test]
    fn a_gpu_whose_subgroups_fit_eye_tiles_walks_them_in_packets() {
        let small_groups = adapter("a GPU of 8-lane SIMD groups", wgpu::DeviceType::IntegratedGpu, 8);
        let profile = DeviceProfile::of(&small_groups, wgpu::Features::SUBGROUP, true);
        assert!(profile.eye_tiles && profile.packets && profile.packets_for(1) && profile.spread, "{profile:?}");
        assert!(!profile.uniform_tree && !profile.one_walk_tree && profile.scene_arrays == SceneArrays::Buffers);
        assert_eq!(profile.workgroups, WorkgroupSizes::PLAIN);
        assert!(!DeviceProfile::of(&small_groups, wgpu::Features::empty(), false).eye_tiles, "no subgroup operations");
    }

    #[test]
    fn a_browser_gets_the_plain_choices_and_resolves_on_the_device() {
        // Chromium on SwiftShader: a fallback adapter, which wgpu calls a CPU.
        let mut swiftshader = adapter("SwiftShader Device (Subzero)", wgpu::DeviceType::Cpu, 4);
        swiftshader.backend = wgpu::Backend::BrowserWebGpu;
        let plain = DeviceProfile::of(&adapter("a GPU", wgpu::DeviceType::DiscreteGpu, 32), wgpu::Features::SUBGROUP, false);
        for features in [wgpu::Features::empty(), wgpu::Features::SUBGROUP] {
            let profile = DeviceProfile::of(&swiftshader, features, true);
            assert_eq!(DeviceProfile { eye_tiles: false, packets: false, spread: false, ..profile }, plain, "{features:?}");
            assert!(!profile.resolves_on_host && profile.describe() == "plain profile");
        }
        assert!(!DeviceProfile::of(&swiftshader, wgpu::Features::empty(), false).eye_tiles, "no subgroup operations");
        assert!(DeviceProfile::of(&swiftshader, wgpu::Features::SUBGROUP, false).eye_tiles, "4-lane groups fit eye tiles");
    }

    #[test]
    fn eye_tiles_need_the_scene_in_storage_buffers() {
        let profile = DeviceProfile::of(&lavapipe(128), wgpu::Features::SUBGROUP, false);
        assert!(!profile.reading(SceneArrays::Textures).eye_tiles);
        assert_eq!(profile.reading(SceneArrays::Buffers), profile);
    }
}
