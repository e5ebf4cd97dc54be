//! The ray tracer behind the viewer: the compiled kernels, a scene on the
//! device at the current render size, and its progressive accumulation.
//!
//! Nothing here waits for the device. Each frame adds at most one sample (a
//! band of rows of one, when a whole sample takes too long) and at most two
//! bands are in flight, so a slow device slows the image, never the UI.

use std::collections::VecDeque;
use std::sync::atomic::{AtomicUsize, Ordering};
use std::sync::{Arc, Mutex};
use std::time::Duration;

use glint_encoding::gpu_types::{GpuLight, GpuMaterial, SceneUniforms, View};
use glint_gpu::interactive::{PresentPipeline, PresentTarget, RayCounter};
use glint_gpu::schedule::{BandScheduler, INTERACTIVE_TARGET};
use glint_gpu::shaders::ShaderSource;
use glint_gpu::{Acceleration, GpuError, Prepared, RenderOptions, Renderer};
use glint_scene::Scene;
use web_time::Instant;

/// Bands submitted but not finished; more would only queue up latency.
const MAX_IN_FLIGHT: usize = 2;
/// How often a frame waiting for the device polls it.
const POLL_INTERVAL: Duration = Duration::from_millis(2);
/// The window over which Mrays/s is averaged.
const RATE_WINDOW: Duration = Duration::from_millis(1000);

/// The trace, resolve and present kernels, compiled from one shader source.
pub struct Kernels {
    pub renderer: Renderer,
    pub present: PresentPipeline,
    /// Where their WGSL came from: the probe kernel is compiled later from the same.
    pub source: ShaderSource,
    queue: wgpu::Queue,
}

impl Kernels {
    pub fn compile(device: &wgpu::Device, queue: &wgpu::Queue, source: &ShaderSource) -> Result<Self, GpuError> {
        let renderer = Renderer::new(device.clone(), queue.clone(), source)?;
        let present = renderer.present_pipeline(source)?;
        Ok(Self { renderer, present, source: source.clone(), queue: queue.clone() })
    }

    /// Has the device compile the kernels a canvas of `scene` first dispatches
    /// for `view` at `spp` samples per pixel (as `RenderOptions::spp`), by
    /// tracing one pixel. A software rasteriser compiles a
    /// kernel at its first dispatch, on its queue's one thread; done as soon as kernels and
    /// scene are both there, that compile runs while the window starts rather
    /// than after the first frame, which gives the canvas its size.
    pub fn warm_up(&self, scene: &Scene, view: View, spp: u32) -> Result<(), GpuError> {
        let mut prepared = self.renderer.prepare(scene, 1, 1, Acceleration::Bvh)?;
        specialise(&mut prepared, view);
        self.renderer.trace_rows(&prepared.buffers, 0, &RenderOptions { view, spp, ..RenderOptions::default() }, 0..1)
    }
}

/// A canvas's kernels compile the view it is made for alone, which a software
/// rasteriser compiles sooner than kernels for every view
/// (docs/decisions/016-kernels-per-view.md); a dispatch of another view gets the kernels for every
/// view, once (`Specialization::dispatching`).
fn specialise(prepared: &mut Prepared, view: View) {
    let specialization = &mut prepared.buffers.specialization;
    *specialization = specialization.for_views(&[view]);
}

/// What a canvas was made for; a canvas whose key differs is out of date.
#[derive(Clone, PartialEq)]
pub(crate) struct CanvasKey {
    pub(crate) kernels: usize,
    pub(crate) scene_generation: u64,
    pub(crate) size: (u32, u32),
}

/// A scene on the device at one image size, with the texture its image goes to.
pub struct Canvas {
    pub kernels: Arc<Kernels>,
    pub prepared: Prepared,
    pub target: PresentTarget,
    /// Which loaded scene this is (the viewer counts loads).
    pub scene_generation: u64,
    counter: RayCounter,
}

impl Canvas {
    /// Builds the BVH, uploads `scene` for an image of `size` (width, height)
    /// and makes its texture, for showing `view` first.
    pub fn new(kernels: Arc<Kernels>, scene: &Scene, view: View, size: (u32, u32), scene_generation: u64) -> Result<Self, GpuError> {
        let mut prepared = kernels.renderer.prepare(scene, size.0, size.1, Acceleration::Bvh)?;
        // Progressive rendering needs the whole image on the device at once.
        prepared.buffers.check_whole_image()?;
        specialise(&mut prepared, view);
        // Here, off the UI thread, for the scene's own terms; the first edit
        // beyond them widens them. Only the view's: a software rasteriser may
        // create a pipeline under the lock its queue holds while it compiles,
        // so a second one here would hold the canvas back until the first
        // compile is done. Picking's is created at the first pick, which
        // compiles it anyway.
        kernels.renderer.create_view_pipelines(&prepared.buffers, &[view])?;
        let target = kernels.renderer.present_target(&kernels.present, &prepared.buffers);
        let counter = kernels.renderer.ray_counter();
        Ok(Self { kernels, prepared, target, scene_generation, counter })
    }

