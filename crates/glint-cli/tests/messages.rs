//! Messages that teach and checks before work (issue 19), through the real
//! binary: usage errors in full, output paths refused before any work,
//! warnings for likely mistakes, legends for the debug views, one-channel
//! data AOVs, the aspect ratio of a one-sided size, `glint check` and `glint
//! view` without a display.

use std::path::{Path, PathBuf};
use std::process::{Command, Output};

fn glint_in(dir: Option<&Path>, env: &[(&str, Option<&str>)], args: &[&str]) -> Output {
    let mut command = Command::new(env!("CARGO_BIN_EXE_glint"));
    command.args(args);
    if let Some(dir) = dir {
        command.current_dir(dir);
    }
    for (name, value) in env {
        match value {
            Some(v) => command.env(name, v),
            None => command.env_remove(name),
        };
    }
    command.output().expect("glint runs")
}

fn glint(args: &[&str]) -> Output {
    glint_in(None, &[], args)
}

fn showcase() -> String {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../../scenes/showcase.toml").display().to_string()
}

fn stderr(o: &Output) -> String {
    String::from_utf8_lossy(&o.stderr).into_owned()
}

fn stdout(o: &Output) -> String {
    String::from_utf8_lossy(&o.stdout).into_owned()
}

fn files_in(dir: &Path) -> Vec<String> {
    let mut names: Vec<String> = std::fs::read_dir(dir).unwrap().map(|e| e.unwrap().file_name().to_string_lossy().into_owned()).collect();
    names.sort();
    names
}

/// A small scene with the given extra TOML, written into `dir`.
fn scene(dir: &Path, name: &str, camera_fov: &str, extra: &str) -> PathBuf {
    let text = format!(
        "[image]\nwidth = 32\nheight = 24\n\n[camera]\neye = [0, 0, 5]\nlook_at = [0, 0, 0]\nfov = {camera_fov}\n\n\
[[light]]\ntype = \"point\"\nposition = [0, 3, 4]\n\n{extra}"
    );
    let path = dir.join(name);
    std::fs::write(&path, text).unwrap();
    path
}

#[test]
fn usage_errors_are_shown_in_full_as_clap_explains_them() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("out.png").display().to_string();
    let s = showcase();
    let cases: &[(&[&str], &[&str])] = &[
        (&["render", "a.toml"], &["the following required arguments were not provided", "--output <OUTPUT>", "Usage: glint render"]),
        (&["render", &s, "-o", &out, "--json"], &["the following required arguments were not provided", "--stats"]),
        (&["rendr", &s], &["unrecognized subcommand 'rendr'", "a similar subcommand exists: 'render'"]),
        (&["render", &s, "-o", &out, "--view", "depht"], &["[possible values: shaded, normal, depth, albedo, diffuse, id, heatmap, ray-depth, ray-count]"]),
        (&["render", &s, "-o", &out, "--tone-map", "filmic"], &["[possible values: clamp, reinhard, aces]"]),
        (&["render", &s, "-o", &out, "--exposure", "-1"], &["'--exposure <EXPOSURE>': the exposure must be a positive number, found -1"]),
        (&["render", &s, "-o", &out, "--aov", "dpeth=d.pfm"], &["unknown AOV `dpeth` (did you mean `depth`?)"]),
    ];
    for (args, needles) in cases {
        let o = glint(args);
        let err = stderr(&o);
        assert_eq!(o.status.code(), Some(2), "{args:?}: {err}");
        assert!(err.starts_with("glint: "), "{args:?}: {err}");
        for needle in *needles {
            assert!(err.contains(needle), "{args:?}: `{needle}` missing in:\n{err}");
        }
        assert!(!err.contains("panicked"), "{err}");
    }
    assert!(files_in(dir.path()).is_empty());
}

