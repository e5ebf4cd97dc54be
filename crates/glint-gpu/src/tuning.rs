//! How a kernel is tuned for the device: the device's half of what a kernel
//! is compiled for (glint-encoding's `Specialization` is the scene's half). The
//! device profile chooses it (profile.rs); every tuning traces the same bits
//! (tests/packet.rs, tests/scene_arrays.rs, tests/spread.rs). A tuning
//! composes the files of shaders/lib/ as the lecture reads them, except where
//! it puts a variant of shaders/fast/ in a file's place ([`STAND_INS`]).

use glint_encoding::gpu_types::{GpuScene, UNIFORM_TREE_RECORDS};

use crate::kernel::Kernel;

/// Its choices are glint-gpu's alone to make, from the device's profile and
/// the work a front end describes: outside the crate they can be read, never
/// set. The `variants` feature lets tests set each one, to hold each variant
/// to the plain code's bits; no front end enables it.
///
/// ```compile_fail,E0616
/// fn retune(tuning: &mut glint_gpu::Tuning) {
///     tuning.packets = false;
/// }
/// ```
///
/// ```compile_fail,E0616
/// fn retune(scene: &mut glint_gpu::SceneBuffers) {
///     scene.tuning = glint_gpu::Tuning::PLAIN;
/// }
/// ```
///
/// ```compile_fail,E0451
/// let tuning = glint_gpu::Tuning { packets: true, ..glint_gpu::Tuning::PLAIN };
/// ```
///
/// What a front end may do: read them.
///
/// ```
/// fn traces_packets(scene: &glint_gpu::SceneBuffers) -> bool {
///     scene.tuning().packets()
/// }
/// ```
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub struct Tuning {
    /// How the kernels read the scene's arrays (one way per renderer: its
    /// bind group layout holds that kind of binding).
    pub(crate) arrays: SceneArrays,
    /// The primary kernel traces the eye rays of 2×2 blocks of pixels as ray
    /// packets: faster per ray, slower to compile.
    pub(crate) packets: bool,
    /// The kernels read the BVH's records and grids from uniform buffers,
    /// which the scene's tree fits ([`fits_uniform_tree`]). The storage
    /// buffers hold the tree too, for kernels tuned without this.
    pub(crate) uniform_tree: bool,
    /// The primary kernel's packets take their eye rays' primitives from their
    /// tile's list (`eye_tiles`) instead of the BVH: set by the renderer when
    /// it has binned the scene for the view, on a device whose profile allows it.
    pub(crate) eye_tiles: bool,
    /// A dispatch's workgroups and a workgroup's invocations take their places
    /// in the order of shaders/fast/spread.wgsl (for lavapipe's threads and
    /// SIMD groups, and the eye tiles' SIMD groups), else in row order.
    pub(crate) spread: bool,
    /// The trace and probe kernels walk the ray tree as one loop whose step is
    /// one query, a ray of the tree or a shadow ray, through one call of the
    /// BVH walk (shaders/fast/ray_tree.wgsl), which lavapipe compiles once.
    pub(crate) one_walk_tree: bool,
    /// Loops over a few cases (a 2×2 block's eye rays, a surface's reflected
    /// and refracted ray, the kinds of rays counted) step through a bit mask
    /// of the cases, a count the compiler does not know, so that lavapipe
    /// compiles their bodies once (shaders/fast/eye_rays.wgsl, push_rays.wgsl
    /// and flush_counts.wgsl; docs/decisions/057-loops-over-bit-masks.md).
    pub(crate) mask_loops: bool,
    /// The trace kernel takes its eye rays' hits from the accumulation
    /// buffer, where the primary kernel's eye tiles left them, instead of
    /// walking the BVH for them (shaders/fast/ray_tree.wgsl;
    /// docs/decisions/059-eye-hits-from-the-eye-tiles.md). Set by
    /// [`Tuning::for_kernel`] alone, where the view has eye tiles and the
    /// tree is walked once.
    pub(crate) eye_hits: bool,
    /// The workgroups of the kernels that trace row bands.
    pub(crate) workgroups: WorkgroupSizes,
}

