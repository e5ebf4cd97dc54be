//! The `glint` binary end to end: renders, exit codes and one-line errors.

use std::path::{Path, PathBuf};
use std::process::{Command, Output};

fn glint(args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_glint")).args(args).output().expect("glint runs")
}

fn scenes() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../../scenes")
}

fn stderr(o: &Output) -> String {
    String::from_utf8_lossy(&o.stderr).into_owned()
}

#[test]
fn renders_the_default_scene_at_the_requested_size() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("showcase.png");
    let scene = scenes().join("showcase.toml");
    let o = glint(&["render", scene.to_str().unwrap(), "-o", out.to_str().unwrap(), "--width", "160", "--height", "100"]);
    assert!(o.status.success(), "{}", stderr(&o));
    assert!(stderr(&o).contains("Mrays/s"), "{}", stderr(&o));
    let img = image::open(&out).unwrap().to_rgb8();
    assert_eq!(img.dimensions(), (160, 100));
    let distinct: std::collections::HashSet<_> = img.pixels().collect();
    assert!(distinct.len() > 100, "the image is nearly uniform: {} colours", distinct.len());
    // Nothing but the image is left beside it.
    let names: Vec<_> = std::fs::read_dir(dir.path()).unwrap().map(|e| e.unwrap().file_name()).collect();
    assert_eq!(names, vec![std::ffi::OsString::from("showcase.png")]);
}

#[test]
fn stats_json_is_one_object_with_the_ray_counts() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("s.png");
    let scene = scenes().join("showcase.toml");
    let o = glint(&[
        "render", scene.to_str().unwrap(), "-o", out.to_str().unwrap(), "--width", "40", "--height", "25", "--stats", "--json", "--quiet",
    ]);
    assert!(o.status.success(), "{}", stderr(&o));
    let stdout = String::from_utf8(o.stdout).unwrap();
    assert_eq!(stdout.lines().count(), 1, "{stdout}");
    let v: serde_json::Value = serde_json::from_str(&stdout).unwrap();
    for key in ["eye_hit", "eye_miss", "shadow", "reflect", "refract"] {
        assert!(v[key].is_u64(), "{key} missing in {stdout}");
    }
    assert_eq!(v["eye_hit"].as_u64().unwrap() + v["eye_miss"].as_u64().unwrap(), 40 * 25);
}

#[test]
fn info_names_the_adapter_and_limits() {
    let o = glint(&["info"]);
    assert!(o.status.success(), "{}", stderr(&o));
    let stdout = String::from_utf8(o.stdout).unwrap();
    for needle in ["adapter:", "backend:", "device type:", "driver:", "profile:", "max storage buffer binding size", "max buffer size", "max workgroup size"] {
        assert!(stdout.contains(needle), "{needle} missing in:\n{stdout}");
    }
}

/// `GLINT_PROFILE` forces a profile on the adapter, which `glint info` shows
/// and which renders the same bytes; a value that names none is a usage
/// error of one line, and no output is written.
#[test]
fn glint_profile_forces_a_profile_and_a_bad_one_is_a_usage_error() {
    let dir = tempfile::tempdir().unwrap();
    let with_profile = |profile: &str, args: &[&str]| {
        Command::new(env!("CARGO_BIN_EXE_glint")).args(args).env(glint_gpu::ADAPTER_ENV, "llvmpipe").env(glint_gpu::PROFILE_ENV, profile).output().expect("glint runs")
    };
    let scene = scenes().join("gallery/primitives.toml");
    let mut images = Vec::new();
    for profile in ["plain", "lavapipe"] {
        let o = with_profile(profile, &["info"]);
        assert!(o.status.success(), "{}", stderr(&o));
        let stdout = String::from_utf8(o.stdout).unwrap();
        let line = stdout.lines().find(|l| l.starts_with("profile:")).unwrap_or_else(|| panic!("no profile in:\n{stdout}"));
        assert!(line.contains(&format!("{profile} profile, forced by GLINT_PROFILE={profile}")), "{line}");
        let out = dir.path().join(format!("{profile}.exr"));
        let o = with_profile(profile, &["render", scene.to_str().unwrap(), "--width", "48", "--height", "32", "--spp", "2", "-o", out.to_str().unwrap()]);
        assert!(o.status.success(), "{}", stderr(&o));
        images.push(std::fs::read(out).unwrap());
    }
    assert!(images[0] == images[1], "the plain profile's image is not the lavapipe profile's");
    let out = dir.path().join("bad.png");
    for args in [&["info"][..], &["render", scene.to_str().unwrap(), "-o", out.to_str().unwrap()]] {
        let o = with_profile("fast", args);
        assert_eq!(o.status.code(), Some(2), "{args:?}: {}", stderr(&o));
        assert_eq!(stderr(&o), "glint: GLINT_PROFILE=fast names no device profile: use plain or lavapipe\n", "{args:?}");
    }
    assert!(!out.exists(), "a render refused wrote its output");
}

