//! The device profile: every device-dependent choice Glint makes, made once
//! from the opened adapter. Lavapipe (Mesa's software Vulkan driver) gets the
//! choices tuned for it; every other device gets the plain ones, the code as
//! the lecture reads it. Every choice traces the same bits. `GLINT_PROFILE`
//! forces either profile on any adapter, for tests and bug reports.

use glint_encoding::gpu_types::GpuScene;

use crate::lavapipe;
use crate::shaders::SceneArrays;
use crate::tuning::{fits_uniform_tree, Tuning, WorkgroupSizes};
use crate::workload::Workload;
use crate::GpuError;

/// The variable that forces a profile on any adapter: `plain` or `lavapipe`.
pub const PROFILE_ENV: &str = "GLINT_PROFILE";

/// The profiles Glint has.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum ProfileName {
    /// The lecture's code, one ray at a time: what every GPU and browser runs.
    Plain,
    /// The choices tuned for lavapipe.
    Lavapipe,
}

impl ProfileName {
    pub const ALL: [ProfileName; 2] = [ProfileName::Plain, ProfileName::Lavapipe];

    pub fn as_str(self) -> &'static str {
        match self {
            ProfileName::Plain => "plain",
            ProfileName::Lavapipe => "lavapipe",
        }
    }

    /// The profile `GLINT_PROFILE` forces, if it names one; an error in one
    /// line if it names none.
    pub fn forced() -> Result<Option<ProfileName>, GpuError> {
        match std::env::var_os(PROFILE_ENV) {
            None => Ok(None),
            Some(value) => value.to_str().and_then(|v| v.parse().ok()).map(Some).ok_or_else(|| {
                GpuError::Profile(format!("{PROFILE_ENV}={} names no device profile: use plain or lavapipe", value.to_string_lossy()))
            }),
        }
    }
}

impl std::str::FromStr for ProfileName {
    type Err = ();

    fn from_str(text: &str) -> Result<ProfileName, ()> {
        ProfileName::ALL.into_iter().find(|name| name.as_str() == text).ok_or(())
    }
}

impl std::fmt::Display for ProfileName {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(self.as_str())
    }
}

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
    pub name: ProfileName,
    /// `GLINT_PROFILE` chose it, not the adapter.
    pub forced: bool,
    /// On lavapipe, the kernels it compiles: the one choice the process
    /// environment makes, and it counts on lavapipe alone.
    pub kernels: Option<CompiledKernels>,
    /// How the kernels read the scene's arrays.
    pub scene_arrays: SceneArrays,
    /// Whether the primary kernel traces 2×2 ray packets at all.
    pub packets: bool,
    /// Eye rays from which a one-off render traces packets (`Workload::traces_packets`).
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
    /// Whether loops over a few cases step through bit masks
    /// (`Tuning::mask_loops`): lavapipe unrolls a loop whose count it knows,
    /// and compiles each copy (docs/decisions/057-loops-over-bit-masks.md).
    pub mask_loops: bool,
    /// The workgroups of the kernels that trace row bands.
    pub workgroups: WorkgroupSizes,
}

impl DeviceProfile {
    /// The profile of the adapter `info` describes, whose device has
    /// `features`; `quick_kernels` is what the process environment asked
    /// lavapipe for, which no other adapter reads.
    pub fn of(info: &wgpu::AdapterInfo, features: wgpu::Features, quick_kernels: bool) -> DeviceProfile {
        let name = if is_lavapipe(info) { ProfileName::Lavapipe } else { ProfileName::Plain };
        DeviceProfile::choose(name, false, info, features, quick_kernels)
    }

    /// The profile `forced` names on that adapter, else the adapter's own.
    /// Forced on lavapipe, the plain profile is `Tuning::PLAIN`, what every
    /// GPU whose SIMD groups are too wide for eye tiles runs; the lavapipe
    /// profile on another adapter walks eye tiles only where its SIMD groups fit.
    pub fn forced(forced: Option<ProfileName>, info: &wgpu::AdapterInfo, features: wgpu::Features, quick_kernels: bool) -> DeviceProfile {
        match forced {
            Some(name) => DeviceProfile::choose(name, true, info, features, quick_kernels),
            None => DeviceProfile::of(info, features, quick_kernels),
        }
    }