/// The invocations of a workgroup, across and down, of the kernels that trace
/// row bands: trace and diffuse, and primary (as wide, its own height). The
/// prelude declares them (`Tuning::wgsl`) and the host dispatches by them.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub struct WorkgroupSizes {
    pub width: u32,
    pub band_height: u32,
    pub primary_height: u32,
}

impl WorkgroupSizes {
    /// 64 invocations: two 32-lane warps or one 64-lane wavefront, the usual
    /// size of a GPU's two-dimensional compute workgroups.
    pub const PLAIN: WorkgroupSizes = WorkgroupSizes { width: 8, band_height: 8, primary_height: 8 };
    /// lavapipe's: its primary kernel's are half as tall, since with packets
    /// each of their invocations traces two rows.
    pub const LAVAPIPE: WorkgroupSizes = WorkgroupSizes { width: 8, band_height: 8, primary_height: 4 };

    pub fn band(self) -> [u32; 2] {
        [self.width, self.band_height]
    }

    pub fn primary(self) -> [u32; 2] {
        [self.width, self.primary_height]
    }

    /// "8x8-8x4": the band kernels' size, then the primary kernel's.
    fn name(self) -> String {
        let [[a, b], [c, d]] = [self.band(), self.primary()];
        format!("{a}x{b}-{c}x{d}")
    }
}

/// A file of shaders/fast/ that a tuning composes in place of one of
/// shaders/lib/, declaring the same functions (tests/wgsl.rs checks).
#[derive(Debug, Clone, Copy)]
pub struct StandIn {
    pub plain: &'static str,
    pub fast: &'static str,
    /// Whether a tuning composes `fast` in place of `plain`.
    pub when: fn(Tuning) -> bool,
}

/// Every stand-in; the first that a tuning asks for takes the plain file's place.
pub const STAND_INS: [StandIn; 10] = [
    StandIn { plain: "lib/scene_arrays.wgsl", fast: "fast/scene_textures.wgsl", when: |t| t.arrays == SceneArrays::Textures },
    StandIn { plain: "lib/bvh_records.wgsl", fast: "fast/uniform_tree.wgsl", when: |t| t.uniform_tree },
    StandIn { plain: "lib/bvh_records.wgsl", fast: "fast/bvh_textures.wgsl", when: |t| t.arrays == SceneArrays::Textures },
    StandIn { plain: "lib/eye_block.wgsl", fast: "fast/eye_tiles.wgsl", when: |t| t.packets && t.eye_tiles },
    StandIn { plain: "lib/eye_block.wgsl", fast: "fast/eye_bvh.wgsl", when: |t| t.packets },
    StandIn { plain: "lib/band_order.wgsl", fast: "fast/spread.wgsl", when: |t| t.spread },
    StandIn { plain: "lib/ray_tree.wgsl", fast: "fast/ray_tree.wgsl", when: |t| t.one_walk_tree },
    StandIn { plain: "lib/eye_rays.wgsl", fast: "fast/eye_rays.wgsl", when: |t| t.mask_loops },
    StandIn { plain: "lib/push_rays.wgsl", fast: "fast/push_rays.wgsl", when: |t| t.mask_loops },
    StandIn { plain: "lib/flush_counts.wgsl", fast: "fast/flush_counts.wgsl", when: |t| t.mask_loops },
];

impl Tuning {
    /// One ray at a time through the BVH, everything in storage buffers: the
    /// code as the lecture reads it, and what any device runs.
    pub const PLAIN: Tuning = Tuning {
        arrays: SceneArrays::Buffers,
        packets: false,
        uniform_tree: false,
        eye_tiles: false,
        spread: false,
        one_walk_tree: false,
        mask_loops: false,
        eye_hits: false,
        workgroups: WorkgroupSizes::PLAIN,
    };

