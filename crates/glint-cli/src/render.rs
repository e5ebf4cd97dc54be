//! `glint render`: load → build BVH → pack → upload → dispatch → resolve → write.

use std::io::IsTerminal;
use std::path::{Path, PathBuf};
use std::time::{Duration, Instant};

use clap::{Args, ValueEnum};
use glint_encoding::gpu_types::{Filter, View};
use glint_gpu::shaders::ShaderSource;
use glint_gpu::stitch::Placement;
use glint_gpu::{
    Acceleration, Bits, CompiledKernels, Format, Gpu, GpuError, ImageSink, PpmForm, Prepared, RayStats, Region, RenderOptions, Renderer, Samples, StagedImage,
    ToneMap, Workload,
};
use glint_scene::MAX_DEPTH_LIMIT;
use glint_scene::MAX_IMAGE_SIDE;
use indicatif::{ProgressBar, ProgressDrawTarget, ProgressStyle};

use crate::{exit, Failure};

#[derive(Args)]
pub struct RenderArgs {
    /// Scene file (.toml, .nff, .ray or .obj), or spd:NAME[:SIZE] for a generated SPD scene
    #[arg(value_parser = crate::scene_arg::parse)]
    scene: PathBuf,
    /// Output image: .png or .ppm (sRGB display values), .exr or .pfm (linear float)
    #[arg(short, long)]
    output: PathBuf,
    /// Image width in pixels (default: the scene's; alone, the scene's aspect ratio is kept)
    #[arg(long, allow_negative_numbers = true, value_parser = clap::value_parser!(u32).range(1..=i64::from(MAX_IMAGE_SIDE)))]
    width: Option<u32>,
    /// Image height in pixels (default: the scene's; alone, the scene's aspect ratio is kept)
    #[arg(long, allow_negative_numbers = true, value_parser = clap::value_parser!(u32).range(1..=i64::from(MAX_IMAGE_SIDE)))]
    height: Option<u32>,
    /// Render only the pixels X0 <= x < X1, Y0 <= y < Y1 of the image (row 0 at
    /// the top), exactly as they are in the whole render; where they belong is
    /// written beside each output as OUTPUT.json, for `glint stitch`
    #[arg(long, num_args = 4, value_names = ["X0", "Y0", "X1", "Y1"], conflicts_with = "shard")]
    region: Option<Vec<u32>>,
    /// Render the I-th of N horizontal strips of the image (I from 0 to N-1),
    /// as --region would, for `glint stitch` to assemble
    #[arg(long, value_name = "I/N", value_parser = parse_shard)]
    shard: Option<(u32, u32)>,
    /// Longest ray path, the eye ray counting as depth 1 (default: the scene's, else 5)
    #[arg(long, allow_negative_numbers = true, value_parser = clap::value_parser!(u32).range(1..=i64::from(MAX_DEPTH_LIMIT)))]
    max_depth: Option<u32>,
    /// Trace every reflection and refraction ray to the maximum depth, however
    /// little it contributes (as classic benchmark procedures require)
    #[arg(long)]
    no_cutoff: bool,
    #[command(flatten)]
    effects: crate::effects::EffectArgs,
    /// How an NFF file's `angle` is read: from the centres of the outer pixel rows
    /// (the NFF text) or from the image edges (what many exporters write)
    #[arg(long, value_enum, default_value_t = NffAngleArg::Centers)]
    nff_angle: NffAngleArg,
    /// Samples per pixel, stratified and jittered (1: through each pixel centre)
    #[arg(long, default_value_t = 1, allow_negative_numbers = true, value_parser = clap::value_parser!(u32).range(1..=4096))]
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
    /// Bits per channel of PNG and PPM output
    #[arg(long, value_enum, default_value_t = BitsArg::Eight)]
    bits: BitsArg,
    /// Write a .ppm output as plain PPM (P3: the samples as decimal text)
    /// rather than raw (P6: bytes), as Netpbm's -plain does
    #[arg(long)]
    plain: bool,
    /// Multiply linear radiance by this before tone mapping
    #[arg(long, default_value_t = 1.0, allow_negative_numbers = true, value_parser = finite_positive)]
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
    /// Trace tiles of at most N pixels, as if the device could hold no more
    /// (for tests of tiled rendering on any device)
    #[arg(long, value_name = "N", hide = true, value_parser = clap::value_parser!(u64).range(1..))]
    max_tile_pixels: Option<u64>,
    #[command(flatten)]
    animation: crate::frames::FrameArgs,
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
    #[value(alias = "normals")]
    Normal,
    Depth,
    Albedo,
    Diffuse,
    Id,
    Heatmap,
    RayDepth,
    RayCount,
}

