//! `glint view --first-image`: the viewer's start-up, measured. It closes the
//! window once the first complete image (one sample per pixel) is shown, or a
//! problem is, and reports how long that took from a given start: window,
//! device, scene, BVH, the kernels' compile and the first sample, which is what
//! a new user waits for (docs/performance.md).

use std::sync::{Arc, Mutex};
use std::time::Duration;

use web_time::Instant;
/// What the first image came to.
#[derive(Debug, Clone, PartialEq, Eq)]
pub enum FirstImage {
    /// Shown `after` this long from the start, by `adapter`.
    Shown { after: Duration, adapter: Box<wgpu::AdapterInfo> },
    /// The scene could not be loaded: its error.
    SceneError(String),
    /// The kernels or the device failed: the errors shown.
    Failed(String),
}

/// Watches the viewer for its first image; the caller keeps a clone to read
/// the outcome once the window has closed.
#[derive(Clone)]
pub struct FirstImageWatch {
    start: Instant,
    outcome: Arc<Mutex<Option<FirstImage>>>,
}

impl FirstImageWatch {
    pub fn new(start: Instant) -> Self {
        Self { start, outcome: Arc::new(Mutex::new(None)) }
    }

    /// The outcome, once there is one.
    pub fn outcome(&self) -> Option<FirstImage> {
        self.outcome.lock().expect("never poisoned").clone()
    }

    /// Records the outcome of this frame, if it has one: true when the window
    /// should close. `shown` waits for the device (`adapter`) to finish the
    /// image first.
    pub(crate) fn check(&self, scene_error: Option<&str>, other_errors: &[String], adapter: &wgpu::AdapterInfo, shown: impl FnOnce() -> bool) -> bool {
        if self.outcome().is_some() {
            return false;
        }
        let outcome = if let Some(e) = scene_error {
            FirstImage::SceneError(e.to_string())
        } else if !other_errors.is_empty() {
            FirstImage::Failed(other_errors.join("; "))
        } else if shown() {
            FirstImage::Shown { after: self.start.elapsed(), adapter: Box::new(adapter.clone()) }
        } else {
            return false;
        };
        *self.outcome.lock().expect("never poisoned") = Some(outcome);
        true
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_first_outcome_is_kept_and_errors_come_before_the_image() {
        let gpu = wgpu::AdapterInfo { name: "gpu".into(), ..wgpu::AdapterInfo::new(wgpu::DeviceType::Cpu, wgpu::Backend::Noop) };
        let watch = FirstImageWatch::new(Instant::now());
        assert!(!watch.check(None, &[], &gpu, || false), "nothing shown yet");
        assert_eq!(watch.outcome(), None);
        let scene = "scene.toml:3: unknown key".to_string();
        assert!(watch.check(Some(scene.as_str()), &["a GPU error".into()], &gpu, || true));
        assert_eq!(watch.outcome(), Some(FirstImage::SceneError(scene)));
        assert!(!watch.check(None, &[], &gpu, || true), "decided once");

        let watch = FirstImageWatch::new(Instant::now());
        assert!(watch.check(None, &["shader: x".into(), "GPU: y".into()], &gpu, || true));
        assert_eq!(watch.outcome(), Some(FirstImage::Failed("shader: x; GPU: y".into())));

        let watch = FirstImageWatch::new(Instant::now());
        assert!(watch.check(None, &[], &gpu, || true));
        assert!(matches!(watch.outcome(), Some(FirstImage::Shown { adapter, .. }) if adapter.name == "gpu"));
    }
}