    fn choose(name: ProfileName, forced: bool, info: &wgpu::AdapterInfo, features: wgpu::Features, quick_kernels: bool) -> DeviceProfile {
        let tuned = name == ProfileName::Lavapipe;
        let kernels = is_lavapipe(info).then(|| CompiledKernels { quick: quick_kernels, vector_bits: lavapipe::vector_bits(info) });
        // Kernels compiled without optimisation passes keep every value in
        // memory anyway, and lavapipe fetches a texel without the per-lane
        // bounds branch a storage buffer's load takes.
        let scene_arrays = if tuned && kernels.is_some_and(|k| k.quick) { SceneArrays::Textures } else { SceneArrays::Buffers };
        let subgroups_fit = features.contains(wgpu::Features::SUBGROUP)
            && TILE_SIMD_SIZES.contains(&info.subgroup_min_size)
            && TILE_SIMD_SIZES.contains(&info.subgroup_max_size);
        let eye_tiles = scene_arrays == SceneArrays::Buffers && subgroups_fit && (tuned || !forced);
        DeviceProfile {
            name,
            forced,
            kernels,
            scene_arrays,
            // Eye tiles are walked by packets; otherwise packets are lavapipe's.
            packets: tuned || eye_tiles,
            packet_eye_rays: if tuned { PACKET_EYE_RAYS } else { 0 },
            uniform_tree: tuned,
            eye_tiles,
            // A browser's page may not wait for a read-back, and its resolve
            // kernel compiles in the GPU process, off the page's thread. Where
            // it resolves is the adapter's, whatever the profile: both ways
            // give the same bits (tests/resolve.rs).
            resolves_on_host: info.device_type == wgpu::DeviceType::Cpu && info.backend != wgpu::Backend::BrowserWebGpu,
            spread: tuned || eye_tiles,
            one_walk_tree: tuned,
            mask_loops: tuned,
            workgroups: if tuned { WorkgroupSizes::LAVAPIPE } else { WorkgroupSizes::PLAIN },
        }
    }

    /// The profile of an open device, with what this process asked lavapipe
    /// for, unless `GLINT_PROFILE` forces one; an error if it names none.
    pub fn of_device(device: &wgpu::Device) -> Result<DeviceProfile, GpuError> {
        Ok(DeviceProfile::of_device_forced(device, ProfileName::forced()?))
    }

    /// The profile `forced` names on an open device, else the device's own.
    pub fn of_device_forced(device: &wgpu::Device, forced: Option<ProfileName>) -> DeviceProfile {
        DeviceProfile::forced(forced, &device.adapter_info(), device.features(), lavapipe::kernels_compile_quickly())
    }

    /// This profile with the scene's arrays read as `arrays` says (tests that
    /// compare the ways); eye tiles need storage buffers.
    pub fn reading(self, arrays: SceneArrays) -> DeviceProfile {
        DeviceProfile { scene_arrays: arrays, eye_tiles: self.eye_tiles && arrays == SceneArrays::Buffers, ..self }
    }

    /// How `scene`'s kernels are tuned here for `workload` before any view
    /// is binned into eye tiles: packets wherever the profile traces them and
    /// the work repays their compile.
    pub fn tuning(&self, scene: &GpuScene, workload: &Workload) -> Tuning {
        Tuning {
            arrays: self.scene_arrays,
            packets: self.packets && workload.traces_packets(self.packet_eye_rays),
            uniform_tree: self.uniform_tree && fits_uniform_tree(scene),
            eye_tiles: false,
            spread: self.spread,
            one_walk_tree: self.one_walk_tree,
            mask_loops: self.mask_loops,
            eye_hits: false,
            workgroups: self.workgroups,
        }
    }

    /// One line for users: which profile, whether `GLINT_PROFILE` chose it,
    /// and on lavapipe which kernels.
    pub fn describe(&self) -> String {
        let forced = if self.forced { format!(", forced by {PROFILE_ENV}={}", self.name) } else { String::new() };
        match self.kernels {
            Some(kernels) => format!("{} profile{forced} ({kernels})", self.name),
            None => format!("{} profile{forced}", self.name),
        }
    }
}

fn is_lavapipe(info: &wgpu::AdapterInfo) -> bool {
    info.name.contains("llvmpipe")
}