impl ViewArg {
    fn view(self) -> View {
        match self {
            ViewArg::Shaded => View::Shaded,
            ViewArg::Normal => View::Normal,
            ViewArg::Depth => View::Depth,
            ViewArg::Albedo => View::Albedo,
            ViewArg::Diffuse => View::Diffuse,
            ViewArg::Id => View::Id,
            ViewArg::Heatmap => View::Heatmap,
            ViewArg::RayDepth => View::RayDepth,
            ViewArg::RayCount => View::RayCount,
        }
    }
}

fn parse_aov(s: &str) -> Result<(ViewArg, PathBuf), String> {
    let (name, path) = s.split_once('=').ok_or("expected NAME=PATH")?;
    let view = match name {
        "depth" => ViewArg::Depth,
        "normal" | "normals" => ViewArg::Normal,
        "albedo" => ViewArg::Albedo,
        "id" => ViewArg::Id,
        other => {
            let names = ["depth", "normal", "albedo", "id"];
            let hint = glint_scene::suggest::nearest(other, names).map_or(String::new(), |n| format!(" (did you mean `{n}`?)"));
            return Err(format!("unknown AOV `{other}`{hint}: the AOVs are depth, normal, albedo and id"));
        }
    };
    let path = PathBuf::from(path);
    match Format::from_path(&path) {
        Ok(Format::Exr | Format::Pfm) => Ok((view, path)),
        _ => Err(format!("{}: an AOV is written as .pfm or .exr", path.display())),
    }
}

fn parse_shard(s: &str) -> Result<(u32, u32), String> {
    let numbers = s.split_once('/').and_then(|(i, n)| Some((i.parse::<u32>().ok()?, n.parse::<u32>().ok()?)));
    match numbers {
        Some((_, 0)) => Err(format!("`{s}`: N, the number of shards, must be at least 1")),
        Some((i, n)) if i >= n => {
            Err(format!("`{s}`: shards count from 0, so I must be below N (0/{n} to {}/{n})", n - 1))
        }
        Some(shard) => Ok(shard),
        None => Err(format!("`{s}` is not I/N: give the shard's index from 0 and the number of shards, as in 0/4")),
    }
}

/// The part of the `width` × `height` image to render: all of it, the
/// `--region` or the `--shard`.
fn render_region(args: &RenderArgs, width: u32, height: u32) -> Result<Region, Failure> {
    if let Some(&[x0, y0, x1, y1]) = args.region.as_deref() {
        let region = Region { x0, y0, x1, y1 };
        if region.is_empty() || !Region::whole(width, height).contains(&region) {
            return Err(Failure::new(
                exit::USAGE,
                format!("--region {region}: must be X0 < X1 <= {width} and Y0 < Y1 <= {height}, inside the {width}x{height} image"),
            ));
        }
        return Ok(region);
    }
    match args.shard {
        Some((_, count)) if count > height => Err(Failure::new(
            exit::USAGE,
            format!("--shard: the {width}x{height} image has only {height} rows, so it splits into at most {height} shards, not {count}"),
        )),
        Some((index, count)) => Ok(Region::whole(width, height).strip(index, count)),
        None => Ok(Region::whole(width, height)),
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
        Ok(_) => Err(format!("the exposure must be a positive number, found {s} (1 leaves the radiance as it is, 2 doubles it)")),
        Err(_) => Err(format!("`{s}` is not a number: the exposure is a positive number such as 0.5 or 2")),
    }
}

/// Refuses, before any work, an output path whose format Glint cannot write
/// (a usage error) or that cannot be created (the output code).
pub fn check_output(path: &std::path::Path) -> Result<(), Failure> {
    glint_gpu::check_output_path(path).map(|_| ()).map_err(|e| match e {
        glint_gpu::OutputPathError::Format(m) => Failure::new(exit::USAGE, m),
        glint_gpu::OutputPathError::Unwritable(m) => Failure::new(exit::OUTPUT, m),
    })
}

