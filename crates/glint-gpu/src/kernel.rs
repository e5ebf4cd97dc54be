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