/// The name of the shader cache glint gives the software adapter's kernels of `width` bits.
fn cache_of(width: impl std::fmt::Display) -> String {
    let dir = glint_gpu::lavapipe::shader_cache_dir(&width.to_string().into(), Some("/".into()), None).unwrap();
    dir.file_name().unwrap().to_string_lossy().into_owned()
}

/// `glint` with the software adapter's vector width `width` (`None`: the environment chooses
/// none) and Mesa's shader cache on, under the cache home `cache_home`.
fn glint_at_width(width: Option<&str>, cache_home: &Path, args: &[&str]) -> Output {
    let mut command = Command::new(env!("CARGO_BIN_EXE_glint"));
    command
        .args(args)
        .env(glint_gpu::ADAPTER_ENV, "llvmpipe")
        .env("XDG_CACHE_HOME", cache_home)
        .env_remove(glint_gpu::lavapipe::SHADER_CACHE_ENV)
        .env_remove("MESA_SHADER_CACHE_DISABLE");
    match width {
        Some(w) => command.env(glint_gpu::lavapipe::LAVAPIPE_WIDTH_ENV, w),
        None => command.env_remove(glint_gpu::lavapipe::LAVAPIPE_WIDTH_ENV),
    };
    command.output().expect("glint runs")
}

/// On the software adapter `glint` asks for the SIMD width its kernels compile fastest
/// at, unless the environment chooses one; the width changes no pixel, and
/// kernels one width compiled are never loaded at another (Mesa's cache does
/// not tell them apart, and such a kernel crashes the process).
#[test]
fn the_software_adapter_gets_the_width_glint_asks_for_and_it_changes_no_pixel() {
    let dir = tempfile::tempdir().unwrap();
    let cache = dir.path().join("cache");
    let adapter = |width| {
        let o = glint_at_width(width, &cache, &["info"]);
        assert!(o.status.success(), "{}", stderr(&o));
        String::from_utf8(o.stdout).unwrap().lines().next().unwrap_or_default().to_string()
    };
    let asked = format!("{} bits", glint_gpu::lavapipe::LAVAPIPE_WIDTH);
    assert!(adapter(None).contains(&asked), "{}", adapter(None));
    assert!(adapter(Some("256")).contains("256 bits"), "{}", adapter(Some("256")));

    let scene = scenes().join("showcase.toml");
    let render = |width, name: &str| {
        let out = dir.path().join(name);
        let o = glint_at_width(width, &cache, &["render", scene.to_str().unwrap(), "--width", "96", "--height", "64", "-o", out.to_str().unwrap()]);
        assert!(o.status.success(), "{}", stderr(&o));
        std::fs::read(out).unwrap()
    };
    let wide = render(Some("256"), "wide.exr");
    assert!(render(None, "asked.exr") == wide, "the image depends on the vector width");
    let mut caches: Vec<_> = std::fs::read_dir(&cache).unwrap().map(|e| e.unwrap().file_name()).collect();
    caches.sort();
    assert_eq!(caches, ["glint"], "Mesa's shared cache was used");
    let mut widths: Vec<_> = std::fs::read_dir(cache.join("glint")).unwrap().map(|e| e.unwrap().file_name()).collect();
    widths.sort();
    assert_eq!(widths, [cache_of(glint_gpu::lavapipe::LAVAPIPE_WIDTH), cache_of(256)].map(std::ffi::OsString::from));
}