#[test]
fn normal_and_normals_are_one_view_shown_once_in_help() {
    let dir = tempfile::tempdir().unwrap();
    let p = |name: &str| dir.path().join(name).display().to_string();
    for (view, aov) in [("normal", "normals"), ("normals", "normal")] {
        let o = glint(&[
            "render", &showcase(), "-o", &p(&format!("{view}.png")), "--width", "24", "--view", view, "--aov",
            &format!("{aov}={}", p(&format!("{aov}.pfm"))), "-q",
        ]);
        assert!(o.status.success(), "{view}: {}", stderr(&o));
    }
    assert_eq!(std::fs::read(p("normal.png")).unwrap(), std::fs::read(p("normals.png")).unwrap());
    assert_eq!(std::fs::read(p("normal.pfm")).unwrap(), std::fs::read(p("normals.pfm")).unwrap());
    let help = stdout(&glint(&["render", "--help"]));
    assert!(help.contains("shaded, normal, depth"), "{help}");
    assert!(!help.contains("normals"), "the alias is not advertised:\n{help}");
}

#[test]
fn a_bad_output_path_is_refused_before_any_work() {
    let dir = tempfile::tempdir().unwrap();
    let missing_dir = dir.path().join("nodir/out.png").display().to_string();
    // A scene that does not exist either: the output path is checked first.
    let no_scene = dir.path().join("no-such-scene.toml").display().to_string();
    let o = glint(&["render", &no_scene, "-o", &missing_dir]);
    assert_eq!(o.status.code(), Some(5), "{}", stderr(&o));
    assert_eq!(stderr(&o), format!("glint: {missing_dir}: cannot write there: the directory `{}` does not exist\n", dir.path().join("nodir").display()));
    // An expensive render is never started.
    let o = glint(&["render", &showcase(), "-o", &missing_dir, "--spp", "4096", "--width", "4096", "--height", "4096"]);
    assert_eq!(o.status.code(), Some(5), "{}", stderr(&o));
    assert!(!stderr(&o).contains("rendered"), "{}", stderr(&o));
    // The same for an AOV's path, and for a directory named as the output.
    let good = dir.path().join("ok.png").display().to_string();
    let aov = format!("depth={}", dir.path().join("nodir/depth.pfm").display());
    let o = glint(&["render", &no_scene, "-o", &good, "--aov", &aov]);
    assert_eq!(o.status.code(), Some(5), "{}", stderr(&o));
    assert!(stderr(&o).contains("depth.pfm: cannot write there"), "{}", stderr(&o));
    std::fs::create_dir(dir.path().join("folder.png")).unwrap();
    let o = glint(&["render", &no_scene, "-o", &dir.path().join("folder.png").display().to_string()]);
    assert_eq!(o.status.code(), Some(5), "{}", stderr(&o));
    assert!(stderr(&o).contains("folder.png: is a directory"), "{}", stderr(&o));
    // An unknown extension stays a usage error, also before the scene is read.
    let o = glint(&["render", &no_scene, "-o", &dir.path().join("out.bmp").display().to_string()]);
    assert_eq!(o.status.code(), Some(2), "{}", stderr(&o));
    assert!(stderr(&o).contains("out.bmp: unsupported output format"), "{}", stderr(&o));
    assert_eq!(stderr(&o).lines().count(), 1, "Glint's own errors are one line: {}", stderr(&o));
    assert_eq!(files_in(dir.path()), ["folder.png"], "nothing was left behind");
}