    /// Makes the kernels take `materials`, `lights` and `uniforms` before they
    /// are written: an edit beyond the scene's own terms (a matte scene's first
    /// mirror, a light that fades, depth cueing turned on, a deeper ray tree)
    /// switches to the kernels with every term, once. Until then the kernels
    /// carry only what the scene uses, which a software rasteriser compiles
    /// sooner, so the first image comes sooner (docs/decisions/017-kernels-per-shading-terms.md).
    pub fn take_edits(&mut self, materials: &[GpuMaterial], lights: &[GpuLight], uniforms: &SceneUniforms, view: View) -> Result<(), GpuError> {
        let specialization = &mut self.prepared.buffers.specialization;
        if !specialization.covers(materials) || !specialization.covers_lights(lights) || !specialization.covers_uniforms(uniforms) {
            *specialization = specialization.editable();
            self.kernels.renderer.create_view_pipelines(&self.prepared.buffers, &[view])?;
        }
        Ok(())
    }

    pub fn size(&self) -> (u32, u32) {
        (self.prepared.buffers.width(), self.prepared.buffers.height())
    }

    pub fn renderer(&self) -> &Renderer {
        &self.kernels.renderer
    }

    /// Resolves what has accumulated into the texture.
    pub fn present(&self, options: &RenderOptions) {
        self.kernels.renderer.present(&self.kernels.present, &self.target, options);
    }
}

/// Progress of the progressive render of the current state.
pub struct Accumulation {
    /// Samples per pixel completed.
    pub samples: u32,
    /// Where the next band starts. A sample may start on any row and wrap
    /// around, so that while the view keeps changing every row still gets its
    /// turn.
    next_row: u32,
    /// Rows of the current sample not yet traced; `None` for all of them.
    rows_left: Option<u32>,
    bands: BandScheduler,
    in_flight: Arc<AtomicUsize>,
    timing: Arc<Mutex<BandTiming>>,
    /// The texture shows an image of the current canvas.
    pub presented: bool,
    rays: VecDeque<(Instant, u64)>,
    /// Rays per second over the last second of rendering.
    pub rays_per_second: f64,
}

/// When bands finish, to estimate how long the device spends on one.
#[derive(Default)]
struct BandTiming {
    /// When the last band finished.
    last_done: Option<Instant>,
    /// Rows and device time of the last band finished.
    last: Option<(u32, Duration)>,
}

/// What a frame's step did.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Step {
    /// All samples are in; nothing to do until something changes.
    Done,
    /// A band was traced.
    Traced,
    /// The device is still busy with earlier bands.
    Waiting,
}

/// How the viewer learns that the device finished a band.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Completions {
    /// At the next `Device::poll`, which a frame runs: natively.
    Polled,
    /// By themselves, from the browser's event loop (WebGPU).
    Delivered,
}

impl Completions {
    /// How a device of `backend` reports finished work.
    pub fn of(backend: wgpu::Backend) -> Self {
        if backend == wgpu::Backend::BrowserWebGpu { Completions::Delivered } else { Completions::Polled }
    }

    /// When a frame whose step did `step` asks for the next one (`None`: it
    /// does not; a finished band wakes the viewer), `room` telling whether
    /// another band may go in flight. Polled completions need frames to poll
    /// for them. Delivered ones wake the viewer themselves, and a frame that
    /// could only wait would cost a paint, which the device queues in front
    /// of the next band: in a browser on a software rasteriser, where a paint
    /// takes longer than a band, such frames kept the queue seconds deep and
    /// a sample took minutes.
    pub fn next_frame(self, step: Step, room: bool) -> Option<Duration> {
        match (self, step) {
            (_, Step::Done) => None,
            (Completions::Polled, Step::Traced) => Some(Duration::ZERO),
            (Completions::Polled, Step::Waiting) => Some(POLL_INTERVAL),
            (Completions::Delivered, Step::Traced) => room.then_some(Duration::ZERO),
            (Completions::Delivered, Step::Waiting) => None,
        }
    }
}

