//! The kernels and where their WGSL comes from: compiling in the background,
//! watching a shader folder and compiling again when it changes. A broken
//! shader keeps the last good kernels running.

use std::sync::Arc;

use glint_gpu::shaders::{ShaderSource, SOURCES};
use glint_gpu::GpuError;

use crate::one_line;
use crate::engine::Kernels;
use crate::jobs::{Job, Jobs};
use crate::warm_up::WarmUp;
use crate::watch::Watch;

pub(crate) struct Shaders {
    device: wgpu::Device,
    queue: wgpu::Queue,
    source: ShaderSource,
    /// Watches a shader folder; built-in shaders never change.
    watch: Option<Watch>,
    /// The last kernels that compiled.
    pub kernels: Option<Arc<Kernels>>,
    pub compiling: bool,
    /// The files changed while compiling: compile once more when done.
    compile_again: bool,
    /// Takes the first kernels compiled.
    warm_up: Option<WarmUp>,
}

impl Shaders {
    pub fn new(device: wgpu::Device, queue: wgpu::Queue, source: ShaderSource, warm_up: WarmUp) -> Self {
        let watch = match &source {
            ShaderSource::Dir(dir) => {
                let files = SOURCES.iter().map(|f| dir.join(f)).collect();
                Some(Watch::new(files))
            }
            ShaderSource::Embedded => None,
        };
        Self { device, queue, source, watch, kernels: None, compiling: false, compile_again: false, warm_up: Some(warm_up) }
    }

    pub fn is_watched(&self) -> bool {
        self.watch.is_some()
    }

    /// True once after a watched shader file changed.
    pub fn changed(&mut self) -> bool {
        self.watch.as_mut().is_some_and(Watch::changed)
    }

    pub fn start_compile(&mut self, jobs: &Jobs<Job>) {
        if self.compiling {
            self.compile_again = true;
            return;
        }
        self.compiling = true;
        let (device, queue, source) = (self.device.clone(), self.queue.clone(), self.source.clone());
        let first = self.kernels.is_none();
        let warm_up = self.warm_up.take();
        jobs.spawn("shaders", move || {
            let (result, fallback_error) = match Kernels::compile(&device, &queue, &source) {
                // A broken shader file at start-up still gives a working viewer.
                Err(e) if first && matches!(source, ShaderSource::Dir(_)) => (Kernels::compile(&device, &queue, &ShaderSource::Embedded), Some(e)),
                result => (result, None),
            };
            let result = result.map(Arc::new);
            if let (Ok(kernels), Some(warm_up)) = (&result, warm_up) {
                warm_up.kernels(kernels);
            }
            Job::Compiled { result, fallback_error }
        });
    }

    /// Takes a finished compile, reporting into `error`; true when it gave new kernels.
    pub fn finish_compile(
        &mut self,
        result: Result<Arc<Kernels>, GpuError>,
        fallback_error: Option<GpuError>,
        error: &mut Option<String>,
        jobs: &Jobs<Job>,
    ) -> bool {
        self.compiling = false;
        let compiled = match result {
            Ok(kernels) => {
                self.kernels = Some(kernels);
                *error = fallback_error.map(|e| one_line(format!("{e} (using the built-in shaders)")));
                true
            }
            Err(e) => {
                *error = Some(one_line(e));
                false
            }
        };
        if std::mem::take(&mut self.compile_again) {
            self.start_compile(jobs);
        }
        compiled
    }
}