/// The image size: both sides as given; one side alone keeps the scene's
/// aspect ratio (the other side rounded to whole pixels); neither, the scene's.
fn image_size(width: Option<u32>, height: Option<u32>, scene: (u32, u32)) -> Result<(u32, u32), Failure> {
    let (sw, sh) = (f64::from(scene.0), f64::from(scene.1));
    let other = |given: u32, ratio: f64, option: &str, missing: &str| -> Result<u32, Failure> {
        let side = (f64::from(given) * ratio).round().max(1.0);
        if side > f64::from(MAX_IMAGE_SIDE) {
            return Err(Failure::new(
                exit::USAGE,
                format!(
                    "--{option} {given} on this {}x{} scene would make the {missing} {side}, beyond {MAX_IMAGE_SIDE}: give --{missing} too",
                    scene.0, scene.1
                ),
            ));
        }
        Ok(side as u32)
    };
    Ok(match (width, height) {
        (Some(w), Some(h)) => (w, h),
        (Some(w), None) => (w, other(w, sh / sw, "width", "height")?),
        (None, Some(h)) => (other(h, sw / sh, "height", "width")?, h),
        (None, None) => scene,
    })
}

/// Options that the chosen view or sample count makes pointless, one warning each.
fn option_warnings(args: &RenderArgs) -> Vec<String> {
    let mut warnings = Vec::new();
    let view = args.view.view();
    let name = args.view.to_possible_value().map_or(String::new(), |v| v.get_name().to_string());
    if view.is_primary_only() {
        let mut ignored = Vec::new();
        if args.spp > 1 {
            ignored.push(format!("--spp {}", args.spp));
        }
        if matches!(args.filter, FilterArg::Tent) {
            ignored.push("--filter tent".to_string());
        }
        if !ignored.is_empty() {
            warnings.push(format!(
                "--view {name} traces one ray through each pixel centre, so {} {} ignored",
                ignored.join(" and "),
                if ignored.len() == 1 { "is" } else { "are" }
            ));
        }
        let mapped = matches!(view, View::Normal | View::Depth | View::Id | View::Heatmap);
        if mapped && (args.exposure != 1.0 || !matches!(args.tone_map, ToneMapArg::Clamp)) {
            warnings.push(format!("--view {name} maps its values to colours itself, so --exposure and --tone-map are ignored"));
        }
    } else if args.spp == 1 && matches!(args.filter, FilterArg::Tent) {
        warnings.push("--filter tent has no effect with one sample per pixel (the pixel centre): add --spp 4 or more".into());
    }
    warnings
}

pub fn run(args: &RenderArgs) -> Result<(), Failure> {
    // Refuse an output path that cannot be written before doing any work.
    check_output(&args.output)?;
    if args.plain && Format::from_path(&args.output).ok() != Some(Format::Ppm) {
        return Err(Failure::new(exit::USAGE, format!("--plain: it writes a plain PPM (P3), but {} is not a .ppm", args.output.display())));
    }
    for (_, path) in &args.aov {
        check_output(path)?;
    }
    for warning in option_warnings(args) {
        eprintln!("glint: warning: {warning}");
    }

    let load_options = glint_scene::LoadOptions {
        nff_angle: match args.nff_angle {
            NffAngleArg::Centers => glint_scene::nff::NffAngle::Centers,
            NffAngleArg::Edges => glint_scene::nff::NffAngle::Edges,
        },
    };
    let mut scene = glint_scene::load_with(&args.scene, &load_options).map_err(|e| Failure::new(exit::INPUT, e))?;
    for warning in &scene.warnings {
        eprintln!("glint: warning: {warning}");
    }
    let (width, height) = image_size(args.width, args.height, (scene.width, scene.height))?;
    let region = render_region(args, width, height)?;
    let outputs: Vec<&Path> = std::iter::once(&args.output).chain(args.aov.iter().map(|(_, p)| p)).map(PathBuf::as_path).collect();
    let plan = args.animation.plan(&scene, &outputs, region == Region::whole(width, height))?;
    for path in plan.all_paths() {
        check_output(&path)?;
    }
    scene.set_frame(plan.frames.start);
    if let Some(d) = args.max_depth {
        scene.render.max_depth = d;
    }
    if args.no_cutoff {
        scene.render.cutoff = 0.0;
    }
    args.effects.apply(&mut scene.render);

    let rendered_scenes = glint_gpu::RenderedScenes::on_this_machine();
    let frames = plan.frames.len() as u64;
    let eye_rays = u64::from(width) * u64::from(height) * frames;
    let workload = Workload::render(eye_rays, samples(args, region, frames), rendered_scenes.contains(&args.scene));
    let (renderer, mut prepared) = prepare_on_device(&scene, (width, height), args, workload)?;

    let view = args.view.view();
    let views: Vec<View> = std::iter::once(view).chain(args.aov.iter().map(|(aov, _)| aov.view())).collect();
    prepared.buffers.specialization = prepared.buffers.specialization.for_views(&views);
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
    let (mut stats, mut legend) = (RayStats::default(), None);
    let count = plan.frames.len() as u64;
    // The device keeps the scene and its BVH; a frame writes only its camera and lights.
    for (i, frame) in plan.frames.clone().enumerate() {
        scene.set_frame(frame);
        renderer.pose(&mut prepared, &scene)?;
        let options = RenderOptions { view_scale: prepared.view_scale(view), ..options };
        let paths = |path: &Path| plan.path(path, frame);
        let (frame_stats, summary) = render_frame(&renderer, &prepared, region, &options, args, &paths, &mut |done, total| {
            if start.elapsed() > Duration::from_secs(1) && bar.is_hidden() && !args.quiet && std::io::stderr().is_terminal() {
                bar.set_draw_target(ProgressDrawTarget::stderr());
            }
            bar.set_length(total * count);
            bar.set_position(i as u64 * total + done);
        })?;
        stats += frame_stats;
        // A legend tells one image's range.
        if count == 1 {
            legend = crate::legend::legend(&summary, options.view_scale, prepared.bvh_nodes, scene.objects.len());
        }
    }
    let elapsed = start.elapsed();
    bar.finish_and_clear();
    rendered_scenes.insert(&args.scene);

    if !args.quiet {
        let part = if region != Region::whole(width, height) { format!(" (region {region} of {width}x{height})") } else { String::new() };
        let (frames, written) = match count {
            1 => (String::new(), plan.path(&args.output, plan.frames.start).display().to_string()),
            n => (format!("{n} frames of "), format!("{} (frames {}..{})", args.output.display(), plan.frames.start, plan.frames.end)),
        };
        eprintln!(
            "glint: rendered {frames}{}x{}{part} in {:.3} s, {:.2} Mrays/s ({} rays) -> {written}",
            region.width(),
            region.height(),
            elapsed.as_secs_f64(),
            stats.total() as f64 / elapsed.as_secs_f64() / 1e6,
            stats.total(),
        );
        if let Some(legend) = legend {
            eprintln!("glint: {legend}");
        }
    }
    plan.encode_video(args.quiet)?;
    if args.stats {
        print_stats(&stats, renderer.profile().kernels, args.json);
    }
    Ok(())
}

