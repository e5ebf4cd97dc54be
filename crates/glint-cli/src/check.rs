//! `glint check`: load and validate scenes without a GPU, and summarise them.
//!
//! Nothing here touches wgpu: a check is as fast as loading the file, so it
//! suits an editor's save hook. Errors and warnings are printed as by `glint
//! render` (`glint: FILE:LINE:COL: …` on stderr); the summary goes to stdout.

use std::path::PathBuf;

use clap::{Args, ValueEnum};
use glam::Vec3;
use glint_scene::{LightKind, Projection, Scene, Shape, SHAPE_NAMES};

use crate::{exit, Failure};

#[derive(Args)]
pub struct CheckArgs {
    /// Scene files (.toml, .nff, .ray or .obj), or spd:NAME[:SIZE] for generated SPD scenes
    #[arg(required = true, value_parser = crate::scene_arg::parse)]
    scenes: Vec<PathBuf>,
    /// How an NFF file's `angle` is read (as for `glint render`)
    #[arg(long, value_enum, default_value_t = NffAngleArg::Centers)]
    nff_angle: NffAngleArg,
    /// Print only errors and warnings, no summary
    #[arg(short, long)]
    quiet: bool,
}

#[derive(Clone, Copy, ValueEnum)]
enum NffAngleArg {
    Centers,
    Edges,
}

pub fn run(args: &CheckArgs) -> Result<(), Failure> {
    let options = glint_scene::LoadOptions {
        nff_angle: match args.nff_angle {
            NffAngleArg::Centers => glint_scene::nff::NffAngle::Centers,
            NffAngleArg::Edges => glint_scene::nff::NffAngle::Edges,
        },
    };
    let mut failed = 0;
    for (i, path) in args.scenes.iter().enumerate() {
        let checked = glint_scene::load_with(path, &options)
            .map_err(|e| e.to_string())
            .and_then(|scene| scene.validate().map(|()| scene).map_err(|e| format!("{}: {e}", path.display())));
        match checked {
            Ok(mut scene) => {
                scene.warnings.extend(material_notes(path));
                for warning in &scene.warnings {
                    eprintln!("glint: warning: {warning}");
                }
                if !args.quiet {
                    if i > 0 {
                        println!();
                    }
                    print!("{}", summary(&path.display().to_string(), &scene));
                }
            }
            Err(message) => {
                eprintln!("glint: {message}");
                failed += 1;
            }
        }
    }
    match failed {
        0 => Ok(()),
        // Each error is printed already.
        _ => Err(Failure::explained(exit::INPUT)),
    }
}

/// What a TOML scene's materials suggest was forgotten (see
/// [`glint_scene::toml_scene::material_notes`]); warnings only `glint check` gives.
fn material_notes(path: &std::path::Path) -> Vec<glint_scene::LoadError> {
    let is_toml = path.extension().is_some_and(|e| e.eq_ignore_ascii_case("toml"));
    match std::fs::read_to_string(path) {
        Ok(source) if is_toml => glint_scene::toml_scene::material_notes(&source, path),
        _ => Vec::new(),
    }
}

/// A number in at most four significant decimals, without trailing zeros.
fn num(v: f64) -> String {
    let v = if v == 0.0 { 0.0 } else { v };
    let digits = if v.abs() >= 1000.0 { 1 } else { 4 };
    let s = format!("{v:.digits$}");
    let s = if s.contains('.') { s.trim_end_matches('0').trim_end_matches('.').to_string() } else { s };
    if s == "-0" { "0".into() } else { s }
}

fn vector(v: glam::DVec3) -> String {
    format!("({}, {}, {})", num(v.x), num(v.y), num(v.z))
}

fn colour(c: Vec3) -> String {
    if c.x == c.y && c.y == c.z {
        num(f64::from(c.x))
    } else {
        format!("[{}, {}, {}]", num(f64::from(c.x)), num(f64::from(c.y)), num(f64::from(c.z)))
    }
}

/// "3 spheres, 1 cone": the non-zero counts, named in the singular or plural.
fn counts(parts: &[(usize, &str, &str)]) -> String {
    let named: Vec<String> = parts
        .iter()
        .filter(|(n, _, _)| *n > 0)
        .map(|&(n, one, many)| format!("{n} {}", if n == 1 { one } else { many }))
        .collect();
    if named.is_empty() { "none".into() } else { named.join(", ") }
}

