//! `glint bench`: build and render times, throughput and ray counts per scene.

use std::path::{Path, PathBuf};
use std::time::{Duration, Instant};

use clap::{Args, ValueEnum};
use glint_encoding::gpu_types::View;
use glint_gpu::shaders::ShaderSource;
use glint_gpu::{Acceleration, Gpu, Prepared, RayStats, RenderOptions, Renderer, Workload};
use glint_scene::MAX_DEPTH_LIMIT;

use crate::{exit, Failure};

#[derive(Args)]
pub struct BenchArgs {
    /// Scene files or spd:NAME[:SIZE] (default: the SPD databases at their
    /// benchmark sizes, and scenes/bench/*.toml when run from the repository)
    #[arg(value_parser = crate::scene_arg::parse)]
    scenes: Vec<PathBuf>,
    #[arg(long, default_value_t = 512)]
    width: u32,
    #[arg(long, default_value_t = 512)]
    height: u32,
    /// Timed frames per measurement, after the warm-up; the median is reported
    #[arg(long, default_value_t = 5, value_parser = clap::value_parser!(u32).range(1..=1000))]
    frames: u32,
    /// Seconds of untimed frames after the first, which compiles the kernels:
    /// the driver runs its first frames after a compile slower
    /// (docs/decisions/053-warm-frames-after-the-compile-settles.md)
    #[arg(long, default_value_t = 0.2, value_parser = parse_seconds)]
    warm_up: f64,
    /// Acceleration structure to measure (brute force tests every primitive per ray)
    #[arg(long, value_enum, default_value_t = AccelArg::Bvh)]
    accel: AccelArg,
    /// Longest ray path of the Whitted frame, the eye ray counting as depth 1
    /// (default: each scene's); 1 traces eye and shadow rays alone
    #[arg(long, value_parser = clap::value_parser!(u32).range(1..=i64::from(MAX_DEPTH_LIMIT)))]
    max_depth: Option<u32>,
    /// One JSON object per scene per line
    #[arg(long)]
    json: bool,
    /// Measure what a first render pays instead: each kernel's pipeline
    /// creation for each scene's primitive kinds, as a one-off render of that
    /// size compiles it (the driver's compile), and the first frame against a
    /// warm one; the header says how to measure what a fresh machine pays.
    #[arg(long)]
    cold: bool,
}

#[derive(Clone, Copy, ValueEnum)]
enum AccelArg {
    Bvh,
    Brute,
}

/// The Standard Procedural Databases benchmarked by default: the classic
/// sizes, and sizes of the others comparable to them.
const SPD_BENCHMARKS: &[&str] = &[
    "balls", "gears", "mount", "rings", "teapot", "tetra", "tree", "shells", "lattice", "sombrero:2", "jacks:3", "nurbtst",
];

fn default_scenes() -> Vec<PathBuf> {
    let mut scenes: Vec<PathBuf> = std::fs::read_dir("scenes/bench")
        .map(|dir| dir.filter_map(|e| e.ok().map(|e| e.path())).filter(|p| p.extension().is_some_and(|e| e == "toml")).collect())
        .unwrap_or_default();
    scenes.sort();
    scenes.extend(SPD_BENCHMARKS.iter().map(|spec| PathBuf::from(format!("{}{spec}", glint_scene::spd::PREFIX))));
    scenes
}

struct Measurement {
    scene: String,
    prims: usize,
    bvh_build: Duration,
    /// Binning the primitives into eye tiles for the view, when the scene has them.
    eye_tiles_build: Option<Duration>,
    bvh_nodes: usize,
    gpu_bytes: u64,
    /// A primary frame with its view's host work: what a camera move costs.
    primary: Duration,
    /// The view's host work alone: its eye tiles binned for the camera.
    view_work: Duration,
    /// Untimed primary frames within the warm-up, after the first.
    warm_up_frames: usize,
    whitted: Duration,
    max_depth: u32,
    stats: RayStats,
    nodes_per_primary_ray: f64,
}