impl Workload {
    /// Readies the driver for this work before the process's first device is
    /// made (the viewer's, which eframe makes; `Gpu::for_workload` calls it
    /// for its own): checks `GLINT_PROFILE`, and asks lavapipe for the kernels
    /// that serve the work best. Only the first call chooses.
    pub fn prepare_driver(&self) -> Result<(), GpuError> {
        ProfileName::forced()?;
        lavapipe::prepare(self);
        Ok(())
    }
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
            planes: (0, 0),
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
                name: ProfileName::Lavapipe,
                forced: false,
                kernels: Some(CompiledKernels { quick: false, vector_bits: Some(bits) }),
                scene_arrays: SceneArrays::Buffers,
                packets: true,
                packet_eye_rays: PACKET_EYE_RAYS,
                uniform_tree: true,
                eye_tiles: true,
                resolves_on_host: true,
                spread: true,
                one_walk_tree: true,
                mask_loops: true,
                workgroups: WorkgroupSizes::LAVAPIPE,
            };
            assert_eq!(optimised, want);
            assert_eq!(optimised.tuning(&empty_scene(), &Workload::UNDESCRIBED), Tuning { eye_tiles: false, ..Tuning::LAVAPIPE });
            let quick = DeviceProfile::of(&lavapipe(bits), wgpu::Features::SUBGROUP, true);
            let want = DeviceProfile {
                kernels: Some(CompiledKernels { quick: true, vector_bits: Some(bits) }),
                scene_arrays: SceneArrays::Textures,
                eye_tiles: false,
                ..want
            };
            assert_eq!(quick, want);
            let packets = |workload: Workload| optimised.tuning(&empty_scene(), &workload).packets;
            assert!(!packets(Workload::render(512 * 512, 512 * 512, true)), "a small render's packets do not repay their compile");
            assert!(packets(Workload::render(PACKET_EYE_RAYS, PACKET_EYE_RAYS, true)) && packets(Workload::interactive(false)));
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
                    name: ProfileName::Plain,
                    forced: false,
                    kernels: None,
                    scene_arrays: SceneArrays::Buffers,
                    packets: false,
                    packet_eye_rays: 0,
                    uniform_tree: false,
                    eye_tiles: false,
                    resolves_on_host: false,
                    spread: false,
                    one_walk_tree: false,
                    mask_loops: false,
                    workgroups: WorkgroupSizes::PLAIN,
                };
                assert_eq!(profile, plain, "{name}, quick kernels asked: {quick_kernels}");
                for workload in [Workload::UNDESCRIBED, Workload::interactive(false), Workload::render(u64::MAX, u64::MAX, true)] {
                    assert_eq!(profile.tuning(&empty_scene(), &workload), Tuning::PLAIN, "{name}: the lecture's code, one ray at a time");
                }
                assert_eq!(profile.describe(), "plain profile");
            }
        }
    }

    #[test]
    fn a_gpu_whose_subgroups_fit_eye_tiles_walks_them_in_packets() {
        let small_groups = adapter("a GPU of 8-lane SIMD groups", wgpu::DeviceType::IntegratedGpu, 8);
        let profile = DeviceProfile::of(&small_groups, wgpu::Features::SUBGROUP, true);
        assert!(profile.eye_tiles && profile.packets && profile.spread, "{profile:?}");
        assert!(profile.tuning(&empty_scene(), &Workload::render(1, 1, false)).packets, "eye tiles repay packets at once");
        assert!(!profile.uniform_tree && !profile.one_walk_tree && !profile.mask_loops && profile.scene_arrays == SceneArrays::Buffers);
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
    fn a_forced_profile_makes_its_choices_on_any_adapter() {
        let lavapipe = lavapipe(128);
        let plain = DeviceProfile::forced(Some(ProfileName::Plain), &lavapipe, wgpu::Features::SUBGROUP, false);
        assert_eq!(plain.tuning(&empty_scene(), &Workload::UNDESCRIBED), Tuning::PLAIN, "what every GPU of wide SIMD groups runs");
        assert_eq!((plain.name, plain.forced, plain.eye_tiles), (ProfileName::Plain, true, false));
        assert_eq!(plain.describe(), "plain profile, forced by GLINT_PROFILE=plain (optimised kernels, 128 bits)");
        assert!(plain.resolves_on_host, "where a profile resolves is the adapter's");
        let own = DeviceProfile::of(&lavapipe, wgpu::Features::SUBGROUP, false);
        assert_eq!(DeviceProfile::forced(Some(ProfileName::Lavapipe), &lavapipe, wgpu::Features::SUBGROUP, false), DeviceProfile { forced: true, ..own });
        assert_eq!(DeviceProfile::forced(None, &lavapipe, wgpu::Features::SUBGROUP, false), own);
        let quick = DeviceProfile::forced(Some(ProfileName::Plain), &lavapipe, wgpu::Features::SUBGROUP, true);
        assert_eq!(quick.scene_arrays, SceneArrays::Buffers, "textures are lavapipe's choice");

        let gpu = adapter("NVIDIA GeForce RTX 4090", wgpu::DeviceType::DiscreteGpu, 32);
        let tuned = DeviceProfile::forced(Some(ProfileName::Lavapipe), &gpu, wgpu::Features::SUBGROUP, true);
        assert_eq!(tuned.tuning(&empty_scene(), &Workload::UNDESCRIBED), Tuning { eye_tiles: false, ..Tuning::LAVAPIPE });
        assert!(!tuned.eye_tiles && tuned.kernels.is_none() && !tuned.resolves_on_host, "32-lane groups walk no eye tiles: {tuned:?}");
        assert_eq!(tuned.describe(), "lavapipe profile, forced by GLINT_PROFILE=lavapipe");
    }

    #[test]
    fn profile_names_parse_from_what_glint_profile_may_say() {
        for name in ProfileName::ALL {
            assert_eq!(name.as_str().parse(), Ok(name));
        }
        assert_eq!("fast".parse::<ProfileName>(), Err(()));
        assert_eq!("Plain".parse::<ProfileName>(), Err(()), "names are lower case, as GLINT_ADAPTER's are not");
    }

    #[test]
    fn eye_tiles_need_the_scene_in_storage_buffers() {
        let profile = DeviceProfile::of(&lavapipe(128), wgpu::Features::SUBGROUP, false);
        assert!(!profile.reading(SceneArrays::Textures).eye_tiles);
        assert_eq!(profile.reading(SceneArrays::Buffers), profile);
    }
}
