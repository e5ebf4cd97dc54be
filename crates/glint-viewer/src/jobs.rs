//! Work that takes longer than a frame (compiling kernels, loading a scene,
//! building and uploading it) runs on its own thread; its result comes back
//! through a channel and wakes the UI. A browser page has one thread: there
//! the job runs at once, and its result comes back the same way.

use std::path::PathBuf;
use std::sync::mpsc::{channel, Receiver, Sender};

use glint_gpu::probe::Prober;
use glint_gpu::GpuError;
use glint_scene::{LoadError, Scene};

use std::sync::Arc;

use crate::engine::{Canvas, CanvasKey, Kernels};

/// A finished background job.
pub(crate) enum Job {
    Compiled { result: Result<Arc<Kernels>, GpuError>, fallback_error: Option<GpuError> },
    Loaded { generation: u64, path: PathBuf, reload: bool, result: Result<Scene, LoadError> },
    Prepared { key: CanvasKey, result: Result<Box<Canvas>, GpuError> },
    ProberCompiled { kernels: Arc<Kernels>, result: Result<Prober, GpuError> },
}

pub struct Jobs<T> {
    tx: Sender<T>,
    rx: Receiver<T>,
    ctx: egui::Context,
}

impl<T: Send + 'static> Jobs<T> {
    pub fn new(ctx: egui::Context) -> Self {
        let (tx, rx) = channel();
        Self { tx, rx, ctx }
    }

    /// Runs `job` on a new thread; its result arrives in `finished`.
    #[cfg(target_arch = "wasm32")]
    pub fn spawn(&self, _name: &str, job: impl FnOnce() -> T + Send + 'static) {
        let _ = self.tx.send(job());
        self.ctx.request_repaint();
    }

    /// Runs `job` on a new thread; its result arrives in `finished`.
    #[cfg(not(target_arch = "wasm32"))]
    pub fn spawn(&self, name: &str, job: impl FnOnce() -> T + Send + 'static) {
        let (tx, ctx) = (self.tx.clone(), self.ctx.clone());
        std::thread::Builder::new()
            .name(format!("glint {name}"))
            .spawn(move || {
                // The receiver lives as long as the app; after that nobody waits.
                let _ = tx.send(job());
                ctx.request_repaint();
            })
            .expect("the OS can start a thread");
    }

    /// The results that arrived since the last call.
    pub fn finished(&self) -> Vec<T> {
        self.rx.try_iter().collect()
    }
}
