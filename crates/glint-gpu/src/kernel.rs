//! The kernels Glint dispatches: each one file of `shaders/kernels/` and its
//! entry point, and what a scene's specialisation changes in it.

use glint_encoding::specialization::Specialization;

/// The kernels, each one file of `shaders/kernels/` with one entry point.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum Kernel {
    /// The full Whitted render.
    Trace,
    /// The eye ray's hit alone: the data views, AOVs, picking.
    Primary,
    /// The diffuse debug view: the eye ray's hit and its shadow rays.
    Diffuse,
    /// Accumulated samples to display values, for read-back.
    Resolve,
    /// The same, into the viewer's texture.
    Present,
    /// One pixel's ray tree, recorded.
    Probe,
}

/// A file one kernel composes in place of a file of shaders/lib/, declaring
/// the same functions (tests/wgsl.rs checks), as a `StandIn` does for a
/// tuning: whatever the tuning, `kernel` composes `own` wherever a file
/// imports `plain`.
#[derive(Debug, Clone, Copy)]
pub struct KernelStandIn {
    pub kernel: Kernel,
    pub plain: &'static str,
    pub own: &'static str,
}

/// Every kernel's stand-in. The ray tree tells its kernel what it traces
/// through lib/notes.wgsl, which records nothing; the probe kernel records it.
pub const KERNEL_STAND_INS: [KernelStandIn; 1] =
    [KernelStandIn { kernel: Kernel::Probe, plain: "lib/notes.wgsl", own: "kernels/probe_notes.wgsl" }];

impl Kernel {
    pub const ALL: [Kernel; 6] =
        [Kernel::Trace, Kernel::Primary, Kernel::Diffuse, Kernel::Resolve, Kernel::Present, Kernel::Probe];

    pub fn file(self) -> &'static str {
        match self {
            Kernel::Trace => "kernels/trace.wgsl",
            Kernel::Primary => "kernels/primary.wgsl",
            Kernel::Diffuse => "kernels/diffuse.wgsl",
            Kernel::Resolve => "kernels/resolve.wgsl",
            Kernel::Present => "kernels/present.wgsl",
            Kernel::Probe => "kernels/probe.wgsl",
        }
    }

    /// The file this kernel composes for the import of `name`: its own
    /// stand-in ([`KERNEL_STAND_INS`]), else `name` itself.
    pub fn file_for(self, name: &str) -> &str {
        KERNEL_STAND_INS.iter().find(|s| s.kernel == self && s.plain == name).map_or(name, |s| s.own)
    }

    /// Whether the kernel intersects primitives, so that its code depends on
    /// the `Specialization` it is composed for (tests/wgsl.rs checks this
    /// against the files it is made of).
    pub fn is_specialised(self) -> bool {
        matches!(self, Kernel::Trace | Kernel::Primary | Kernel::Diffuse | Kernel::Probe)
    }

    /// What this kernel is compiled for when a scene's kernels are
    /// specialised to `specialization`: only what changes its code, so that
    /// its renders share one pipeline whatever else differs (its tuning:
    /// `Tuning::for_kernel`).
    pub fn compiled_for(self, specialization: Specialization) -> Specialization {
        if self.is_specialised() { specialization } else { Specialization::ALL }
    }

    pub fn entry_point(self) -> &'static str {
        match self {
            Kernel::Trace => "trace_main",
            Kernel::Primary => "primary_main",
            Kernel::Diffuse => "diffuse_main",
            Kernel::Resolve => "resolve_main",
            Kernel::Present => "present_main",
            Kernel::Probe => "probe_main",
        }
    }
}