impl Accumulation {
    /// Nothing accumulated yet, in bands sized by `bands`.
    pub fn new(bands: BandScheduler) -> Self {
        Self {
            samples: 0,
            next_row: 0,
            rows_left: None,
            bands,
            in_flight: Arc::new(AtomicUsize::new(0)),
            timing: Arc::new(Mutex::new(BandTiming::default())),
            presented: false,
            rays: VecDeque::new(),
            rays_per_second: 0.0,
        }
    }

    /// Starts over. The first sample clears each band before tracing it, so
    /// until it is done the rows below it still show the previous image.
    pub fn restart(&mut self) {
        self.samples = 0;
        self.rows_left = None;
    }

    /// Another band may go in flight.
    pub fn has_room(&self) -> bool {
        self.in_flight.load(Ordering::Acquire) < MAX_IN_FLIGHT
    }

    /// Adds the next band of rows of the next sample, up to `target` samples;
    /// `wake` is called when the band is done (see [`Completions`]).
    pub fn step(&mut self, canvas: &Canvas, options: &RenderOptions, target: u32, wake: impl FnOnce() + Send + 'static) -> Result<Step, GpuError> {
        if self.samples >= target {
            return Ok(Step::Done);
        }
        if !self.has_room() {
            return Ok(Step::Waiting);
        }
        let (width, height) = canvas.size();
        if let Some((rows, took)) = self.timing.lock().expect("never poisoned").last.take() {
            self.bands.record(width, rows, took);
        }
        let left = *self.rows_left.get_or_insert(height);
        let start = self.next_row.min(height - 1);
        let rows = start..(start + self.bands.rows(width, left)).min(height);
        if self.samples == 0 {
            canvas.renderer().clear_rows(&canvas.prepared.buffers, rows.clone());
        }
        canvas.renderer().trace_rows(&canvas.prepared.buffers, self.samples, options, rows.clone())?;
        self.in_flight.fetch_add(1, Ordering::AcqRel);
        let (in_flight, timing, submitted, count) =
            (Arc::clone(&self.in_flight), Arc::clone(&self.timing), Instant::now(), rows.len() as u32);
        canvas.kernels.queue.on_submitted_work_done(move || {
            in_flight.fetch_sub(1, Ordering::AcqRel);
            let now = Instant::now();
            let mut t = timing.lock().expect("never poisoned");
            // The queue runs in order: a band starts when it was submitted or
            // when the band before it finished, whichever is later.
            let started = t.last_done.map_or(submitted, |done| done.max(submitted));
            t.last = Some((count, now - started));
            t.last_done = Some(now);
            drop(t);
            wake();
        });
        self.next_row = if rows.end >= height { 0 } else { rows.end };
        let left = left - (rows.end - rows.start);
        self.rows_left = Some(left);
        if left == 0 {
            // A whole sample is in: the bands make way for the UI from now on
            // (at the interactive target already, this changes nothing).
            self.bands.retarget(INTERACTIVE_TARGET);
            self.samples += 1;
            self.rows_left = None;
        }
        Ok(Step::Traced)
    }