/// Renders one frame: the output and its AOVs, at `paths` of the names given.
/// Every file is complete under a temporary name before any appears, so a
/// failure writes none of them.
fn render_frame(
    renderer: &Renderer,
    prepared: &Prepared,
    region: Region,
    options: &RenderOptions,
    args: &RenderArgs,
    paths: &dyn Fn(&Path) -> PathBuf,
    progress: &mut dyn FnMut(u64, u64),
) -> Result<(RayStats, crate::legend::Summary), Failure> {
    let bits = match args.bits {
        BitsArg::Eight => Bits::Eight,
        BitsArg::Sixteen => Bits::Sixteen,
    };
    let samples = Samples { bits, ppm: if args.plain { PpmForm::Plain } else { PpmForm::Raw } };
    let (width, height) = (prepared.buffers.width(), prepared.buffers.height());
    let part = (region != Region::whole(width, height)).then_some(Placement { width, height, region, shard: args.shard });
    let output = paths(&args.output);
    let (main, stats, summary) = render_to_file(renderer, &prepared.buffers, region, options, &output, samples, progress)?;
    let mut staged = vec![(main, output)];
    for (aov, path) in &args.aov {
        let aov_view = aov.view();
        let aov_options = RenderOptions { view: aov_view, spp: 1, view_scale: prepared.view_scale(aov_view), ..*options };
        let path = paths(path);
        staged.push((render_to_file(renderer, &prepared.buffers, region, &aov_options, &path, samples, &mut |_, _| {})?.0, path));
    }
    for (file, path) in staged {
        file.commit().map_err(GpuError::from)?;
        if let Some(placement) = &part {
            glint_gpu::stitch::write_placement(&path, placement).map_err(GpuError::from)?;
        }
    }
    Ok((stats, summary))
}

