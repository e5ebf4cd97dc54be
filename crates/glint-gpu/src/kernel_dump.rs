//! Every kernel as a device is given it, in each tuning a device profile can
//! choose, written out for other WGSL compilers to check (tests/webgpu.rs
//! loads them in a browser's WebGPU) and for readers (`glint kernels --dump`).

use std::path::{Path, PathBuf};

use glint_encoding::specialization::Specialization;

use crate::shaders::{Composed, Kernel, ShaderSource};
use crate::tuning::Tuning;
use crate::GpuError;

/// One kernel in one tuning, specialised to every primitive kind and term.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct KernelVariant {
    pub kernel: Kernel,
    pub tuning: Tuning,
}

impl KernelVariant {
    /// Each kernel in each tuning that changes its code.
    pub fn all() -> Vec<KernelVariant> {
        let mut all: Vec<KernelVariant> = Vec::new();
        for kernel in Kernel::ALL {
            for tuning in Tuning::all().into_iter().map(|t| t.for_kernel(kernel)) {
                let variant = KernelVariant { kernel, tuning };
                if !all.contains(&variant) {
                    all.push(variant);
                }
            }
        }
        all
    }

    /// "primary.buffers-packets-eye-tiles-spread-8x8-8x4.wgsl": the kernel's file, then its tuning.
    pub fn file_name(self) -> String {
        let file = self.kernel.file();
        let stem = file.trim_start_matches("kernels/").trim_end_matches(".wgsl");
        format!("{stem}.{}.wgsl", self.tuning.name())
    }

    pub fn compose(self) -> Result<Composed, GpuError> {
        ShaderSource::Embedded.compose(self.kernel, Specialization::ALL, self.tuning)
    }

    /// Its WGSL as a WebGPU device takes it: with `enable subgroups;` where it
    /// uses them, which WebGPU requires and naga 30 does not parse yet.
    pub fn webgpu_source(self) -> Result<String, GpuError> {
        let source = self.compose()?.source;
        Ok(if self.tuning.needs_subgroups() { format!("enable subgroups;\n{source}") } else { source })
    }
}

/// The list `dump` writes beside the kernels: for each, its file, entry point
/// and whether it needs subgroup operations.
pub const DUMP_MANIFEST: &str = "kernels.json";

/// Writes the WebGPU WGSL of every [`KernelVariant`] into `dir` (made if missing),
/// one file each, and [`DUMP_MANIFEST`]; returns the files written.
pub fn dump(dir: &Path) -> Result<Vec<PathBuf>, GpuError> {
    let failed = |path: &Path, e: std::io::Error| GpuError::Output(format!("{}: {e}", path.display()));
    std::fs::create_dir_all(dir).map_err(|e| failed(dir, e))?;
    let mut written = Vec::new();
    let mut manifest = Vec::new();
    for variant in KernelVariant::all() {
        let path = dir.join(variant.file_name());
        crate::write_atomically(&path, variant.webgpu_source()?.as_bytes()).map_err(|e| failed(&path, e))?;
        manifest.push(serde_json::json!({
            "file": variant.file_name(),
            "entry_point": variant.kernel.entry_point(),
            "subgroups": variant.tuning.needs_subgroups(),
        }));
        written.push(path);
    }
    let path = dir.join(DUMP_MANIFEST);
    let text = serde_json::to_string_pretty(&manifest).map_err(|e| GpuError::Output(e.to_string()))?;
    crate::write_atomically(&path, text.as_bytes()).map_err(|e| failed(&path, e))?;
    written.push(path);
    Ok(written)
}