#[test]
fn likely_mistakes_warn_with_file_and_line_and_the_render_goes_on() {
    let dir = tempfile::tempdir().unwrap();
    let path = scene(dir.path(), "mistakes.toml", "0.5", "[material.red]\ncolor = [230, 50, 25]\n\n[[object]]\ntype = \"sphere\"\ncenter = [0, 0, 0]\nradius = 1\nmaterial = \"red\"\n");
    let out = dir.path().join("out.png");
    let o = glint(&["render", path.to_str().unwrap(), "-o", out.to_str().unwrap(), "-q"]);
    assert!(o.status.success(), "{}", stderr(&o));
    let shown = path.display();
    assert_eq!(
        stderr(&o),
        format!(
            "glint: warning: {shown}:8:7: fov: 0.5° is a very narrow view; angles are in degrees (0.5 radians is 28.6)\n\
glint: warning: {shown}:15:9: color: [230, 50, 25] looks like 0–255 values, but colours are 0 to 1, so what this material colours renders white; did you mean [0.9, 0.2, 0.1]?\n"
        )
    );
    assert!(out.is_file());

    // Options the chosen view or sample count makes pointless.
    let s = showcase();
    let out = out.to_str().unwrap();
    for (extra, warning) in [
        (&["--filter", "tent"][..], "glint: warning: --filter tent has no effect with one sample per pixel (the pixel centre): add --spp 4 or more\n"),
        (&["--spp", "4", "--view", "depth"][..], "glint: warning: --view depth traces one ray through each pixel centre, so --spp 4 is ignored\n"),
        (
            &["--spp", "4", "--filter", "tent", "--view", "id"][..],
            "glint: warning: --view id traces one ray through each pixel centre, so --spp 4 and --filter tent are ignored\n",
        ),
        (&["--view", "normal", "--exposure", "2"][..], "glint: warning: --view normal maps its values to colours itself, so --exposure and --tone-map are ignored\n"),
    ] {
        let mut args = vec!["render", s.as_str(), "-o", out, "--width", "16", "-q"];
        args.extend_from_slice(extra);
        let o = glint(&args);
        assert!(o.status.success(), "{extra:?}: {}", stderr(&o));
        assert_eq!(stderr(&o), warning, "{extra:?}");
    }
    // And none for a sensible command line.
    let o = glint(&["render", &s, "-o", out, "--width", "16", "--spp", "4", "--filter", "tent", "-q"]);
    assert!(o.status.success() && stderr(&o).is_empty(), "{}", stderr(&o));
}

#[test]
fn debug_views_print_a_legend_with_their_range_and_units() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("v.png").display().to_string();
    let s = showcase();
    for (view, needles) in [
        ("depth", &["glint: depth: distance t along the eye ray in scene units, white at 0 to black at ", "nearest hit ", "farthest "][..]),
        ("heatmap", &["glint: heatmap: BVH nodes visited by each eye ray, blue at 0 through green to red at ", "this image "][..]),
        ("id", &["glint: id: object index, 0 to 5 in file order (6 objects)", "objects seen"][..]),
        ("diffuse", &["glint: diffuse: direct diffuse light Σ k_d·O_d·I_l·max(0, N·L)·V/d²", "try --exposure"][..]),
        ("normal", &["glint: normal: the unit geometric normal N", "0.5 + 0.5·N"][..]),
        ("albedo", &["glint: albedo: the diffuse colour O_d"][..]),
    ] {
        let o = glint(&["render", &s, "-o", &out, "--width", "64", "--view", view]);
        assert!(o.status.success(), "{view}: {}", stderr(&o));
        let err = stderr(&o);
        let legend: Vec<&str> = err.lines().filter(|l| l.starts_with(&format!("glint: {view}:"))).collect();
        assert_eq!(legend.len(), 1, "{view}: one legend line in:\n{err}");
        for needle in needles {
            assert!(err.contains(needle), "{view}: `{needle}` missing in:\n{err}");
        }
        // --quiet leaves it out with the timing line.
        let o = glint(&["render", &s, "-o", &out, "--width", "64", "--view", view, "-q"]);
        assert!(o.status.success() && stderr(&o).is_empty(), "{view}: {}", stderr(&o));
    }
    let o = glint(&["render", &s, "-o", &out, "--width", "64"]);
    assert_eq!(stderr(&o).lines().count(), 1, "the shaded render has no legend: {}", stderr(&o));
}

/// The channel names of an EXR file.
fn exr_channels(path: &str) -> (Vec<String>, Vec<f32>) {
    use exr::prelude::traits::*;
    let image = exr::prelude::read()
        .no_deep_data()
        .largest_resolution_level()
        .all_channels()
        .first_valid_layer()
        .all_attributes()
        .from_file(path)
        .unwrap();
    let channels = &image.layer_data.channel_data.list;
    (channels.iter().map(|c| c.name.to_string()).collect(), channels[0].sample_data.values_as_f32().collect())
}

