//! `glint render`: load → build BVH → pack → upload → dispatch → resolve → write.

use std::io::IsTerminal;
use std::path::PathBuf;
use std::time::{Duration, Instant};

use clap::{Args, ValueEnum};
use glint_gpu::shaders::ShaderSource;
use glint_gpu::{Acceleration, Gpu, RayStats, RenderOptions, Renderer, ToneMap};
use glint_scene::scene::MAX_DEPTH_LIMIT;
use glint_scene::toml_scene::MAX_IMAGE_SIDE;
use indicatif::{ProgressBar, ProgressDrawTarget, ProgressStyle};

use crate::{exit, Failure};

#[derive(Args)]
pub struct RenderArgs {
    /// Scene file (.toml)
    scene: PathBuf,
    /// Output image (.png)
    #[arg(short, long)]
    output: PathBuf,
    /// Image width in pixels (default: the scene's)
    #[arg(long, value_parser = clap::value_parser!(u32).range(1..=i64::from(MAX_IMAGE_SIDE)))]
    width: Option<u32>,
    /// Image height in pixels (default: the scene's)
    #[arg(long, value_parser = clap::value_parser!(u32).range(1..=i64::from(MAX_IMAGE_SIDE)))]
    height: Option<u32>,
    /// Longest ray path, the eye ray counting as depth 1 (default: the scene's, else 5)
    #[arg(long, value_parser = clap::value_parser!(u32).range(1..=i64::from(MAX_DEPTH_LIMIT)))]
    max_depth: Option<u32>,
    /// Trace every reflection and refraction ray to the maximum depth, however
    /// little it contributes (as classic benchmark procedures require)
    #[arg(long)]
    no_cutoff: bool,
    /// Multiply linear radiance by this before tone mapping
    #[arg(long, default_value_t = 1.0, value_parser = finite_positive)]
    exposure: f32,
    /// How radiance above 1 is brought into range
    #[arg(long, value_enum, default_value_t = ToneMapArg::Clamp)]
    tone_map: ToneMapArg,
    /// Print ray counts
    #[arg(long)]
    stats: bool,
    /// With --stats: print them as one JSON object on stdout
    #[arg(long, requires = "stats")]
    json: bool,
    /// No progress bar or timing line
    #[arg(short, long)]
    quiet: bool,
}

#[derive(Clone, Copy, ValueEnum)]
enum ToneMapArg {
    Clamp,
    Reinhard,
    Aces,
}

fn finite_positive(s: &str) -> Result<f32, String> {
    match s.parse::<f32>() {
        Ok(v) if v.is_finite() && v > 0.0 => Ok(v),
        _ => Err(format!("`{s}` is not a positive finite number")),
    }
}

pub fn run(args: &RenderArgs) -> Result<(), Failure> {
    // Refuse an unwritable output format before doing any work.
    match image::ImageFormat::from_path(&args.output) {
        Ok(image::ImageFormat::Png) => {}
        _ => {
            return Err(Failure::new(
                exit::USAGE,
                format!("{}: unsupported output format: use .png", args.output.display()),
            ));
        }
    }

    let mut scene = glint_scene::load(&args.scene).map_err(|e| Failure::new(exit::INPUT, e))?;
    for warning in &scene.warnings {
        eprintln!("glint: warning: {warning}");
    }
    let width = args.width.unwrap_or(scene.width);
    let height = args.height.unwrap_or(scene.height);
    if let Some(d) = args.max_depth {
        scene.render.max_depth = d;
    }
    if args.no_cutoff {
        scene.render.cutoff = 0.0;
    }

    let gpu = Gpu::new()?;
    if let Some(warning) = gpu.driver_warning() {
        eprintln!("glint: {warning}");
    }
    let renderer = Renderer::new(gpu.device.clone(), gpu.queue.clone(), &ShaderSource::Embedded)?;
    let prepared = renderer.prepare(&scene, width, height, Acceleration::Bvh)?;

    let options = RenderOptions {
        width,
        height,
        exposure: args.exposure,
        tone_map: match args.tone_map {
            ToneMapArg::Clamp => ToneMap::Clamp,
            ToneMapArg::Reinhard => ToneMap::Reinhard,
            ToneMapArg::Aces => ToneMap::Aces,
        },
    };
    let bar = progress_bar(args.quiet);
    let start = Instant::now();
    let (image, stats) = renderer.render(&prepared.buffers, &options, &mut |done, total| {
        if start.elapsed() > Duration::from_secs(1) && bar.is_hidden() && !args.quiet && std::io::stderr().is_terminal() {
            bar.set_draw_target(ProgressDrawTarget::stderr());
        }
        bar.set_length(u64::from(total));
        bar.set_position(u64::from(done));
    })?;
    let elapsed = start.elapsed();
    bar.finish_and_clear();

    glint_gpu::write_image(&image, &args.output)?;

    if !args.quiet {
        eprintln!(
            "glint: rendered {}x{} in {:.3} s, {:.2} Mrays/s ({} rays) -> {}",
            width,
            height,
            elapsed.as_secs_f64(),
            stats.total() as f64 / elapsed.as_secs_f64() / 1e6,
            stats.total(),
            args.output.display()
        );
    }
    if args.stats {
        print_stats(&stats, args.json);
    }
    Ok(())
}

fn progress_bar(quiet: bool) -> ProgressBar {
    let bar = ProgressBar::with_draw_target(None, ProgressDrawTarget::hidden());
    if !quiet {
        bar.set_style(
            ProgressStyle::with_template("{spinner} rendering [{bar:40}] {pos}/{len} tiles {elapsed_precise}")
                .expect("the template is valid")
                .progress_chars("=> "),
        );
    }
    bar
}

fn print_stats(stats: &RayStats, json: bool) {
    if json {
        let value = serde_json::json!({
            "eye_hit": stats.eye_hit,
            "eye_miss": stats.eye_miss,
            "shadow": stats.shadow,
            "reflect": stats.reflect,
            "refract": stats.refract,
        });
        println!("{value}");
    } else {
        println!("eye rays (hit):  {}", stats.eye_hit);
        println!("eye rays (miss): {}", stats.eye_miss);
        println!("shadow rays:     {}", stats.shadow);
        println!("reflection rays: {}", stats.reflect);
        println!("refraction rays: {}", stats.refract);
        println!("total:           {}", stats.total());
    }
}
