//! What a front end is about to do, described for the device: how many
//! samples and eye rays, for a viewer or a one-off command, of a scene rendered
//! before or not. glint-gpu alone turns it into the driver's environment
//! (lavapipe.rs) and the kernels' tuning (`DeviceProfile::tuning`); no front
//! end chooses either.

use crate::lavapipe::{self, QUICK_COMPILE_MAX_SAMPLES};
use crate::profile::ProfileName;
use crate::GpuError;

#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Workload {
    /// Pixel samples in all (pixels × samples per pixel × images); `None`:
    /// frames without end.
    pub samples: Option<u64>,
    /// Eye rays in all (pixels × images); `None`: frames without end.
    pub eye_rays: Option<u64>,
    /// A viewer's, whose user waits for the first image.
    pub interactive: bool,
    /// The scene was rendered on this machine before ([`RenderedScenes`]), so
    /// its kernels are likely compiled already.
    ///
    /// [`RenderedScenes`]: crate::RenderedScenes
    pub rendered_before: bool,
}

impl Workload {
    /// A one-off render of `eye_rays` eye rays and `samples` pixel samples in all.
    pub fn render(eye_rays: u64, samples: u64, rendered_before: bool) -> Workload {
        Workload { samples: Some(samples), eye_rays: Some(eye_rays), interactive: false, rendered_before }
    }

    /// A viewer's frames, of a scene viewed or rendered before or not.
    pub fn interactive(viewed_before: bool) -> Workload {
        Workload { samples: None, eye_rays: None, interactive: true, rendered_before: viewed_before }
    }

    /// Frames without end of a scene rendered before: what a long render
    /// runs, which a benchmark's warm frames stand for.
    pub const REPEATED_FRAMES: Workload = Workload { samples: None, eye_rays: None, interactive: false, rendered_before: true };

    /// Work no front end described (`Gpu::new`, `Renderer::new`): optimised
    /// kernels at the width Glint asks lavapipe for, and packets wherever the
    /// profile traces them.
    pub(crate) const UNDESCRIBED: Workload = Workload { samples: Some(0), eye_rays: None, interactive: false, rendered_before: true };

    /// Readies the driver for this work before the process's first device is
    /// made (the viewer's, which eframe makes; `Gpu::for_workload` calls it
    /// for its own): checks `GLINT_PROFILE`, and asks lavapipe for the kernels
    /// that serve the work best. Only the first call chooses.
    pub fn prepare_driver(&self) -> Result<(), GpuError> {
        ProfileName::forced()?;
        lavapipe::prepare(self);
        Ok(())
    }

    /// Whether lavapipe should compile this work's kernels without LLVM's
    /// optimisation passes: a first viewing, or a small render of a scene not
    /// rendered before (docs/decisions/030-quick-kernels.md, 047). A scene
    /// rendered before is likely rendered again, and with optimised kernels
    /// Mesa's cache then holds the kernels that run fastest.
    pub(crate) fn quick_kernels(&self) -> bool {
        !self.rendered_before && (self.interactive || self.samples.is_some_and(|s| s <= QUICK_COMPILE_MAX_SAMPLES))
    }

    /// The samples that choose lavapipe's SIMD width (`lavapipe::width_for`):
    /// a viewer's open-ended frames never choose the long renders' width.
    pub(crate) fn samples_for_width(&self) -> u64 {
        if self.interactive { 0 } else { self.samples.unwrap_or(u64::MAX) }
    }

    /// Whether the primary kernel's packets, on a profile that traces them
    /// from `packet_eye_rays` eye rays on, repay their compile for this work.
    pub(crate) fn traces_packets(&self, packet_eye_rays: u64) -> bool {
        self.eye_rays.is_none_or(|rays| rays >= packet_eye_rays)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::lavapipe::{width_for, LAVAPIPE_WIDTH, LONG_RENDER_MIN_SAMPLES};

    #[test]
    fn quick_kernels_only_for_first_viewings_and_small_renders_of_new_scenes() {
        assert!(Workload::render(512 * 512, 512 * 512, false).quick_kernels());
        assert!(Workload::render(1, QUICK_COMPILE_MAX_SAMPLES, false).quick_kernels());
        assert!(!Workload::render(1, QUICK_COMPILE_MAX_SAMPLES + 1, false).quick_kernels());
        assert!(!Workload::render(64 * 64, 64 * 64, true).quick_kernels());
        assert!(Workload::interactive(false).quick_kernels() && !Workload::interactive(true).quick_kernels());
        assert!(!Workload::REPEATED_FRAMES.quick_kernels() && !Workload::UNDESCRIBED.quick_kernels());
    }

    #[test]
    fn the_long_renders_width_for_long_renders_and_repeated_frames_alone() {
        let width = |w: Workload| width_for(w.samples_for_width(), w.quick_kernels());
        assert_eq!(width(Workload::render(1, LONG_RENDER_MIN_SAMPLES, true)), width_for(u64::MAX, false));
        assert_eq!(width(Workload::REPEATED_FRAMES), width_for(LONG_RENDER_MIN_SAMPLES, false), "a benchmark times a long render's kernels");
        assert_eq!(width(Workload::render(1, LONG_RENDER_MIN_SAMPLES - 1, true)), LAVAPIPE_WIDTH);
        assert_eq!(width(Workload::interactive(true)), LAVAPIPE_WIDTH, "a viewer's frames are open-ended");
        assert_eq!(width(Workload::UNDESCRIBED), LAVAPIPE_WIDTH);
    }

    #[test]
    fn packets_where_they_repay_their_compile() {
        assert!(!Workload::render(999, 999, true).traces_packets(1000));
        assert!(Workload::render(1000, 1000, false).traces_packets(1000));
        for open_ended in [Workload::interactive(false), Workload::REPEATED_FRAMES, Workload::UNDESCRIBED] {
            assert!(open_ended.traces_packets(u64::MAX), "{open_ended:?}");
        }
    }
}