#[test]
fn depth_and_id_are_written_as_one_channel() {
    let dir = tempfile::tempdir().unwrap();
    let p = |name: &str| dir.path().join(name).display().to_string();
    let o = glint(&[
        "render", &showcase(), "-o", &p("depth-view.pfm"), "--view", "depth", "--width", "32", "--height", "20",
        "--aov", &format!("depth={}", p("depth.exr")), "--aov", &format!("id={}", p("id.pfm")),
        "--aov", &format!("id={}", p("id.exr")), "--aov", &format!("normal={}", p("normal.pfm")), "-q",
    ]);
    assert!(o.status.success(), "{}", stderr(&o));
    for name in ["depth-view.pfm", "id.pfm"] {
        let bytes = std::fs::read(p(name)).unwrap();
        assert!(bytes.starts_with(b"Pf\n32 20\n"), "{name} is a greyscale PFM");
        let (w, h, channels, values) = glint_gpu::read_pfm_channels(&bytes).unwrap();
        assert_eq!((w, h, channels, values.len()), (32, 20, 1, 640), "{name}");
    }
    let (_, _, _, depth) = glint_gpu::read_pfm_channels(&std::fs::read(p("depth-view.pfm")).unwrap()).unwrap();
    assert_eq!(depth[0], f32::INFINITY, "the top-left pixel sees the sky");
    assert!(depth[19 * 32 + 16].is_finite() && depth[19 * 32 + 16] > 0.0, "the bottom centre sees the floor");
    let (_, _, _, ids) = glint_gpu::read_pfm_channels(&std::fs::read(p("id.pfm")).unwrap()).unwrap();
    assert_eq!(ids[0], -1.0);
    let (names, values) = exr_channels(&p("depth.exr"));
    assert_eq!(names, ["Z"]);
    assert_eq!(values, depth, "the EXR and PFM depths agree");
    let (names, values) = exr_channels(&p("id.exr"));
    assert_eq!(names, ["id"]);
    assert_eq!(values, ids);
    // Normals stay colour.
    assert!(std::fs::read(p("normal.pfm")).unwrap().starts_with(b"PF\n"));
}

fn png_size(path: &Path) -> (u32, u32) {
    image::image_dimensions(path).unwrap()
}

#[test]
fn one_side_alone_keeps_the_scene_aspect_ratio() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("a.png");
    let s = showcase(); // 640 × 400
    for (args, size) in [
        (&["--width", "320"][..], (320, 200)),
        (&["--height", "100"][..], (160, 100)),
        (&["--width", "101"][..], (101, 63)),
        (&["--width", "50", "--height", "50"][..], (50, 50)),
    ] {
        let mut all = vec!["render", s.as_str(), "-o", out.to_str().unwrap(), "-q"];
        all.extend_from_slice(args);
        let o = glint(&all);
        assert!(o.status.success(), "{args:?}: {}", stderr(&o));
        assert_eq!(png_size(&out), size, "{args:?}");
    }
    let o = glint(&["render", &s, "-o", out.to_str().unwrap(), "--height", "16384"]);
    assert_eq!(o.status.code(), Some(2), "{}", stderr(&o));
    assert_eq!(stderr(&o), "glint: --height 16384 on this 640x400 scene would make the width 26214, beyond 16384: give --width too\n");
}

#[test]
fn check_counts_infinite_planes_apart_from_the_bounds() {
    let dir = tempfile::tempdir().unwrap();
    let floor = "[[object]]\ntype = \"plane\"\npoint = [0, -1, 0]\nnormal = [0, 1, 0]\n\n";
    let ball = "[[object]]\ntype = \"sphere\"\ncenter = [0, 0, 0]\nradius = 1\n";
    let path = scene(dir.path(), "floor.toml", "40", &format!("{floor}{ball}"));
    let text = stdout(&glint(&["check", path.to_str().unwrap()]));
    assert!(text.contains("  objects    2, made of 2 primitives: 1 sphere, 1 infinite plane\n"), "{text}");
    assert!(text.contains("  bounds     (-1, -1, -1) to (1, 1, 1) and infinite planes\n"), "{text}");
    let path = scene(dir.path(), "plane.toml", "40", floor);
    assert!(stdout(&glint(&["check", path.to_str().unwrap()])).contains("  bounds     infinite planes only\n"));
}

