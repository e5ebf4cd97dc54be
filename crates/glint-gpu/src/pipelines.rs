//! The kernels' compute pipelines, each created the first time something
//! needs it, for the `Specialization` of the scene it runs on and the
//! `Tuning` the device profile chose for it. A command
//! creates only the pipelines it uses (each creation translates a kernel, tens
//! of milliseconds), and a software rasteriser, which compiles a kernel to CPU
//! code when it first runs (seconds on a fresh machine), compiles only the
//! code the scene needs.

use std::collections::HashMap;
use std::sync::Mutex;

use glint_encoding::specialization::Specialization;

use crate::error_scope::ErrorScope;
use crate::one_line;
use crate::shaders::{Kernel, SceneArrays, ShaderSource};
use crate::tuning::Tuning;
use crate::GpuError;

pub(crate) struct Pipelines {
    device: wgpu::Device,
    source: ShaderSource,
    /// The layout of the kernels bound to a scene (trace, primary).
    scene_layout: wgpu::PipelineLayout,
    built: Mutex<HashMap<(Kernel, Specialization, Tuning), wgpu::ComputePipeline>>,
    /// Held while a pipeline is created, so that two threads needing the same
    /// one (the viewer's warm-up and its first canvas) create it once: a second
    /// pipeline would be compiled again at its first dispatch.
    creating: Mutex<()>,
}

impl Pipelines {
    /// Kernels read from a directory (the viewer's hot reload, possibly
    /// mid-edit) are checked at once, so a broken file is reported before any
    /// frame needs it; the embedded ones are checked by tests/wgsl.rs.
    pub fn new(
        device: &wgpu::Device,
        source: &ShaderSource,
        scene_layout: wgpu::PipelineLayout,
        arrays: SceneArrays,
    ) -> Result<Self, GpuError> {
        if let ShaderSource::Dir(_) = source {
            for kernel in Kernel::ALL {
                source.compose(kernel, Specialization::ALL, Tuning { arrays, ..Tuning::PLAIN })?.validate()?;
            }
        }
        Ok(Self {
            device: device.clone(),
            source: source.clone(),
            scene_layout,
            built: Mutex::new(HashMap::new()),
            creating: Mutex::new(()),
        })
    }

    /// The pipeline of `kernel` for scenes of `specialization` tuned as
    /// `tuning` says, created now if it has not been.
    pub fn get(&self, kernel: Kernel, specialization: Specialization, tuning: Tuning) -> Result<wgpu::ComputePipeline, GpuError> {
        let key = (kernel, kernel.compiled_for(specialization), tuning.for_kernel(kernel));
        let built = || self.built.lock().unwrap_or_else(|e| e.into_inner()).get(&key).cloned();
        if let Some(pipeline) = built() {
            return Ok(pipeline);
        }
        let _creating = self.creating.lock().unwrap_or_else(|e| e.into_inner());
        if let Some(pipeline) = built() {
            return Ok(pipeline);
        }
        let layout = matches!(kernel, Kernel::Trace | Kernel::Primary | Kernel::Diffuse).then_some(&self.scene_layout);
        let pipeline = create_pipeline(&self.device, &self.source, kernel, (key.1, key.2), layout)?;
        self.built.lock().unwrap_or_else(|e| e.into_inner()).insert(key, pipeline.clone());
        Ok(pipeline)
    }

    /// The kernels with a pipeline so far, for any specialisation.
    pub fn kernels(&self) -> Vec<Kernel> {
        let built = self.built();
        Kernel::ALL.into_iter().filter(|&kernel| built.iter().any(|&(built, ..)| built == kernel)).collect()
    }

    /// Each pipeline so far: its kernel, and the specialisation and tuning it
    /// was compiled for.
    pub fn built(&self) -> Vec<(Kernel, Specialization, Tuning)> {
        self.built.lock().unwrap_or_else(|e| e.into_inner()).keys().copied().collect()
    }

    /// Creates the pipelines of `kernels` for `specialization` and `tuning`
    /// that do not exist yet.
    pub fn create(&self, kernels: &[Kernel], specialization: Specialization, tuning: Tuning) -> Result<(), GpuError> {
        kernels.iter().try_for_each(|&kernel| self.get(kernel, specialization, tuning).map(drop))
    }
}

/// Creates the compute pipeline of `kernel` inside an error scope, so a
/// shader that the driver rejects fails here, loudly, instead of later reading
/// back zeros. With `layout` `None` the pipeline derives its own bind group
/// layout.
pub(crate) fn create_pipeline(
    device: &wgpu::Device,
    source: &ShaderSource,
    kernel: Kernel,
    (specialization, tuning): (Specialization, Tuning),
    layout: Option<&wgpu::PipelineLayout>,
) -> Result<wgpu::ComputePipeline, GpuError> {
    let entry = kernel.entry_point();
    // Parsed and validated here, with errors that name file and line; wgpu
    // takes the IR as it is rather than parsing the WGSL again. A browser
    // compiles WGSL text itself: it gets the text tests/webgpu.rs compiles
    // in Chromium.
    let composed = source.compose(kernel, specialization, tuning)?;
    let ir = composed.validate()?;
    #[cfg(not(target_arch = "wasm32"))]
    let shader = wgpu::ShaderSource::Naga(std::borrow::Cow::Owned(ir));
    #[cfg(target_arch = "wasm32")]
    let shader = {
        drop(ir);
        wgpu::ShaderSource::Wgsl(std::borrow::Cow::Owned(composed.source))
    };
    let scope = ErrorScope::push(device);
    let descriptor = wgpu::ShaderModuleDescriptor { label: Some(entry), source: shader };
    let module = match source {
        // SAFETY: the embedded kernels are Glint's own. Every loop in them ends:
        // BVH traversal pushes at most one node per level of a tree whose depth
        // the builder bounds by the stack size, and every other loop runs over a
        // count the host wrote. Every index stays in its array: node and
        // primitive indices come from the same builder and packer. So wgpu's
        // injected loop counters and index clamps, which cost the software
        // rasteriser ~5% of traversal time, are not needed. Kernels read from a
        // directory (the viewer's hot reload, possibly mid-edit) keep them.
        ShaderSource::Embedded => unsafe {
            device.create_shader_module_trusted(descriptor, wgpu::ShaderRuntimeChecks::unchecked())
        },
        ShaderSource::Dir(_) => device.create_shader_module(descriptor),
    };
    let pipeline = device.create_compute_pipeline(&wgpu::ComputePipelineDescriptor {
        label: Some(entry),
        layout,
        module: &module,
        entry_point: Some(entry),
        compilation_options: Default::default(),
        cache: None,
    });
    if let Some(e) = scope.pop() {
        return Err(GpuError::Shader(format!("{entry}: {}", one_line(&e))));
    }
    Ok(pipeline)
}
