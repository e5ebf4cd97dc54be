//! How much of the image one dispatch traces: one policy for `glint render`,
//! `glint bench` and the viewer. A dispatch should keep the device busy for
//! about a target time, long enough to amortise the submission and short
//! enough that no GPU watchdog fires and progress (or the UI) stays fluid.

use std::time::Duration;

/// The target of a batch render: long bands, few submissions.
pub const BATCH_TARGET: Duration = Duration::from_millis(150);
/// The target of an interactive render: the UI must stay responsive.
pub const INTERACTIVE_TARGET: Duration = Duration::from_millis(30);
/// The target of the viewer's image of a new scene or size: longer bands,
/// fewer frames. Each frame costs a repaint of the window, which on a software
/// rasteriser takes as long as a short band, and the rasteriser shares the CPU
/// with the ray tracer.
pub const NEW_CANVAS_TARGET: Duration = BATCH_TARGET;
/// The target of the viewer's very first image, before which the window shows
/// nothing to interact with: longer still, so that a whole sample takes one or
/// two bands after the one that measures the scene.
pub const FIRST_IMAGE_TARGET: Duration = Duration::from_millis(300);

/// Rows are traced in whole workgroups of this many.
const TILE_ROWS: u32 = 8;
/// The size of the first band, which waits for the kernel's compile and so
/// measures nothing: large, since a band that small would take many to regrow.
const FIRST_BAND_PIXELS: u32 = 64 * 512;

/// Sizes bands from the time the last one took: towards the target in
/// proportion, growing at most twofold per band (at once, for the viewer's
/// first image) and shrinking at once.
#[derive(Debug, Clone, Copy)]
pub struct BandScheduler {
    target: Duration,
    /// Pixels per band, so a size learnt at one image width carries to another.
    pixels: u32,
    /// The next band recorded also waited for its kernel's compile (lavapipe
    /// compiles a kernel at its first dispatch), so it says nothing of a band.
    compiling: bool,
    /// The next band may be sized to the target whatever the last one was.
    grow_at_once: bool,
}

impl BandScheduler {
    /// The bands of a renderer whose kernels have not yet been dispatched:
    /// aimed at `target`, the first band, which the kernel's compile delays,
    /// not learnt from, and so starting larger (a first band learnt from
    /// would shrink to one workgroup of rows and take many bands to regrow).
    pub const fn before_compile(target: Duration) -> Self {
        Self { target, pixels: FIRST_BAND_PIXELS, compiling: true, grow_at_once: false }
    }

    /// The bands of the viewer's image on a new canvas.
    pub const fn new_canvas() -> Self {
        Self::before_compile(NEW_CANVAS_TARGET)
    }

    /// The bands of the viewer's first image, whose kernel was compiled while
    /// the window started (the viewer's warm-up): the first band measures the
    /// scene, and the next is sized from it to the target at once. (Had the
    /// first band waited for a compile after all, the next would be small and
    /// the one after it sized right.)
    pub const fn first_image() -> Self {
        Self { target: FIRST_IMAGE_TARGET, pixels: FIRST_BAND_PIXELS, compiling: false, grow_at_once: true }
    }

    /// Aims the bands from now on at `target`, starting from what was learnt,
    /// growing twofold at most; at the target they already have, it changes
    /// only that.
    pub fn retarget(&mut self, target: Duration) {
        self.pixels = (f64::from(self.pixels) * target.as_secs_f64() / self.target.as_secs_f64()) as u32;
        self.target = target;
        self.grow_at_once = false;
    }

    /// The rows of the next band of an image `width` wide with `left` rows to
    /// go: whole workgroups of rows, at least one workgroup, at most `left`.
    pub fn rows(&self, width: u32, left: u32) -> u32 {
        let rows = (self.pixels / width.max(1)) / TILE_ROWS * TILE_ROWS;
        rows.max(TILE_ROWS).min(left).max(1)
    }