#[test]
fn check_summarises_scenes_without_a_gpu() {
    let dir = tempfile::tempdir().unwrap();
    // Environments in which no GPU can be had: `glint info` fails in them, `glint check` does not care.
    let no_gpu: &[(&str, Option<&str>)] = &[("GLINT_ADAPTER", Some("no-such-adapter")), ("VK_ICD_FILENAMES", Some("/nonexistent.json"))];
    let info = glint_in(None, no_gpu, &["info"]);
    assert_eq!(info.status.code(), Some(4), "the environment really has no adapter: {}", stderr(&info));
    let s = showcase();
    let o = glint_in(None, no_gpu, &["check", &s, "spd:tetra:1"]);
    assert!(o.status.success(), "{}", stderr(&o));
    assert!(stderr(&o).is_empty(), "{}", stderr(&o));
    let text = stdout(&o);
    for needle in [
        &format!("{s}: ok\n"),
        "  image      640 x 400, background [0.55, 0.68, 0.85]\n",
        "  camera     perspective, vertical field of view 38°\n",
        "e = (0, 2.2, 7.5)  the eye\n",
        "u = (1, 0, 0)  right\n",
        "v = (0, 0.9806, -0.1961)  up\n",
        "w = (0, 0.1961, 0.9806)  backwards, from look_at to the eye\n",
        "  objects    6, made of 6 primitives: 3 spheres, 1 polygon, 1 cone, 1 cylinder\n",
        "  lights     2: 2 point; ambient 0.2\n",
        "  bounds     (-9, 0, -9) to (9, 2, 9)\n",
        "  materials  6: default, floor, glass, gold, mirror, red\n",
        "  render     max depth 6, cutoff 0.0039, shadows tinted, reflections on, refractions on; depth cue from 6 to 30\n",
        "  warnings   none\n",
        "spd:tetra:1: ok\n",
        "  objects    4, made of 4 primitives: 4 triangles\n",
    ] {
        assert!(text.contains(needle), "`{needle}` missing in:\n{text}");
    }

    // Warnings as in `glint render`, errors one line each, exit 3 if any scene is bad.
    let warned = scene(dir.path(), "warned.toml", "1", "");
    let bad = dir.path().join("bad.toml");
    std::fs::write(&bad, "[image]\nwidth = 8\nheight = 8\n[camera]\neye = [0, 0, 1]\nlook_at = [0, 0, 0]\nfov = 40\n[[object]]\ntype = \"sphere\"\nradus = 1\n").unwrap();
    let o = glint_in(None, no_gpu, &["check", warned.to_str().unwrap(), bad.to_str().unwrap()]);
    assert_eq!(o.status.code(), Some(3), "{}", stderr(&o));
    assert_eq!(
        stderr(&o),
        format!(
            "glint: warning: {}:8:7: fov: 1° is a very narrow view; angles are in degrees (1 radians is 57.3)\n\
glint: {}:10:1: unknown key `radus` in a sphere object; did you mean `radius`?\n",
            warned.display(),
            bad.display()
        )
    );
    assert!(stdout(&o).contains("warned.toml: ok\n") && stdout(&o).contains("  warnings   1 (on stderr)\n"), "{}", stdout(&o));
    assert!(!stdout(&o).contains("bad.toml"), "{}", stdout(&o));
    // --quiet: only the problems.
    let o = glint_in(None, no_gpu, &["check", "-q", &s]);
    assert!(o.status.success() && o.stdout.is_empty() && o.stderr.is_empty());
    // A misspelt database is a usage error, as for render.
    let o = glint(&["check", "spd:tetras"]);
    assert_eq!(o.status.code(), Some(2), "{}", stderr(&o));
}