#[test]
fn first_small_renders_compile_quick_kernels_to_the_same_pixels() {
    let dir = tempfile::tempdir().unwrap();
    let scene = scenes().join("showcase.toml");
    // The image's bytes and whether the kernels skipped LLVM's passes,
    // for a render of `size` pixels at `spp` with the shader cache under
    // `cache_home` (None: disabled) and `perf` as the driver's performance
    // flags (None: unset).
    let render = |cache_home: Option<&str>, perf: Option<&str>, size: &str, spp: &str| {
        let out = dir.path().join("out.exr");
        let mut command = Command::new(env!("CARGO_BIN_EXE_glint"));
        let args = ["render", scene.to_str().unwrap(), "--width", size, "--height", size, "--spp", spp, "--stats", "--json", "-o", out.to_str().unwrap()];
        command
            .args(args)
            .env(glint_gpu::ADAPTER_ENV, "llvmpipe")
            .env_remove(glint_gpu::lavapipe::SHADER_CACHE_ENV)
            .env_remove(glint_gpu::lavapipe::LAVAPIPE_WIDTH_ENV);
        match cache_home {
            Some(home) => command.env("XDG_CACHE_HOME", dir.path().join(home)).env_remove("MESA_SHADER_CACHE_DISABLE"),
            None => command.env("MESA_SHADER_CACHE_DISABLE", "true"),
        };
        match perf {
            Some(flags) => command.env(glint_gpu::lavapipe::LAVAPIPE_PERF_ENV, flags),
            None => command.env_remove(glint_gpu::lavapipe::LAVAPIPE_PERF_ENV),
        };
        let o = command.output().expect("glint runs");
        assert!(o.status.success(), "{}", stderr(&o));
        let stats: serde_json::Value = serde_json::from_slice(&o.stdout).expect("--stats --json prints JSON");
        let bits = stats["vector_bits"].as_u64().expect("the software adapter reports its width");
        let quick = stats["quick_kernels"].as_bool().expect("the software adapter reports its kernels");
        let samples = size.parse::<u64>().unwrap().pow(2) * spp.parse::<u64>().unwrap();
        let width = glint_gpu::lavapipe::width_for(samples, quick);
        assert_eq!(bits.to_string(), width, "the width of {} kernels for {samples} samples", if quick { "quick" } else { "optimised" });
        (std::fs::read(out).unwrap(), quick, bits)
    };
    let (quick, was_quick, quick_bits) = render(Some("a"), None, "96", "1");
    assert!(was_quick, "a first 96x96 render compiled optimised kernels");
    let (optimised, was_quick, _) = render(Some("a"), None, "96", "1");
    assert!(!was_quick, "a second render of the scene compiled quick kernels");
    assert!(quick == optimised, "quick kernels changed the image");
    // Each width's kernels in its own cache; the record of rendered scenes in
    // the cache of the width for optimised kernels.
    let widths = |home: &str| {
        let mut names: Vec<String> = std::fs::read_dir(dir.path().join(home).join("glint")).unwrap().map(|e| e.unwrap().file_name().to_string_lossy().into_owned()).collect();
        names.sort();
        names
    };
    let mut expected = vec![cache_of(glint_gpu::lavapipe::LAVAPIPE_WIDTH), cache_of(quick_bits)];
    expected.dedup();
    assert_eq!(widths("a"), expected);
    assert!(render(None, None, "96", "1").1, "without a shader cache a scene rendered before compiled optimised kernels");
    assert!(!render(Some("b"), Some(""), "96", "1").1, "empty performance flags did not keep the optimised kernels");
    // Just over the limit in samples, not in pixels.
    let side = (glint_gpu::lavapipe::QUICK_COMPILE_MAX_SAMPLES / 16).isqrt() + 1;
    assert!(!render(Some("c"), None, &side.to_string(), "16").1, "a render of {} samples compiled quick kernels", side * side * 16);
    // A long render: optimised kernels at the wide width (the render checks
    // the width), in that width's cache.
    let spp = glint_gpu::lavapipe::LONG_RENDER_MIN_SAMPLES.div_ceil(48 * 48);
    let (_, was_quick, long_bits) = render(Some("d"), None, "48", &spp.to_string());
    assert!(!was_quick, "a long render compiled quick kernels");
    assert!(widths("d").contains(&cache_of(long_bits)), "no cache of the long render's width: {:?}", widths("d"));
}

/// `glint bench` times its warm frames with the kernels a long render runs,
/// at the width Glint chooses for them, and says which.
#[test]
fn bench_times_the_kernels_of_a_long_render() {
    let dir = tempfile::tempdir().unwrap();
    let o = glint_at_width(None, dir.path(), &["bench", "spd:tetra:1", "--width", "16", "--height", "16", "--frames", "1", "--json"]);
    assert!(o.status.success(), "{}", stderr(&o));
    let report: serde_json::Value = serde_json::from_slice(&o.stdout).expect("--json prints JSON");
    let long_render = glint_gpu::lavapipe::width_for(glint_gpu::lavapipe::LONG_RENDER_MIN_SAMPLES, false);
    assert_eq!(report["vector_bits"].to_string(), long_render, "{report}");
    // The primary frame counts the view's host work, which is also reported apart.
    let (primary, view) = (report["primary_ms"].as_f64().unwrap(), report["view_work_ms"].as_f64().unwrap());
    assert!(view > 0.0 && primary >= view, "{report}");
}

