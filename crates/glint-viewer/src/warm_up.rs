//! The start-up's kernels and scene brought together off the UI thread, so
//! that the first canvas's trace kernel compiles while the window starts
//! (`Kernels::warm_up`): the UI thread takes the two jobs' results only at a
//! frame, and its first frames wait for the UI's own shaders to compile.

use std::sync::{Arc, Mutex};

use glint_encoding::gpu_types::View;
use glint_scene::Scene;

use crate::engine::Kernels;

/// Handed to the first compile and the first load; whichever finishes second
/// starts the warm-up.
#[derive(Clone)]
pub(crate) struct WarmUp {
    /// The view the viewer opens in, and the samples per pixel it traces
    /// (a one-sample Whitted image may compile the primary kernel too).
    view: View,
    spp: u32,
    parts: Arc<Mutex<Parts>>,
}

#[derive(Default)]
struct Parts {
    kernels: Option<Arc<Kernels>>,
    scene: Option<Scene>,
}

impl WarmUp {
    pub fn new(view: View, spp: u32) -> Self {
        Self { view, spp, parts: Arc::default() }
    }

    pub fn kernels(&self, kernels: &Arc<Kernels>) {
        self.offer(|parts| parts.kernels = Some(Arc::clone(kernels)));
    }

    /// The scene as the viewer shows it first (frame 0 of an animation).
    pub fn scene(&self, scene: &Scene) {
        let mut scene = scene.clone();
        scene.set_frame(0);
        self.offer(|parts| parts.scene = Some(scene));
    }

    fn offer(&self, put: impl FnOnce(&mut Parts)) {
        let mut parts = self.parts.lock().expect("never poisoned");
        put(&mut parts);
        let (Some(kernels), Some(scene)) = (&parts.kernels, &parts.scene) else { return };
        let (kernels, scene) = (Arc::clone(kernels), scene.clone());
        *parts = Parts::default();
        // A browser page has no second thread to compile on.
        if cfg!(target_arch = "wasm32") {
            return;
        }
        let (view, spp) = (self.view, self.spp);
        std::thread::Builder::new()
            .name("glint warm-up".into())
            // A failure is the first canvas's too, made of the same scene and
            // kernels, and reported when that one fails.
            .spawn(move || drop(kernels.warm_up(&scene, view, spp)))
            .expect("the OS can start a thread");
    }
}