/// Renders `region` with `options` into the file for `path`, each tile going
/// to the file as it is read back (a depth view's misses as +∞) and into the
/// summary its legend is made from; the file is complete but not yet at `path`.
fn render_to_file(
    renderer: &Renderer,
    buffers: &glint_gpu::SceneBuffers,
    region: Region,
    options: &RenderOptions,
    path: &Path,
    samples: Samples,
    progress: &mut dyn FnMut(u64, u64),
) -> Result<(StagedImage, RayStats, crate::legend::Summary), Failure> {
    let mut sink =
        ImageSink::create(path, region.width(), region.height(), samples, crate::legend::channels(options.view)).map_err(GpuError::from)?;
    let mut summary = crate::legend::Summary::new(options.view);
    let stats = renderer.render_tiles(buffers, region, options, progress, &mut |tile, pixels| {
        let pixels = if options.view == View::Depth { pixels.with_misses_at_infinity() } else { pixels };
        summary.add(&pixels);
        sink.paste(&pixels, tile.x0 - region.x0, tile.y0 - region.y0).map_err(GpuError::from)
    })?;
    Ok((sink.finish().map_err(GpuError::from)?, stats, summary))
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

/// The samples a render command traces in all: per pixel of the region and
/// frame, the output's samples and one per AOV.
fn samples(args: &RenderArgs, region: Region, frames: u64) -> u64 {
    let per_pixel = if args.view.view().is_primary_only() { 1 } else { u64::from(args.spp) } + args.aov.len() as u64;
    u64::from(region.width()) * u64::from(region.height()) * frames * per_pixel
}

/// A renderer and `scene` on its device for an image of `size`: a device of
/// WebGPU's default limits, opened again with the adapter's own value of a
/// limit the scene needs more of.
fn prepare_on_device(scene: &glint_scene::Scene, size: (u32, u32), args: &RenderArgs, workload: Workload) -> Result<(Renderer, Prepared), Failure> {
    let mut gpu = Gpu::for_workload(&workload)?;
    if let Some(warning) = gpu.driver_warning() {
        eprintln!("glint: {warning}");
    }
    loop {
        let renderer = Renderer::new(gpu.device.clone(), gpu.queue.clone(), &ShaderSource::Embedded)?.plan(workload);
        let renderer = match args.max_tile_pixels {
            Some(pixels) => renderer.with_max_tile_pixels(pixels),
            None => renderer,
        };
        let error = match renderer.prepare(scene, size.0, size.1, Acceleration::Bvh) {
            Ok(prepared) => return Ok((renderer, prepared)),
            Err(error) => error,
        };
        match gpu.raised_for(&error) {
            Some(raised) => {
                if !args.quiet {
                    eprintln!("glint: {error}, WebGPU's default; asking the adapter for more");
                }
                gpu = raised?;
            }
            None => return Err(error.into()),
        }
    }
}

/// The rays traced, and where the device profile chooses the driver's
/// kernels, whether they skipped LLVM's optimisation passes (`quick_kernels`)
/// and their SIMD width (`vector_bits`).
fn print_stats(stats: &RayStats, kernels: Option<CompiledKernels>, json: bool) {
    if json {
        let mut value = serde_json::json!({
            "eye_hit": stats.eye_hit,
            "eye_miss": stats.eye_miss,
            "shadow": stats.shadow,
            "reflect": stats.reflect,
            "refract": stats.refract,
        });
        if let Some(CompiledKernels { quick, vector_bits }) = kernels {
            value["quick_kernels"] = quick.into();
            value["vector_bits"] = vector_bits.into();
        }
        println!("{value}");
    } else {
        if let Some(CompiledKernels { quick, vector_bits: bits }) = kernels {
            let how = if quick { "quickly, without LLVM's optimisation passes (a first, small render)" } else { "optimised" };
            let width = bits.map_or_else(String::new, |bits| format!(", {bits}-bit vectors"));
            println!("kernels compiled {how}{width}");
        }
        println!("eye rays (hit):  {}", stats.eye_hit);
        println!("eye rays (miss): {}", stats.eye_miss);
        println!("shadow rays:     {}", stats.shadow);
        println!("reflection rays: {}", stats.reflect);
        println!("refraction rays: {}", stats.refract);
        println!("total:           {}", stats.total());
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn one_given_side_keeps_the_aspect_ratio() {
        let size = |w, h| image_size(w, h, (320, 240)).map_err(|f| f.message);
        assert_eq!(size(Some(640), None), Ok((640, 480)));
        assert_eq!(size(None, Some(120)), Ok((160, 120)));
        assert_eq!(size(Some(100), Some(100)), Ok((100, 100)));
        assert_eq!(size(None, None), Ok((320, 240)));
        assert_eq!(size(Some(1), None), Ok((1, 1)), "never less than a pixel");
        assert_eq!(image_size(Some(101), None, (640, 400)).map_err(|f| f.message), Ok((101, 63)), "rounded");
        let e = image_size(None, Some(16384), (640, 400)).unwrap_err();
        assert_eq!(e.code, exit::USAGE);
        assert!(e.message.contains("give --width too"), "{}", e.message);
    }
}