    pub fn arrays(self) -> SceneArrays {
        self.arrays
    }

    pub fn packets(self) -> bool {
        self.packets
    }

    pub fn uniform_tree(self) -> bool {
        self.uniform_tree
    }

    pub fn eye_tiles(self) -> bool {
        self.eye_tiles
    }

    pub fn spread(self) -> bool {
        self.spread
    }

    pub fn one_walk_tree(self) -> bool {
        self.one_walk_tree
    }

    pub fn mask_loops(self) -> bool {
        self.mask_loops
    }

    pub fn eye_hits(self) -> bool {
        self.eye_hits
    }

    pub fn workgroups(self) -> WorkgroupSizes {
        self.workgroups
    }

    /// This tuning as dispatched where eye tiles cannot be walked: over a
    /// region whose workgroups start off the tiles' corners (a pick's pixel).
    pub fn without_eye_tiles(self) -> Tuning {
        Tuning { eye_tiles: false, ..self }
    }

    /// This tuning as dispatched for a view too crowded to bin into eye
    /// tiles: each eye ray walks the BVH alone.
    pub(crate) fn with_single_eye_rays(self) -> Tuning {
        Tuning { packets: false, eye_tiles: false, ..self }
    }

    /// Every choice of lavapipe's profile at once, eye tiles included: what
    /// tests hold the plain tuning's bits to.
    pub const LAVAPIPE: Tuning = Tuning {
        arrays: SceneArrays::Buffers,
        packets: true,
        uniform_tree: true,
        eye_tiles: true,
        spread: true,
        one_walk_tree: true,
        mask_loops: true,
        eye_hits: false,
        workgroups: WorkgroupSizes::LAVAPIPE,
    };

    /// Every tuning a profile can choose, and every one tests set on
    /// lavapipe (eye tiles only over storage buffers): for tests and dumps of
    /// every kernel.
    pub fn all() -> Vec<Tuning> {
        let mut all = Vec::new();
        for arrays in SceneArrays::ALL {
            for bits in 0..32u32 {
                let [packets, uniform_tree, eye_tiles, spread, one_walk_tree] = [0, 1, 2, 3, 4].map(|b| bits & (1 << b) != 0);
                // Eye tiles hand SIMD groups blocks of one tile in spread order.
                if !eye_tiles || (arrays == SceneArrays::Buffers && spread) {
                    // Both of lavapipe's ways of compiling once come together.
                    let mask_loops = one_walk_tree;
                    all.push(Tuning { arrays, packets, uniform_tree, eye_tiles, spread, one_walk_tree, mask_loops, eye_hits: false, workgroups: WorkgroupSizes::LAVAPIPE });
                }
            }
        }
        // The plain profile's: single rays in row order, or, where subgroups
        // fit, packets in spread order, with or without the view's eye tiles.
        for (packets, eye_tiles, spread) in [(false, false, false), (true, false, true), (true, true, true)] {
            all.push(Tuning { packets, eye_tiles, spread, ..Tuning::PLAIN });
        }
        all
    }

    /// A name for file names: its choices joined by dashes, workgroup sizes
    /// other than the plain ones last ("buffers" alone for the plain tuning).
    pub fn name(self) -> String {
        let arrays = match self.arrays {
            SceneArrays::Buffers => "buffers",
            SceneArrays::Textures => "textures",
        };
        let choices = [
            (self.packets, "packets"),
            (self.uniform_tree, "uniform-tree"),
            (self.eye_tiles, "eye-tiles"),
            (self.spread, "spread"),
            (self.one_walk_tree, "one-walk-tree"),
            (self.mask_loops, "mask-loops"),
            (self.eye_hits, "eye-hits"),
        ];
        let chosen = choices.iter().filter(|(on, _)| *on).map(|(_, name)| name.to_string());
        let workgroups = (self.workgroups != WorkgroupSizes::PLAIN).then(|| self.workgroups.name());
        std::iter::once(arrays.to_string()).chain(chosen).chain(workgroups).collect::<Vec<_>>().join("-")
    }