pub fn run(args: &BenchArgs) -> Result<(), Failure> {
    let scenes = if args.scenes.is_empty() { default_scenes() } else { args.scenes.clone() };
    // Cold, the kernels a first render of each scene compiles; warm, those of
    // a long render, whose time the warm frames stand for.
    let pixels = u64::from(args.width) * u64::from(args.height);
    let workload = if args.cold { Workload::render(pixels, pixels, false) } else { Workload::REPEATED_FRAMES };
    let gpu = Gpu::for_workload(&workload)?;
    if args.cold {
        return crate::bench_cold::run(&gpu, workload, &scenes, args.width, args.height, args.json);
    }
    let renderer = Renderer::new(gpu.device.clone(), gpu.queue.clone(), &ShaderSource::Embedded)?.plan(workload);
    let acceleration = match args.accel {
        AccelArg::Bvh => Acceleration::Bvh,
        AccelArg::Brute => Acceleration::BruteForce,
    };
    if !args.json {
        let depth = args.max_depth.map_or(String::new(), |d| format!(", Whitted frame to depth {d}"));
        eprintln!("{} — {}x{}, median of {} frames{depth}", gpu.info().name, args.width, args.height, args.frames);
        println!(
            "{:<22} {:>9} {:>9} {:>9} {:>9} {:>10} {:>9} {:>11} {:>9} {:>10} {:>11} {:>11} {:>9}",
            "scene", "prims", "build ms", "tiles ms", "nodes", "GPU bytes", "B/prim", "primary ms", "view ms", "Mrays/s", "Whitted ms", "Mrays/s", "nodes/ray"
        );
    }
    // The driver's SIMD width, where the profile chooses it: the kernels'
    // speed depends on it.
    let vector_bits = renderer.profile().kernels.and_then(|kernels| kernels.vector_bits);
    let mut measured = Vec::new();
    for path in &scenes {
        let m = measure(&renderer, path, args, acceleration)?;
        print(&m, args, vector_bits);
        measured.push(m);
    }
    if !args.json {
        print_kinds(&measured);
    }
    Ok(())
}

fn measure(renderer: &Renderer, path: &Path, args: &BenchArgs, acceleration: Acceleration) -> Result<Measurement, Failure> {
    let mut scene = glint_scene::load(path).map_err(|e| Failure::new(exit::INPUT, e))?;
    if let Some(depth) = args.max_depth {
        scene.render.max_depth = depth;
    }
    let mut prepared = renderer.prepare(&scene, args.width, args.height, acceleration)?;
    let scene_kernels = prepared.buffers.specialization;
    // Device time per frame: tracing only, no resolve or read-back. When the
    // camera moves, each frame follows a view's host work as in the viewer:
    // the camera and lights written, the eye tiles binned; the frame's
    // submission takes the lists with it.
    let mut time = |view: View, camera_moves: bool| -> Result<(Duration, Duration, usize, RayStats), Failure> {
        let options = RenderOptions { view, ..RenderOptions::default() };
        let mut stats = RayStats::default();
        let (mut times, mut view_times) = (Vec::new(), Vec::new());
        let (mut warm_from, mut warm_up_frames) = (None, 0);
        while times.len() < args.frames as usize {
            let start = Instant::now();
            if camera_moves {
                prepared.buffers.specialization = scene_kernels;
                prepared.buffers.forget_view();
                renderer.pose(&mut prepared, &scene)?;
            }
            let view_time = start.elapsed();
            // The kernels `glint render` compiles for a long render of that
            // view alone: a kernel for every view would time the other views'
            // code too (in the depth view, each hit loaded the whole primitive
            // for the views that shade it).
            prepared.buffers.specialization = scene_kernels.for_views(&[view]);
            stats = renderer.trace_frame(&prepared.buffers, &options, &mut |_, _| {})?;
            // The first frame compiles; frames that start within the warm-up after it are not timed.
            match warm_from {
                None => warm_from = Some(Instant::now() + Duration::from_secs_f64(args.warm_up)),
                Some(warm) if start < warm => warm_up_frames += 1,
                Some(_) => {
                    times.push(start.elapsed());
                    view_times.push(view_time);
                }
            }
        }
        Ok((median(times), median(view_times), warm_up_frames, stats))
    };
    let (primary, view_work, warm_up_frames, _) = time(View::Depth, true)?;
    let (whitted, _, _, stats) = time(View::Shaded, false)?;
    let heat_options = RenderOptions { view: View::Heatmap, ..RenderOptions::default() };
    let (heat, _) = renderer.render(&prepared.buffers, &heat_options, &mut |_, _| {})?;
    let nodes_per_primary_ray = heat.linear.iter().map(|p| f64::from(p[0])).sum::<f64>() / heat.linear.len() as f64;
    let Prepared { primitives, bvh_nodes, bvh_build, eye_tiles_build, buffers, .. } = prepared;
    Ok(Measurement {
        scene: path.display().to_string(),
        prims: primitives,
        bvh_build,
        eye_tiles_build,
        bvh_nodes,
        gpu_bytes: buffers.scene_bytes,
        primary,
        view_work,
        warm_up_frames,
        whitted,
        max_depth: scene.render.max_depth,
        stats,
        nodes_per_primary_ray,
    })
}

fn parse_seconds(text: &str) -> Result<f64, String> {
    match text.parse::<f64>() {
        Ok(seconds) if (0.0..=60.0).contains(&seconds) => Ok(seconds),
        _ => Err(format!("`{text}` is not a number of seconds from 0 to 60")),
    }
}

fn median(mut times: Vec<Duration>) -> Duration {
    times.sort();
    times[times.len() / 2]
}

