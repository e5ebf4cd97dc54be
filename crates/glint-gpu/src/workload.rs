//! What a front end is about to do, described for the device: how many
//! samples and eye rays, for a viewer or a one-off command, of a scene rendered
//! before or not. glint-gpu alone turns it into the driver's environment
//! (lavapipe.rs) and the kernels' tuning (`DeviceProfile::tuning`); no front
//! end chooses either.

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

    /// Whether the primary kernel's packets, on a profile that traces them
    /// from `packet_eye_rays` eye rays on, repay their compile for this work.
    pub(crate) fn traces_packets(&self, packet_eye_rays: u64) -> bool {
        self.eye_rays.is_none_or(|rays| rays >= packet_eye_rays)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn packets_where_they_repay_their_compile() {
        assert!(!Workload::render(999, 999, true).traces_packets(1000));
        assert!(Workload::render(1000, 1000, false).traces_packets(1000));
        for open_ended in [Workload::interactive(false), Workload::REPEATED_FRAMES, Workload::UNDESCRIBED] {
            assert!(open_ended.traces_packets(u64::MAX), "{open_ended:?}");
        }
    }
}