    /// The file composed for the import of `name`: the stand-in this tuning
    /// asks for, else `name` itself.
    pub fn file(self, name: &str) -> &str {
        STAND_INS.iter().find(|s| s.plain == name && (s.when)(self)).map_or(name, |s| s.fast)
    }

    /// Whether its kernels need the device's subgroup operations.
    pub fn needs_subgroups(self) -> bool {
        self.eye_tiles
    }

    /// What `kernel` is compiled with when a scene's kernels are tuned this
    /// way: only what changes its code, so that its renders share one
    /// pipeline (and one entry of a driver's disk cache) whatever else
    /// differs. Only the primary kernel traces packets, only the trace and
    /// probe kernels walk the ray tree, only the trace kernel's one walk takes
    /// the eye hits the primary kernel's eye tiles found, and only the kernels
    /// that trace row bands have their workgroup sizes.
    pub fn for_kernel(self, kernel: Kernel) -> Tuning {
        match kernel {
            Kernel::Primary => Tuning { eye_tiles: self.eye_tiles && self.packets, one_walk_tree: false, eye_hits: false, ..self },
            Kernel::Diffuse => Tuning { packets: false, eye_tiles: false, one_walk_tree: false, eye_hits: false, ..self },
            Kernel::Trace => {
                let eye_hits = self.eye_tiles && self.packets && self.one_walk_tree;
                Tuning { packets: false, eye_tiles: false, eye_hits, ..self }
            }
            Kernel::Probe => Tuning { packets: false, eye_tiles: false, eye_hits: false, workgroups: WorkgroupSizes::PLAIN, ..self },
            Kernel::Resolve | Kernel::Present => Tuning { arrays: self.arrays, ..Tuning::PLAIN },
        }
    }

    /// The invocations of one workgroup of `kernel`, a kernel that traces row
    /// bands, across and down (its `@workgroup_size`).
    pub fn workgroup_size(self, kernel: Kernel) -> [u32; 2] {
        if kernel == Kernel::Primary { self.workgroups.primary() } else { self.workgroups.band() }
    }

    /// The side of the square block of pixels one invocation of `kernel`
    /// traces: 2 for the primary kernel with packets, else 1.
    pub fn block_side(self, kernel: Kernel) -> u32 {
        if kernel == Kernel::Primary && self.packets { 2 } else { 1 }
    }

    /// The WGSL constants that carry it, appended to a kernel's prelude.
    pub fn wgsl(self) -> String {
        let WorkgroupSizes { width, band_height, primary_height } = self.workgroups;
        format!(
            "const PACKETS: bool = {};\nconst EYE_HITS: bool = {};\n\
             const BAND_WORKGROUP_WIDTH: u32 = {width}u;\nconst BAND_WORKGROUP_HEIGHT: u32 = {band_height}u;\nconst PRIMARY_WORKGROUP_HEIGHT: u32 = {primary_height}u;\n",
            self.packets, self.eye_hits
        )
    }
}

/// Each choice set by hand, for tests that hold each variant to the plain
/// code's bits (the `variants` feature, which only tests enable).
#[cfg(feature = "variants")]
impl Tuning {
    pub fn with_arrays(self, arrays: SceneArrays) -> Tuning {
        Tuning { arrays, ..self }
    }

    pub fn with_packets(self, packets: bool) -> Tuning {
        Tuning { packets, ..self }
    }

    pub fn with_uniform_tree(self, uniform_tree: bool) -> Tuning {
        Tuning { uniform_tree, ..self }
    }

    pub fn with_eye_tiles(self, eye_tiles: bool) -> Tuning {
        Tuning { eye_tiles, ..self }
    }

    pub fn with_spread(self, spread: bool) -> Tuning {
        Tuning { spread, ..self }
    }

    pub fn with_one_walk_tree(self, one_walk_tree: bool) -> Tuning {
        Tuning { one_walk_tree, ..self }
    }