/// Frames that start within `--warm-up` seconds of the first, which
/// compiles, are traced but not timed.
#[test]
fn bench_leaves_the_warm_up_untimed() {
    let dir = tempfile::tempdir().unwrap();
    let warm_up_frames = |seconds: &str| {
        let o = glint_at_width(None, dir.path(), &["bench", "spd:tetra:1", "--width", "16", "--height", "16", "--frames", "1", "--warm-up", seconds, "--json"]);
        assert!(o.status.success(), "{}", stderr(&o));
        let report: serde_json::Value = serde_json::from_slice(&o.stdout).expect("--json prints JSON");
        report["warm_up_frames"].as_u64().unwrap_or_else(|| panic!("no warm_up_frames: {report}"))
    };
    assert_eq!(warm_up_frames("0"), 0);
    // A 16×16 frame takes milliseconds.
    assert!(warm_up_frames("0.3") > 1);
    let o = glint(&["bench", "spd:tetra:1", "--warm-up", "61"]);
    assert_eq!(o.status.code(), Some(2), "{}", stderr(&o));
    assert!(stderr(&o).contains("`61` is not a number of seconds from 0 to 60"), "{}", stderr(&o));
}

#[test]
fn bad_inputs_fail_with_one_line_and_leave_no_file() {
    let dir = tempfile::tempdir().unwrap();
    let bad = dir.path().join("bad.toml");
    std::fs::write(&bad, "[image]\nwidth = 10\nheight = 10\n[camera]\neye = [0,0,1]\nlook_at = [0,0,0]\nfov = \"wide\"\n").unwrap();
    let out = dir.path().join("out.png");
    let cases: [(Vec<String>, i32, String); 4] = [
        (vec![bad.display().to_string()], 3, format!("{}:7:", bad.display())),
        (vec![dir.path().join("missing.toml").display().to_string()], 3, "missing.toml".into()),
        (vec![scenes().join("showcase.toml").display().to_string(), "--width".into(), "0".into()], 2, "width".into()),
        (vec![scenes().join("showcase.toml").display().to_string(), "--max-depth".into(), "1000".into()], 2, "max-depth".into()),
    ];
    for (extra, code, needle) in cases {
        let mut args = vec!["render".to_string(), "-o".into(), out.display().to_string()];
        args.extend(extra);
        let args: Vec<&str> = args.iter().map(String::as_str).collect();
        let o = glint(&args);
        assert_eq!(o.status.code(), Some(code), "{args:?}: {}", stderr(&o));
        assert!(stderr(&o).contains(&needle), "{args:?}: {}", stderr(&o));
        assert!(!stderr(&o).contains("panicked"), "{}", stderr(&o));
        assert!(!out.exists(), "{args:?} left an output file");
    }
    // A scene error is exactly one line.
    let o = glint(&["render", bad.to_str().unwrap(), "-o", out.to_str().unwrap()]);
    assert_eq!(stderr(&o).trim_end().lines().count(), 1, "{}", stderr(&o));
}

#[test]
fn unsupported_output_format_is_refused_before_rendering() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("out.bmpx");
    let o = glint(&["render", scenes().join("showcase.toml").to_str().unwrap(), "-o", out.to_str().unwrap()]);
    assert_eq!(o.status.code(), Some(2), "{}", stderr(&o));
    assert!(!out.exists());
}

#[test]
fn failed_write_keeps_an_existing_file_untouched() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("keep.png");
    std::fs::write(&out, b"precious").unwrap();
    // A scene error after the output path was named must not touch the file.
    let bad = dir.path().join("bad.toml");
    std::fs::write(&bad, "not toml at all [").unwrap();
    let o = glint(&["render", bad.to_str().unwrap(), "-o", out.to_str().unwrap()]);
    assert_eq!(o.status.code(), Some(3));
    assert_eq!(std::fs::read(&out).unwrap(), b"precious");
}

#[test]
fn unwritable_output_fails_with_code_5_and_leaves_nothing() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("no/such/dir/out.png");
    let o = glint(&["render", scenes().join("showcase.toml").to_str().unwrap(), "-o", out.to_str().unwrap(), "--width", "16", "--height", "16"]);
    assert_eq!(o.status.code(), Some(5), "{}", stderr(&o));
    assert!(stderr(&o).contains("out.png"), "{}", stderr(&o));
    assert_eq!(std::fs::read_dir(dir.path()).unwrap().count(), 0);
}