    /// Collects ray counts that have arrived and asks for the next ones.
    pub fn count_rays(&mut self, canvas: &mut Canvas) -> Result<(), GpuError> {
        let now = Instant::now();
        if let Some(stats) = canvas.counter.poll() {
            self.rays.push_back((now, stats?.total()));
        }
        canvas.counter.request(&canvas.kernels.renderer, &canvas.prepared.buffers);
        while self.rays.front().is_some_and(|(t, _)| now.duration_since(*t) > RATE_WINDOW) {
            self.rays.pop_front();
        }
        if let (Some((first, _)), Some((last, _))) = (self.rays.front(), self.rays.back()) {
            // Each entry holds the rays traced since the one before, so the
            // first one's rays belong to the time before the window.
            let span = last.duration_since(*first).as_secs_f64();
            let rays: u64 = self.rays.iter().skip(1).map(|(_, r)| r).sum();
            self.rays_per_second = if span > 0.0 { rays as f64 / span } else { 0.0 };
        }
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use std::path::Path;
    use std::sync::atomic::{AtomicUsize, Ordering};
    use std::sync::Arc;
    use std::time::Duration;

    use glint_encoding::gpu_types::View;
    use glint_gpu::schedule::BandScheduler;
    use glint_gpu::shaders::{Kernel, ShaderSource};
    use glint_gpu::RenderOptions;

    use super::{Accumulation, Canvas, Completions, Kernels, Step, POLL_INTERVAL};

    #[test]
    fn a_browser_frame_never_only_waits_for_the_device() {
        let browser = Completions::of(wgpu::Backend::BrowserWebGpu);
        assert_eq!(browser, Completions::Delivered);
        assert_eq!(browser.next_frame(Step::Waiting, false), None, "the finished band wakes the viewer");
        assert_eq!(browser.next_frame(Step::Traced, false), None, "both bands in flight: the next finished one wakes it");
        assert_eq!(browser.next_frame(Step::Traced, true), Some(Duration::ZERO), "a second band can go in flight at once");
        assert_eq!(browser.next_frame(Step::Done, true), None);
        let native = Completions::of(wgpu::Backend::Vulkan);
        assert_eq!(native.next_frame(Step::Waiting, false), Some(POLL_INTERVAL), "natively a frame polls for the band");
        assert_eq!(native.next_frame(Step::Traced, false), Some(Duration::ZERO));
        assert_eq!(native.next_frame(Step::Done, true), None);
    }

    #[test]
    fn a_finished_band_wakes_the_viewer_and_makes_room() {
        let gpu = glint_gpu::Gpu::new().expect("a device (a software one in CI)");
        let kernels = Arc::new(Kernels::compile(&gpu.device, &gpu.queue, &ShaderSource::Embedded).unwrap());
        let scene = glint_scene::load(Path::new("spd:tetra:1")).unwrap();
        let canvas = Canvas::new(kernels, &scene, View::Shaded, (40, 30), 1).unwrap();
        let mut acc = Accumulation::new(BandScheduler::new_canvas());
        let woken = Arc::new(AtomicUsize::new(0));
        let options = RenderOptions { view: View::Shaded, ..RenderOptions::default() };
        // Each band is a whole sample of this small image.
        for band in 1..=2 {
            let wake = Arc::clone(&woken);
            assert_eq!(acc.step(&canvas, &options, 2, move || { wake.fetch_add(1, Ordering::AcqRel); }).unwrap(), Step::Traced);
            gpu.device.poll(wgpu::PollType::wait_indefinitely()).unwrap();
            assert_eq!(woken.load(Ordering::Acquire), band, "each band, once done, wakes the viewer");
            assert!(acc.has_room() && acc.samples == band as u32);
        }
        assert_eq!(acc.step(&canvas, &options, 2, || ()).unwrap(), Step::Done);
    }

    #[test]
    fn the_warm_up_compiles_the_kernel_the_first_canvas_dispatches() {
        let gpu = glint_gpu::Gpu::new().expect("a device (a software one in CI)");
        let kernels = Arc::new(Kernels::compile(&gpu.device, &gpu.queue, &ShaderSource::Embedded).unwrap());
        let scene = glint_scene::load(Path::new("spd:tetra:1")).unwrap();
        // The viewer's default: progressive samples (Settings::traced_samples).
        kernels.warm_up(&scene, View::Shaded, 0).unwrap();
        let warmed = kernels.renderer.pipelines_created();
        let canvas = Canvas::new(Arc::clone(&kernels), &scene, View::Shaded, (40, 30), 1).unwrap();
        let (specialization, tuning) = (canvas.prepared.buffers.specialization, canvas.prepared.buffers.tuning());
        assert_eq!(specialization.view, Some(View::Shaded), "the canvas's kernels are for its first view alone");
        // Progressive samples leave the pixel centres: no eye hits.
        let progressive = tuning.without_eye_tiles().for_kernel(Kernel::Trace);
        let trace = (Kernel::Trace, Kernel::Trace.compiled_for(specialization.dispatching(View::Shaded)), progressive);
        assert_eq!(warmed, [trace]);
        assert_eq!(kernels.renderer.pipelines_created(), warmed, "the canvas needs no other pipeline for its first image");
        // Picking gets the primary kernel for every view; its one pixel is no
        // eye tile's corner, so the kernel that walks the BVH.
        canvas.renderer().pick(&canvas.prepared.buffers, 20, 15).unwrap();
        let mut created = kernels.renderer.pipelines_created();
        created.retain(|p| !warmed.contains(p));
        let picking = tuning.without_eye_tiles().for_kernel(Kernel::Primary);
        assert_eq!(created, [(Kernel::Primary, Kernel::Primary.compiled_for(specialization.dispatching(View::Id)), picking)]);
        assert_eq!(specialization.dispatching(View::Id).view, None);
    }
}
