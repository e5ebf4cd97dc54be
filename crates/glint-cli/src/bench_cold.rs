//! `glint bench --cold`: what a first render pays before its first pixel —
//! each kernel's pipeline creation (on a software rasteriser, compiling the
//! kernel to CPU code) for the primitive kinds of each scene, and the first
//! frame against the next.

use std::path::{Path, PathBuf};
use std::time::{Duration, Instant};

use glint_encoding::gpu_types::View;
use glint_gpu::shaders::{Kernel, ShaderSource};
use glint_gpu::{Acceleration, Gpu, RenderOptions, Renderer, Workload};

use crate::{exit, Failure};

/// Measures each of `scenes` on `gpu`, readied for `workload`: a first
/// render of that size.
pub fn run(gpu: &Gpu, workload: Workload, scenes: &[PathBuf], width: u32, height: u32, json: bool) -> Result<(), Failure> {
    if !json {
        let note = gpu.cold_start_note().map_or(String::new(), |note| format!(", {note}"));
        eprintln!(
            "{} — {width}x{height}, {}{note}; a kernel's compile = its pipeline's creation + its first run − its second",
            gpu.info().name,
            gpu.profile().describe()
        );
        println!("{:<22} {:<44} {:>17} {:>19} {:>19}", "scene", "kinds", "trace compile ms", "primary compile ms", "resolve compile ms");
    }
    for path in scenes {
        measure(gpu, workload, path, width, height, json)?;
    }
    Ok(())
}

fn measure(gpu: &Gpu, workload: Workload, path: &Path, width: u32, height: u32, json: bool) -> Result<(), Failure> {
    let scene = glint_scene::load(path).map_err(|e| Failure::new(exit::INPUT, e))?;
    // A renderer of its own, so no kernel compiled for an earlier scene is
    // reused; its kernels those a one-off render of this size compiles (`glint render`).
    let renderer = &Renderer::new(gpu.device.clone(), gpu.queue.clone(), &ShaderSource::Embedded)?.plan(workload);
    let prepared = renderer.prepare(&scene, width, height, Acceleration::Bvh)?;
    let buffers = &prepared.buffers;
    // Software rasterisers compile a pipeline when it first runs, not when it is
    // created: its compile is the creation and the first run's excess over the second.
    let compile = |kernel: Kernel, run: &dyn Fn() -> Result<(), Failure>| -> Result<Duration, Failure> {
        let start = Instant::now();
        renderer.create_pipelines(buffers, &[kernel])?;
        let created = start.elapsed();
        let runs = [(); 2].map(|_| {
            let start = Instant::now();
            run().map(|_| start.elapsed())
        });
        let [first, second] = runs;
        Ok(created + first?.saturating_sub(second?))
    };
    let frame = |view: View| {
        move || -> Result<(), Failure> {
            let options = RenderOptions { view, ..RenderOptions::default() };
            renderer.trace_frame(buffers, &options, &mut |_, _| {})?;
            Ok(())
        }
    };
    let trace = compile(Kernel::Trace, &frame(View::Shaded))?;
    let primary = compile(Kernel::Primary, &frame(View::Depth))?;
    // A CPU adapter resolves renders on the host: no kernel to compile.
    let resolve = (!renderer.resolves_on_host())
        .then(|| {
            compile(Kernel::Resolve, &|| {
                renderer.resolve(buffers, &RenderOptions::default())?;
                Ok(())
            })
        })
        .transpose()?;
    let ms = |d: Duration| d.as_secs_f64() * 1e3;
    let kinds = format!("{}, {}", buffers.specialization, buffers.tuning());
    if json {
        let value = serde_json::json!({
            "scene": path.display().to_string(),
            "width": width,
            "height": height,
            "kinds": kinds,
            "trace_compile_ms": ms(trace),
            "primary_compile_ms": ms(primary),
            "resolve_compile_ms": resolve.map(ms),
        });
        println!("{value}");
    } else {
        let name = path.file_stem().map_or(path.display().to_string(), |s| s.to_string_lossy().into_owned());
        let resolve = resolve.map_or("on the host".to_string(), |d| format!("{:.0}", ms(d)));
        println!("{:<22} {:<44} {:>17.0} {:>19.0} {:>19}", name, kinds, ms(trace), ms(primary), resolve);
    }
    Ok(())
}