/// `glint kernels --dump` writes one WGSL file per kernel and tuning, each
/// listed in kernels.json with its entry point, and prints their paths; a
/// directory it cannot make fails with one line and exit code 5.
#[test]
fn kernels_are_dumped_one_file_each_with_a_manifest() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("kernels");
    let o = glint(&["kernels", "--dump", out.to_str().unwrap()]);
    assert!(o.status.success(), "{}", stderr(&o));
    let manifest: serde_json::Value = serde_json::from_str(&std::fs::read_to_string(out.join("kernels.json")).unwrap()).unwrap();
    let entries = manifest.as_array().unwrap();
    let printed = String::from_utf8(o.stdout).unwrap();
    assert_eq!(printed.lines().count(), entries.len() + 1, "{printed}");
    for entry in entries {
        let file = entry["file"].as_str().unwrap();
        let wgsl = std::fs::read_to_string(out.join(file)).unwrap();
        let entry_point = entry["entry_point"].as_str().unwrap();
        assert!(wgsl.contains(&format!("fn {entry_point}(")), "{file} lacks {entry_point}");
        assert_eq!(wgsl.starts_with("enable subgroups;"), entry["subgroups"].as_bool().unwrap(), "{file}");
    }
    for kernel in ["trace", "primary", "diffuse", "resolve", "present", "probe"] {
        assert!(out.join(format!("{kernel}.buffers.wgsl")).exists(), "no plain {kernel} kernel");
    }
    let blocked = dir.path().join("file");
    std::fs::write(&blocked, "").unwrap();
    let o = glint(&["kernels", "--dump", blocked.join("kernels").to_str().unwrap()]);
    assert_eq!(o.status.code(), Some(5), "{}", stderr(&o));
    assert_eq!(stderr(&o).lines().count(), 1, "{}", stderr(&o));
}

#[test]
fn aovs_and_float_outputs_are_written_beside_the_image() {
    let dir = tempfile::tempdir().unwrap();
    let p = |name: &str| dir.path().join(name).display().to_string();
    let o = glint(&[
        "render",
        scenes().join("showcase.toml").to_str().unwrap(),
        "-o",
        &p("beauty.exr"),
        "--width",
        "32",
        "--height",
        "20",
        "--spp",
        "2",
        "--aov",
        &format!("depth={}", p("depth.pfm")),
        "--aov",
        &format!("normal={}", p("normal.exr")),
        "--aov",
        &format!("albedo={}", p("albedo.pfm")),
        "--aov",
        &format!("id={}", p("id.pfm")),
        "-q",
    ]);
    assert!(o.status.success(), "{}", stderr(&o));
    let (w, h, depth) = glint_gpu::read_pfm(&std::fs::read(p("depth.pfm")).unwrap()).unwrap();
    assert_eq!((w, h), (32, 20));
    assert_eq!(depth[0][0], f32::INFINITY, "the top-left pixel sees the sky");
    assert!(depth[(19 * 32 + 16) as usize][0].is_finite(), "the bottom centre sees the floor");
    let (_, _, ids) = glint_gpu::read_pfm(&std::fs::read(p("id.pfm")).unwrap()).unwrap();
    assert_eq!(ids[0][0], -1.0);
    assert!(image::open(p("normal.exr")).is_ok() && image::open(p("beauty.exr")).is_ok());
    // A bad AOV name is a usage error, before any work.
    let o = glint(&["render", scenes().join("showcase.toml").to_str().unwrap(), "-o", &p("x.png"), "--aov", "shadow=x.pfm"]);
    assert_eq!(o.status.code(), Some(2));
}