    /// Learns from a band of `rows` rows of an image `width` wide that kept
    /// the device busy for `took`.
    pub fn record(&mut self, width: u32, rows: u32, took: Duration) {
        if std::mem::take(&mut self.compiling) {
            return;
        }
        let pixels = f64::from(rows) * f64::from(width);
        let ideal = pixels * self.target.as_secs_f64() / took.as_secs_f64().max(1e-6);
        let growth = if self.grow_at_once { f64::INFINITY } else { 2.0 };
        let next = ideal.min(f64::from(self.pixels) * growth).min(f64::from(u32::MAX));
        self.pixels = (next as u32).max(TILE_ROWS * width.max(1));
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    const WIDTH: u32 = 512;

    /// A scheduler past its compile band, which is not learnt from.
    fn compiled(target: Duration) -> BandScheduler {
        let mut s = BandScheduler::before_compile(target);
        s.record(WIDTH, s.rows(WIDTH, 10_000), Duration::from_secs(1));
        s
    }

    /// Bands of a device that traces `per_row` per row settle near the target.
    fn settle(per_row: Duration, target: Duration) -> u32 {
        let mut s = compiled(target);
        for _ in 0..20 {
            let rows = s.rows(WIDTH, 100_000);
            s.record(WIDTH, rows, per_row * rows);
        }
        s.rows(WIDTH, 100_000)
    }

    #[test]
    fn bands_converge_to_the_target_time_in_whole_workgroups() {
        let rows = settle(Duration::from_micros(500), BATCH_TARGET);
        assert_eq!(rows % TILE_ROWS, 0);
        assert!((288..=304).contains(&rows), "150 ms at 0.5 ms a row is 300 rows, got {rows}");
        let rows = settle(Duration::from_micros(500), INTERACTIVE_TARGET);
        assert!((56..=64).contains(&rows), "30 ms is 60 rows, got {rows}");
    }

    #[test]
    fn a_new_canvas_starts_larger_aims_longer_and_is_retargeted_at_once() {
        let mut s = BandScheduler::new_canvas();
        let first = s.rows(WIDTH, 10_000);
        assert_eq!(first, FIRST_BAND_PIXELS / WIDTH);
        s.record(WIDTH, first, Duration::from_secs(1));
        assert_eq!(s.rows(WIDTH, 10_000), first, "the band that waited for the compile is not learnt from");
        for _ in 0..20 {
            let rows = s.rows(WIDTH, 100_000);
            s.record(WIDTH, rows, Duration::from_micros(500) * rows);
        }
        assert!((288..=304).contains(&s.rows(WIDTH, 100_000)), "150 ms at 0.5 ms a row");
        s.retarget(INTERACTIVE_TARGET);
        assert!((56..=64).contains(&s.rows(WIDTH, 100_000)), "30 ms at 0.5 ms a row, from the next band on");
    }

    #[test]
    fn the_first_image_learns_from_its_first_band_and_grows_to_the_target_at_once() {
        let mut s = BandScheduler::first_image();
        let first = s.rows(WIDTH, 10_000);
        assert_eq!(first, FIRST_BAND_PIXELS / WIDTH);
        s.record(WIDTH, first, Duration::from_micros(500) * first);
        let rows = s.rows(WIDTH, 10_000);
        assert!((592..=600).contains(&rows), "300 ms at 0.5 ms a row is 600 rows, got {rows}");
        assert_eq!(s.rows(WIDTH, 400), 400, "the rest of the sample in one band");

        s.retarget(INTERACTIVE_TARGET);
        let pixels = s.pixels;
        s.record(WIDTH, s.rows(WIDTH, 10_000), Duration::from_micros(1));
        assert_eq!(s.pixels, 2 * pixels, "once retargeted, an instant band only doubles the next");
    }

    #[test]
    fn growth_is_gentle_and_shrinking_immediate() {
        let mut s = compiled(BATCH_TARGET);
        let first = s.rows(WIDTH, 10_000);
        s.record(WIDTH, first, Duration::from_micros(1));
        assert_eq!(s.rows(WIDTH, 10_000), 2 * first, "an instant band only doubles the next");
        s.record(WIDTH, 2 * first, Duration::from_secs(10));
        assert_eq!(s.rows(WIDTH, 10_000), TILE_ROWS, "a slow band shrinks the next to one workgroup");
    }

    #[test]
    fn a_band_never_passes_the_rows_left_nor_is_empty() {
        let s = BandScheduler::before_compile(BATCH_TARGET);
        assert_eq!(s.rows(WIDTH, 3), 3);
        assert_eq!(s.rows(100_000, 5), 5, "a very wide image still gets one workgroup of rows");
        assert_eq!(s.rows(0, 0), 1);
    }
}