    pub fn with_mask_loops(self, mask_loops: bool) -> Tuning {
        Tuning { mask_loops, ..self }
    }

    pub fn with_workgroups(self, workgroups: WorkgroupSizes) -> Tuning {
        Tuning { workgroups, ..self }
    }
}

/// Whether `scene`'s BVH records and grids fit the uniform buffers of
/// `UNIFORM_TREE_RECORDS` each.
pub fn fits_uniform_tree(scene: &GpuScene) -> bool {
    let records = UNIFORM_TREE_RECORDS as usize;
    scene.nodes.len() <= records && scene.grids.len() <= records
}

impl std::fmt::Display for Tuning {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(match (self.packets, self.eye_tiles) {
            (false, _) => "single eye rays",
            (true, false) => "ray packets",
            (true, true) => "eye tiles",
        })
    }
}

/// How the kernels read the scene's arrays (primitives, BVH records and
/// grids, polygon points): `prim_at` and its siblings, declared alike by
/// shaders/lib/scene_arrays.wgsl and bvh_records.wgsl, or the textures of
/// shaders/fast/, over the same bindings. A renderer reads one way (its bind
/// group layout holds that kind of binding).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum SceneArrays {
    /// Storage buffers: what optimised kernels read fastest. lavapipe fetches
    /// a texel through a call, around which an optimised kernel saves and
    /// restores its registers (docs/decisions/034-scene-textures.md).
    Buffers,
    /// Textures, for kernels compiled without LLVM's optimisation passes (a
    /// first, small render on lavapipe): those keep every value in memory
    /// anyway, and a texel costs them no per-lane bounds branch, as each
    /// component of a storage buffer's load does.
    Textures,
}

impl SceneArrays {
    pub const ALL: [SceneArrays; 2] = [SceneArrays::Buffers, SceneArrays::Textures];
}

#[cfg(test)]
mod tests {
    use super::*;
    use bytemuck::Zeroable;
    use glint_encoding::gpu_bvh::{GpuGrid, GpuNode};

    #[test]
    fn a_tree_that_fits_a_uniform_buffer_is_read_from_one() {
        let mut scene = GpuScene {
            prims: Vec::new(),
            nodes: vec![GpuNode::zeroed(); UNIFORM_TREE_RECORDS as usize],
            grids: vec![GpuGrid::zeroed(); UNIFORM_TREE_RECORDS as usize],
            bvh_root: 0,
            materials: Vec::new(),
            lights: Vec::new(),
            points: Vec::new(),
            light_count: 0,
            planes: (0, 0),
        };
        assert!(fits_uniform_tree(&scene));
        scene.nodes.push(GpuNode::zeroed());
        assert!(!fits_uniform_tree(&scene), "one record too many");
        scene.nodes.pop();
        scene.grids.push(GpuGrid::zeroed());
        assert!(!fits_uniform_tree(&scene), "one grid too many");
        let tuned = Tuning { uniform_tree: true, ..Tuning::PLAIN };
        assert_eq!(tuned.file("lib/bvh_records.wgsl"), "fast/uniform_tree.wgsl");
        assert_eq!(Tuning { arrays: SceneArrays::Textures, ..tuned }.file("lib/bvh_records.wgsl"), "fast/uniform_tree.wgsl");
        assert_eq!(Tuning::PLAIN.file("lib/bvh_records.wgsl"), "lib/bvh_records.wgsl");
    }

    #[test]
    fn the_plain_tuning_composes_the_lecture_files_and_every_stand_in_is_some_tunings() {
        for s in STAND_INS {
            assert!(s.plain.starts_with("lib/") && s.fast.starts_with("fast/"), "{s:?}");
            assert_eq!(Tuning::PLAIN.file(s.plain), s.plain);
            assert!(Tuning::all().iter().any(|t| t.file(s.plain) == s.fast), "no tuning composes {}", s.fast);
        }
    }