#[test]
fn nff_scenes_render_with_either_angle_reading() {
    let dir = tempfile::tempdir().unwrap();
    let nff = dir.path().join("tiny.nff");
    std::fs::write(&nff, "v\nfrom 0 0 5\nat 0 0 0\nup 0 1 0\nangle 40\nhither 1\nresolution 24 24\nb 0 0 0\nl 2 2 5\nf 1 0 0 1 0 0 0 1\ns 0 0 0 1\n").unwrap();
    let mut centre_pixels = Vec::new();
    for angle in ["centers", "edges"] {
        let out = dir.path().join(format!("{angle}.png"));
        let o = glint(&["render", nff.to_str().unwrap(), "-o", out.to_str().unwrap(), "--nff-angle", angle, "-q"]);
        assert!(o.status.success(), "{}", stderr(&o));
        let img = image::open(&out).unwrap().to_rgb8();
        assert_eq!(img.dimensions(), (24, 24));
        assert!(img.get_pixel(12, 12)[0] > 100, "the red sphere is in the middle");
        centre_pixels.push(img.pixels().filter(|p| p[0] > 0).count());
    }
    // Read edge to edge, the same angle is a narrower view: the sphere looks bigger.
    assert!(centre_pixels[1] > centre_pixels[0], "{centre_pixels:?}");
}

#[test]
fn an_image_beyond_what_the_device_holds_at_once_renders_in_tiles() {
    // 4100 × 2100 is 8.6 Mpixels, more than WebGPU's default 128 MiB storage
    // buffers hold at 16 bytes a pixel; the cheap depth view keeps it quick.
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("huge.png");
    let scene = scenes().join("showcase.toml");
    let o = glint(&["render", scene.to_str().unwrap(), "-o", out.to_str().unwrap(), "--width", "4100", "--height", "2100", "--view", "depth", "-q"]);
    assert!(o.status.success(), "{}", stderr(&o));
    assert_eq!(image::image_dimensions(&out).unwrap(), (4100, 2100));
}

/// A PPM holds the samples of the PNG of the same render, raw or plain, at 8
/// or 16 bits, and `glint compare` finds no difference between the two.
#[test]
fn ppm_output_holds_the_samples_of_the_png_of_the_same_render() {
    let dir = tempfile::tempdir().unwrap();
    let p = |name: &str| dir.path().join(name).display().to_string();
    let scene = scenes().join("showcase.toml");
    let render = |out: &str, extra: &[&str]| {
        let path = p(out);
        let args = [&["render", scene.to_str().unwrap(), "-o", &path, "--width", "40", "--height", "30", "-q"][..], extra].concat();
        let o = glint(&args);
        assert!(o.status.success(), "{args:?}: {}", stderr(&o));
        std::fs::read(p(out)).unwrap()
    };
    let samples_of = |png: &str| -> Vec<u16> {
        match image::open(p(png)).unwrap() {
            image::DynamicImage::ImageRgb8(rgb) => rgb.into_raw().into_iter().map(u16::from).collect(),
            image::DynamicImage::ImageRgb16(rgb) => rgb.into_raw(),
            other => panic!("{png}: {:?}", other.color()),
        }
    };
    render("t.png", &[]);
    render("t16.png", &["--bits", "16"]);
    let cases: [(&str, &[&str], &str, &str); 4] = [
        ("t.ppm", &[], "P6\n40 30\n255\n", "t.png"),
        ("t16.ppm", &["--bits", "16"], "P6\n40 30\n65535\n", "t16.png"),
        ("plain.ppm", &["--plain"], "P3\n40 30\n255\n", "t.png"),
        ("plain16.ppm", &["--plain", "--bits", "16"], "P3\n40 30\n65535\n", "t16.png"),
    ];
    for (out, extra, header, png) in cases {
        let bytes = render(out, extra);
        assert!(bytes.starts_with(header.as_bytes()), "{out}: {:?}", String::from_utf8_lossy(&bytes[..20]));
        let ppm = glint_gpu::read_ppm(&bytes).unwrap();
        assert_eq!(ppm.samples, samples_of(png), "{out}");
        if out == "t.ppm" {
            assert!(bytes[header.len()..] == image::open(p(png)).unwrap().to_rgb8().into_raw()[..], "P6 holds the PNG's bytes");
        }
        let o = glint(&["compare", &p(png), &p(out), "--metric", "max", "--threshold", "0", "--json"]);
        assert_eq!(o.status.code(), Some(0), "{out}: {}", stderr(&o));
        let v: serde_json::Value = serde_json::from_slice(&o.stdout).unwrap();
        assert_eq!(v["max"], 0.0, "{out}: {v}");
    }
    // --plain is for PPM alone, and refused before any work.
    let o = glint(&["render", scene.to_str().unwrap(), "-o", &p("x.png"), "--plain"]);
    assert_eq!(o.status.code(), Some(2), "{}", stderr(&o));
    assert_eq!(stderr(&o), format!("glint: --plain: it writes a plain PPM (P3), but {} is not a .ppm\n", p("x.png")));
    assert!(!dir.path().join("x.png").exists());
}
