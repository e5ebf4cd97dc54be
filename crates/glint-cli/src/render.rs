//! `glint render`: load → build BVH → pack → upload → dispatch → resolve → write.

use std::io::IsTerminal;
use std::path::PathBuf;
use std::time::{Duration, Instant};

use clap::{Args, ValueEnum};
use glint_gpu::shaders::ShaderSource;
use glint_gpu::{Acceleration, Format, Gpu, Image, PngBits, RayStats, RenderOptions, Renderer, ToneMap};
use glint_scene::gpu_types::{Filter, View};
use glint_scene::scene::MAX_DEPTH_LIMIT;
use glint_scene::toml_scene::MAX_IMAGE_SIDE;
use indicatif::{ProgressBar, ProgressDrawTarget, ProgressStyle};

use crate::{exit, Failure};

#[derive(Args)]
pub struct RenderArgs {
    /// Scene file (.toml, .nff or .obj), or spd:NAME[:SIZE] for a generated SPD scene
    #[arg(value_parser = crate::scene_arg::parse)]
    scene: PathBuf,
    /// Output image: .png (display values), .exr or .pfm (linear float)
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
    /// How an NFF file's `angle` is read: from the centres of the outer pixel rows
    /// (the NFF text) or from the image edges (what many exporters write)
    #[arg(long, value_enum, default_value_t = NffAngleArg::Centers)]
    nff_angle: NffAngleArg,
    /// Samples per pixel, stratified and jittered (1: through each pixel centre)
    #[arg(long, default_value_t = 1, value_parser = clap::value_parser!(u32).range(1..=4096))]
    spp: u32,
    /// Seed of the sample jitter: the same seed gives the same image
    #[arg(long, default_value_t = 0)]
    seed: u32,
    /// Reconstruction filter for --spp > 1
    #[arg(long, value_enum, default_value_t = FilterArg::Box)]
    filter: FilterArg,
    /// What to show: the full render or a debug view (one ray per pixel centre)
    #[arg(long, value_enum, default_value_t = ViewArg::Shaded)]
    view: ViewArg,
    /// Also write an arbitrary output variable, NAME=PATH with NAME one of depth,
    /// normal, albedo, id and PATH a .pfm or .exr file (repeatable)
    #[arg(long, value_name = "NAME=PATH", value_parser = parse_aov)]
    aov: Vec<(ViewArg, PathBuf)>,
    /// Bits per channel of PNG output
    #[arg(long, value_enum, default_value_t = BitsArg::Eight)]
    bits: BitsArg,
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
enum NffAngleArg {
    Centers,
    Edges,
}

#[derive(Clone, Copy, ValueEnum)]
enum BitsArg {
    #[value(name = "8")]
    Eight,
    #[value(name = "16")]
    Sixteen,
}

#[derive(Clone, Copy, ValueEnum)]
enum FilterArg {
    Box,
    Tent,
}

#[derive(Clone, Copy, Debug, PartialEq, ValueEnum)]
enum ViewArg {
    Shaded,
    Normals,
    Depth,
    Albedo,
    Diffuse,
    Id,
    Heatmap,
}

impl ViewArg {
    fn view(self) -> View {
        match self {
            ViewArg::Shaded => View::Shaded,
            ViewArg::Normals => View::Normal,
            ViewArg::Depth => View::Depth,
            ViewArg::Albedo => View::Albedo,
            ViewArg::Diffuse => View::Diffuse,
            ViewArg::Id => View::Id,
            ViewArg::Heatmap => View::Heatmap,
        }
    }
}

fn parse_aov(s: &str) -> Result<(ViewArg, PathBuf), String> {
    let (name, path) = s.split_once('=').ok_or("expected NAME=PATH")?;
    let view = match name {
        "depth" => ViewArg::Depth,
        "normal" => ViewArg::Normals,
        "albedo" => ViewArg::Albedo,
        "id" => ViewArg::Id,
        other => return Err(format!("unknown AOV `{other}`: expected depth, normal, albedo or id")),
    };
    let path = PathBuf::from(path);
    match Format::from_path(&path) {
        Ok(Format::Exr | Format::Pfm) => Ok((view, path)),
        _ => Err(format!("{}: an AOV is written as .pfm or .exr", path.display())),
    }
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
    Format::from_path(&args.output).map_err(|e| Failure::new(exit::USAGE, e))?;

    let load_options = glint_scene::LoadOptions {
        nff_angle: match args.nff_angle {
            NffAngleArg::Centers => glint_scene::NffAngle::Centers,
            NffAngleArg::Edges => glint_scene::NffAngle::Edges,
        },
    };
    let mut scene = glint_scene::load_with(&args.scene, &load_options).map_err(|e| Failure::new(exit::INPUT, e))?;
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

    let view = args.view.view();
    let options = RenderOptions {
        view,
        spp: if view.is_primary_only() { 1 } else { args.spp },
        seed: args.seed,
        filter: match args.filter {
            FilterArg::Box => Filter::Box,
            FilterArg::Tent => Filter::Tent,
        },
        exposure: args.exposure,
        tone_map: match args.tone_map {
            ToneMapArg::Clamp => ToneMap::Clamp,
            ToneMapArg::Reinhard => ToneMap::Reinhard,
            ToneMapArg::Aces => ToneMap::Aces,
        },
        view_scale: prepared.view_scale(view),
        band_rows: None,
    };
    let bar = progress_bar(args.quiet);
    let start = Instant::now();
    let (image, stats) = renderer.render(&prepared.buffers, &options, &mut |done, total| {
        if start.elapsed() > Duration::from_secs(1) && bar.is_hidden() && !args.quiet && std::io::stderr().is_terminal() {
            bar.set_draw_target(ProgressDrawTarget::stderr());
        }
        bar.set_length(total);
        bar.set_position(done);
    })?;
    let elapsed = start.elapsed();
    bar.finish_and_clear();

    // Every image is rendered before any is written, so a failure writes nothing.
    let mut outputs: Vec<(Image, &PathBuf)> = vec![(image, &args.output)];
    for (aov, path) in &args.aov {
        let aov_view = aov.view();
        let aov_options = RenderOptions { view: aov_view, spp: 1, view_scale: prepared.view_scale(aov_view), ..options };
        let (image, _) = renderer.render(&prepared.buffers, &aov_options, &mut |_, _| {})?;
        outputs.push((if aov_view == View::Depth { image.with_misses_at_infinity() } else { image }, path));
    }
    if view == View::Depth {
        outputs[0].0 = outputs[0].0.clone().with_misses_at_infinity();
    }
    let bits = match args.bits {
        BitsArg::Eight => PngBits::Eight,
        BitsArg::Sixteen => PngBits::Sixteen,
    };
    for (image, path) in &outputs {
        glint_gpu::write_image(image, path, bits)?;
    }

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
            ProgressStyle::with_template("{spinner} rendering [{bar:40}] {percent}% {elapsed_precise} (eta {eta})")
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