/// The summary `glint check` prints for a scene that loaded.
pub fn summary(name: &str, scene: &Scene) -> String {
    let mut out = format!("{name}: ok\n");
    let mut line = |label: &str, text: String| out.push_str(&format!("  {label:<11}{text}\n"));
    line("image", format!("{} x {}, background {}", scene.width, scene.height, colour(scene.background)));
    let projection = match scene.camera.projection {
        Projection::Perspective { fov_y_degrees } => format!("perspective, vertical field of view {}°", num(f64::from(fov_y_degrees))),
        Projection::Orthographic { height } => format!("orthographic, view window {} high", num(f64::from(height))),
    };
    line("camera", projection);
    let basis = scene.camera.basis().expect("a loaded scene's camera has a basis");
    line("", format!("e = {}  the eye", vector(scene.camera.eye.as_dvec3())));
    line("", format!("u = {}  right", vector(basis.u)));
    line("", format!("v = {}  up", vector(basis.v)));
    line("", format!("w = {}  backwards, from look_at to the eye", vector(basis.w)));

    let shapes = || scene.objects.iter().flat_map(|o| &o.shapes);
    let mut per_name = SHAPE_NAMES.map(|name| (0, name, format!("{name}s")));
    for shape in shapes() {
        per_name.iter_mut().find(|(_, name, _)| *name == shape.name()).expect("SHAPE_NAMES holds every name").0 += 1;
    }
    let primitives = counts(&per_name.iter().map(|(n, one, many)| (*n, *one, many.as_str())).collect::<Vec<_>>());
    let planes = shapes().filter(|s| !s.is_bounded()).count();
    let n = scene.primitive_count();
    line("objects", format!("{}, made of {n} primitive{}: {primitives}", scene.objects.len(), if n == 1 { "" } else { "s" }));

    let point = scene.lights.iter().filter(|l| matches!(l.kind, LightKind::Point { .. })).count();
    let directional = scene.lights.len() - point;
    let off = scene.lights.iter().filter(|l| !l.enabled).count();
    let mut lights = format!("{}: {}", scene.lights.len(), counts(&[(point, "point", "point"), (directional, "directional", "directional")]));
    if off > 0 {
        lights.push_str(&format!(" ({off} switched off)"));
    }
    line("lights", format!("{lights}; ambient {}", colour(scene.ambient)));

    let bounds = scene
        .objects
        .iter()
        .flat_map(|o| o.shapes.iter().filter_map(Shape::bounds))
        .reduce(|(a, b), (c, d)| (a.min(c), b.max(d)));
    let unbounded = if planes > 0 { " and infinite planes" } else { "" };
    line(
        "bounds",
        match bounds {
            Some((lo, hi)) => format!("{} to {}{unbounded}", vector(lo.as_dvec3()), vector(hi.as_dvec3())),
            None if planes > 0 => "infinite planes only".into(),
            None => "none (no objects)".into(),
        },
    );

    const SHOWN: usize = 12;
    let mut names: Vec<&str> = scene.materials.iter().take(SHOWN).map(|m| m.name.as_str()).collect();
    if scene.materials.len() > SHOWN {
        names.push("…");
    }
    line("materials", format!("{}: {}", scene.materials.len(), names.join(", ")));

    let r = &scene.render;
    let on = |b: bool| if b { "on" } else { "off" };
    let shadows = match (r.shadows, r.shadow_mode) {
        (false, _) => "off",
        (true, glint_scene::ShadowMode::Opaque) => "opaque",
        (true, glint_scene::ShadowMode::Tinted) => "tinted",
    };
    let mut render = format!(
        "max depth {}, cutoff {}, shadows {shadows}, reflections {}, refractions {}",
        r.max_depth,
        num(f64::from(r.cutoff)),
        on(r.reflections),
        on(r.refractions)
    );
    if let Some(cue) = &scene.depth_cue {
        render.push_str(&format!("; depth cue from {} to {}", num(f64::from(cue.near)), num(f64::from(cue.far))));
    }
    line("render", render);
    let transmitters = scene.objects.iter().any(|o| scene.materials.get(o.material).is_some_and(|m| m.is_transmissive()));
    if transmitters && r.shadows && r.shadow_mode == glint_scene::ShadowMode::Opaque {
        line("", "glass casts black shadows and blocks light from inside; shadow_mode = \"tinted\" in [render] lets light through".into());
    }
    if let Some(a) = &scene.animation {
        use glint_scene::animation::{CameraTrack, Interpolation};
        let mut moves = vec![match &a.camera {
            None => "the camera still".to_string(),
            Some(CameraTrack::Orbit(o)) => {
                let s = if o.turns.abs() == 1.0 { "" } else { "s" };
                format!("the camera orbiting {} turn{s} about {}", num(f64::from(o.turns)), vector(o.center.as_dvec3()))
            }
            Some(CameraTrack::Keys(keys)) => counts(&[(keys.len(), "camera key", "camera keys")]),
        }];
        if !a.lights.is_empty() {
            moves.push(counts(&[(a.lights.len(), "light keyed", "lights keyed")]));
        }
        if matches!(a.camera, Some(CameraTrack::Keys(_))) || !a.lights.is_empty() {
            moves.push(format!("{} interpolation", if a.interpolation == Interpolation::Smooth { "smooth" } else { "linear" }));
        }
        line("animation", format!("{} frames at {} fps: {}", a.frames, num(f64::from(a.fps)), moves.join(", ")));
    }
    line("warnings", if scene.warnings.is_empty() { "none".into() } else { format!("{} (on stderr)", scene.warnings.len()) });
    out
}