    #[test]
    fn only_the_primary_kernel_traces_packets_and_eye_tiles() {
        let fast = Tuning::LAVAPIPE;
        assert_eq!(fast.for_kernel(Kernel::Primary), Tuning { one_walk_tree: false, eye_hits: false, ..fast });
        assert_eq!(fast.block_side(Kernel::Primary), 2);
        let trace = Tuning { uniform_tree: true, spread: true, one_walk_tree: true, mask_loops: true, workgroups: WorkgroupSizes::LAVAPIPE, ..Tuning::PLAIN };
        assert_eq!(fast.for_kernel(Kernel::Trace), Tuning { eye_hits: true, ..trace }, "the trace kernel takes the eye tiles' hits");
        assert_eq!(fast.for_kernel(Kernel::Probe), Tuning { workgroups: WorkgroupSizes::PLAIN, ..trace }, "the probe traces no bands");
        assert_eq!(fast.for_kernel(Kernel::Diffuse), Tuning { one_walk_tree: false, ..trace });
        assert_eq!(fast.for_kernel(Kernel::Trace).block_side(Kernel::Trace), 1);
        assert_eq!(fast.for_kernel(Kernel::Resolve), Tuning::PLAIN);
        let no_packets = Tuning { packets: false, ..fast };
        assert!(!no_packets.for_kernel(Kernel::Primary).eye_tiles, "eye tiles are walked by packets");
        assert_eq!(no_packets.for_kernel(Kernel::Trace), trace, "no eye hits without the tiles' packets");
        assert_eq!(fast.without_eye_tiles().for_kernel(Kernel::Trace), trace, "no eye hits without eye tiles");
        assert_eq!(Tuning { one_walk_tree: false, ..fast }.for_kernel(Kernel::Trace), Tuning { one_walk_tree: false, ..trace }, "only the one walk takes eye hits");
        assert!(!fast.for_kernel(Kernel::Primary).eye_hits && !fast.for_kernel(Kernel::Probe).eye_hits);
        assert_eq!(no_packets.block_side(Kernel::Primary), 1);
    }

    #[test]
    fn the_prelude_declares_the_workgroup_sizes_the_host_dispatches_by() {
        for workgroups in [WorkgroupSizes::PLAIN, WorkgroupSizes::LAVAPIPE] {
            let tuning = Tuning { workgroups, ..Tuning::PLAIN };
            let [[width, band_height], [_, primary_height]] = [tuning.workgroup_size(Kernel::Trace), tuning.workgroup_size(Kernel::Primary)];
            assert_eq!(tuning.workgroup_size(Kernel::Diffuse), [width, band_height]);
            for (name, value) in [("BAND_WORKGROUP_WIDTH", width), ("BAND_WORKGROUP_HEIGHT", band_height), ("PRIMARY_WORKGROUP_HEIGHT", primary_height)] {
                assert!(tuning.wgsl().contains(&format!("const {name}: u32 = {value}u;")), "{}", tuning.wgsl());
            }
        }
        assert_eq!(Tuning { workgroups: WorkgroupSizes::LAVAPIPE, ..Tuning::PLAIN }.name(), "buffers-8x8-8x4");
        assert_eq!(Tuning::PLAIN.name(), "buffers");
    }

    #[test]
    fn every_workgroup_deals_2x2_blocks_and_covers_whole_eye_tiles() {
        use glint_encoding::gpu_types::{EYE_TILE_HEIGHT, EYE_TILE_WIDTH};
        for workgroups in [WorkgroupSizes::PLAIN, WorkgroupSizes::LAVAPIPE] {
            for [across, down] in [workgroups.band(), workgroups.primary()] {
                assert!(across % 2 == 0 && down % 2 == 0, "spread_invocation deals places in 2x2 blocks: {workgroups:?}");
            }
            let [across, down] = workgroups.primary().map(|n| 2 * n);
            assert!(across % EYE_TILE_WIDTH == 0 && down % EYE_TILE_HEIGHT == 0, "a packet workgroup's SIMD groups stay in one tile: {workgroups:?}");
        }
    }
}