#[test]
fn view_without_a_display_says_so_with_its_own_code() {
    let dir = tempfile::tempdir().unwrap();
    let no_display: &[(&str, Option<&str>)] = &[("DISPLAY", None), ("WAYLAND_DISPLAY", None), ("WAYLAND_SOCKET", None)];
    let unreachable: &[(&str, Option<&str>)] = &[("DISPLAY", Some(":12345")), ("WAYLAND_DISPLAY", None), ("WAYLAND_SOCKET", None)];
    for env in [no_display, unreachable] {
        // With no scene named, from a directory without scenes/: the built-in showcase.
        let o = glint_in(Some(dir.path()), env, &["view"]);
        let err = stderr(&o);
        assert_eq!(o.status.code(), Some(6), "{env:?}: {err}");
        assert!(err.starts_with("glint: cannot open a window:") && err.contains("display"), "{env:?}: {err}");
        assert_eq!(err.lines().count(), 1, "{err}");
        assert!(!err.contains(".rs:") && !err.contains(".cargo") && !err.contains("registry"), "a source path in: {err}");
        assert!(err.contains("xvfb-run"), "{err}");
    }
    assert!(files_in(dir.path()).is_empty());
}

/// The text of the first fenced block after `heading` in README.md.
fn readme_block(heading: &str) -> String {
    let readme = std::fs::read_to_string(Path::new(env!("CARGO_MANIFEST_DIR")).join("../../README.md")).unwrap();
    let after = &readme[readme.find(heading).unwrap_or_else(|| panic!("README.md has no `{heading}`"))..];
    let start = after.find("```").unwrap();
    let body = &after[start..];
    let body = &body[body.find('\n').unwrap() + 1..];
    body[..body.find("```").unwrap()].to_string()
}

#[test]
fn the_readme_first_scene_is_the_file_and_its_summary_is_what_check_prints() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("../..").canonicalize().unwrap();
    let file = std::fs::read_to_string(root.join("scenes/first.toml")).unwrap();
    assert_eq!(readme_block("## Your first scene"), file, "README.md shows scenes/first.toml as it is");
    assert!(root.join("docs/images/first-scene.png").is_file());
    let o = glint_in(Some(&root), &[], &["check", "scenes/first.toml"]);
    assert!(o.status.success() && o.stderr.is_empty(), "{}", stderr(&o));
    assert_eq!(readme_block("### Checking scenes"), stdout(&o), "README.md's example summary is current");
}

#[test]
fn check_names_objects_without_material_unused_materials_and_tinted_shadows() {
    let dir = tempfile::tempdir().unwrap();
    let extra = "[material.glass]\ncolor = 0.1\ntransmit = 0.9\nior = 1.5\n[material.blue]\ncolor = [0.1, 0.1, 0.9]\n\n\
[[object]]\ntype = \"sphere\"\ncenter = [0, 0, 0]\nradius = 1\nmaterial = \"glass\"\n\n\
[[object]]\ntype = \"sphere\"\ncenter = [2, 0, 0]\nradius = 0.5\n";
    let path = scene(dir.path(), "student.toml", "40", extra);
    let o = glint(&["check", path.to_str().unwrap()]);
    assert!(o.status.success(), "{}", stderr(&o));
    let shown = path.display();
    assert_eq!(
        stderr(&o),
        format!(
            "glint: warning: {shown}:18:1: material.blue: defined but never used: no object has `material = \"blue\"`\n\
glint: warning: {shown}:27:1: object: this sphere has no `material`, so it gets the default, a matte light grey\n"
        )
    );
    let tinted = "             glass casts black shadows and blocks light from inside; shadow_mode = \"tinted\" in [render] lets light through\n";
    assert!(stdout(&o).contains(&format!("shadows opaque, reflections on, refractions on\n{tinted}")), "{}", stdout(&o));
    std::fs::write(&path, std::fs::read_to_string(&path).unwrap() + "\n[render]\nshadow_mode = \"tinted\"\n").unwrap();
    let o = glint(&["check", path.to_str().unwrap()]);
    assert!(o.status.success() && !stdout(&o).contains("glass casts"), "{}", stdout(&o));
}