fn mrays(rays: u64, time: Duration) -> f64 {
    rays as f64 / time.as_secs_f64() / 1e6
}

/// The Whitted frame's rays by kind. The kinds are traced together in one
/// frame and a GPU times no kind alone, so each kind's rate is its rays over
/// the whole frame's time.
fn by_kind(stats: &RayStats) -> [(&'static str, u64); 4] {
    [("eye", stats.eye_hit + stats.eye_miss), ("shadow", stats.shadow), ("reflected", stats.reflect), ("refracted", stats.refract)]
}

fn scene_name(m: &Measurement) -> String {
    Path::new(&m.scene).file_stem().map_or(m.scene.clone(), |s| s.to_string_lossy().into_owned())
}

fn print_kinds(measured: &[Measurement]) {
    println!();
    println!("Whitted frame by ray kind: rays per frame, and Mrays/s = that kind's rays / the whole frame's time (no kind is timed alone)");
    print!("{:<22} {:>6} {:>11}", "scene", "depth", "Whitted ms");
    for (kind, _) in by_kind(&RayStats::default()) {
        print!(" {:>14} {:>9}", format!("{kind} rays"), "Mrays/s");
    }
    println!();
    for m in measured {
        print!("{:<22} {:>6} {:>11.1}", scene_name(m), m.max_depth, m.whitted.as_secs_f64() * 1e3);
        for (_, rays) in by_kind(&m.stats) {
            print!(" {:>14} {:>9.2}", rays, mrays(rays, m.whitted));
        }
        println!();
    }
}

fn print(m: &Measurement, args: &BenchArgs, vector_bits: Option<u32>) {
    let pixels = u64::from(args.width) * u64::from(args.height);
    let ms = |d: Duration| d.as_secs_f64() * 1e3;
    if args.json {
        let kinds: serde_json::Map<String, serde_json::Value> = by_kind(&m.stats)
            .iter()
            .map(|&(kind, rays)| (kind.to_string(), serde_json::json!({ "rays": rays, "mrays_per_s": mrays(rays, m.whitted) })))
            .collect();
        let value = serde_json::json!({
            "scene": m.scene,
            "width": args.width,
            "height": args.height,
            "prims": m.prims,
            "bvh_build_ms": ms(m.bvh_build),
            "eye_tiles_ms": m.eye_tiles_build.map(ms),
            "bvh_nodes": m.bvh_nodes,
            "gpu_bytes": m.gpu_bytes,
            "gpu_bytes_per_prim": m.gpu_bytes as f64 / m.prims.max(1) as f64,
            "primary_ms": ms(m.primary),
            "view_work_ms": ms(m.view_work),
            "warm_up_frames": m.warm_up_frames,
            "render_ms": ms(m.whitted),
            "primary_mrays_per_s": mrays(pixels, m.primary),
            "whitted_mrays_per_s": mrays(m.stats.total(), m.whitted),
            "nodes_per_primary_ray": m.nodes_per_primary_ray,
            "eye_hit": m.stats.eye_hit,
            "eye_miss": m.stats.eye_miss,
            "shadow": m.stats.shadow,
            "reflect": m.stats.reflect,
            "refract": m.stats.refract,
            "rays": m.stats.total(),
            "vector_bits": vector_bits,
            "max_depth": m.max_depth,
            "kinds": kinds,
        });
        println!("{value}");
    } else {
        let name = scene_name(m);
        let tiles = m.eye_tiles_build.map_or("-".to_string(), |d| format!("{:.1}", ms(d)));
        println!(
            "{:<22} {:>9} {:>9.1} {:>9} {:>9} {:>10} {:>9.1} {:>11.1} {:>9.1} {:>10.2} {:>11.1} {:>11.2} {:>9.1}",
            name,
            m.prims,
            ms(m.bvh_build),
            tiles,
            m.bvh_nodes,
            m.gpu_bytes,
            m.gpu_bytes as f64 / m.prims.max(1) as f64,
            ms(m.primary),
            ms(m.view_work),
            mrays(pixels, m.primary),
            ms(m.whitted),
            mrays(m.stats.total(), m.whitted),
            m.nodes_per_primary_ray
        );
    }
}

#[cfg(test)]
mod tests {
    #[test]
    fn the_default_scenes_are_generated_or_in_the_repository() {
        let scenes = super::default_scenes();
        for name in glint_scene::spd::CLASSIC {
            assert!(scenes.iter().any(|s| s.to_str() == Some(&format!("spd:{name}"))), "{name} is not benchmarked");
        }
        for scene in &scenes {
            let text = scene.to_str().unwrap();
            assert!(text.starts_with("spd:") || scene.starts_with("scenes/bench"), "{text} is outside the repository");
            if let Some(spec) = glint_scene::spd::spec_of(scene) {
                glint_scene::spd::check(spec).unwrap();
            }
        }
    }
}