#[test]
fn probe_says_along_for_shadow_rays_and_why_glass_blocks_its_own() {
    let dir = tempfile::tempdir().unwrap();
    let glass = "[material.glass]\ncolor = [0.1, 0.1, 0.1]\ntransmit = 0.9\nior = 1.5\n\n\
[[object]]\ntype = \"sphere\"\ncenter = [0, 0, 0]\nradius = 1\nmaterial = \"glass\"\n";
    let path = scene(dir.path(), "glass.toml", "20", glass);
    let o = glint(&["probe", path.to_str().unwrap(), "16", "12"]);
    assert!(o.status.success(), "{}", stderr(&o));
    let out = stdout(&o);
    let shadows: Vec<&str> = out.lines().filter(|l| l.contains("shadow ray to light")).collect();
    assert!(shadows.len() >= 2, "{out}");
    assert!(shadows.iter().all(|l| l.contains(", from (") && l.contains(") along (")), "{out}");
    let explained = "the glass it leaves blocks it: shadows are opaque; with shadow_mode = \"tinted\" in [render], light passes through glass, tinted by its transmit";
    let blocked = out.lines().position(|l| l.contains(explained)).unwrap_or_else(|| panic!("no explanation in:\n{out}"));
    assert!(out.lines().nth(blocked - 2).unwrap().contains("blocked by object 0 (sphere, material \"glass\")"), "{out}");
    assert_eq!(out.matches(explained).count(), out.matches("blocked by object 0").count(), "{out}");

    std::fs::write(&path, std::fs::read_to_string(&path).unwrap() + "\n[render]\nshadow_mode = \"tinted\"\n").unwrap();
    let o = glint(&["probe", path.to_str().unwrap(), "16", "12"]);
    assert!(o.status.success() && !stdout(&o).contains("the glass it leaves"), "{}", stdout(&o));
}

#[test]
fn the_tutorials_probe_printout_is_what_probe_prints() {
    let tutorial = std::fs::read_to_string(Path::new(env!("CARGO_MANIFEST_DIR")).join("../../docs/tutorial.md")).unwrap();
    let start = tutorial.find("```\npixel (178, 96)").expect("the printout's block") + 4;
    // The closing fence is on a line of its own.
    let end = start + tutorial[start..].find("\n```\n").expect("a closing fence on its own line") + 1;
    let scene = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../scenes/tutorial.toml");
    let o = glint(&["probe", scene.to_str().unwrap(), "178", "96"]);
    assert!(o.status.success(), "{}", stderr(&o));
    assert_eq!(&tutorial[start..end], stdout(&o));
}

/// glint with its stdout a pipe whose reading end is already closed, as
/// `glint … | head -1` leaves it once head has its line.
#[cfg(unix)]
fn glint_into_a_closed_pipe(args: &[&str]) -> Output {
    let (reader, writer) = std::io::pipe().unwrap();
    drop(reader);
    Command::new(env!("CARGO_BIN_EXE_glint")).args(args).stdout(writer).output().expect("glint runs")
}

#[cfg(unix)]
#[test]
fn a_closed_stdout_ends_every_command_quietly() {
    use std::os::unix::process::ExitStatusExt;
    let dir = tempfile::tempdir().unwrap();
    let image = dir.path().join("a.png");
    image::RgbImage::from_pixel(8, 6, image::Rgb([90, 120, 150])).save(&image).unwrap();
    let image = image.display().to_string();
    std::fs::create_dir(dir.path().join("ann")).unwrap();
    std::fs::copy(&image, dir.path().join("ann/a.png")).unwrap();
    let manifest = dir.path().join("course.toml");
    std::fs::write(&manifest, "[[case]]\nimage = \"a.png\"\ngolden = \"a.png\"\n").unwrap();
    let (manifest, class) = (manifest.display().to_string(), dir.path().display().to_string());
    let showcase = showcase();
    let commands: [&[&str]; 6] = [
        &["compare", &image, &image],
        &["check", &showcase],
        &["spd", "balls"],
        &["test", &manifest, "--submissions", &class],
        &["info"],
        &["--help"],
    ];
    for args in commands {
        let o = glint_into_a_closed_pipe(args);
        // Ended by SIGPIPE at its first line, as `cat` would be: no panic, no
        // message (a driver may still say its piece on stderr).
        assert_eq!(o.status.signal(), Some(libc::SIGPIPE), "glint {args:?}: {:?}: {}", o.status, stderr(&o));
        assert!(!stderr(&o).contains("panicked") && !stderr(&o).contains("glint:"), "glint {args:?}: {}", stderr(&o));
    }
}
