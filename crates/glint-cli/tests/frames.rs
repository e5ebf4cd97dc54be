//! `glint render --frames A..B` of an animated scene (scenes/turntable.toml):
//! frame ranges split across concurrent processes give the files of one run,
//! byte for byte, a frame's bytes do not depend on the range it is rendered
//! in, frames compose with shards and AOVs, `--video` hands the frames to
//! ffmpeg, and every bad request is refused before anything is rendered.

use std::path::{Path, PathBuf};
use std::process::{Command, Output};

fn glint(args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_glint")).args(args).output().expect("glint runs")
}

fn turntable() -> String {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../../scenes/turntable.toml").to_str().unwrap().to_string()
}

/// Small frames, so that the test is quick on a software rasteriser.
const SIZE: [&str; 5] = ["--width", "64", "--height", "48", "-q"];

fn path(p: &Path) -> &str {
    p.to_str().unwrap()
}

fn stderr(o: &Output) -> String {
    String::from_utf8_lossy(&o.stderr).into_owned()
}

/// `glint render` of the turntable with `extra` options, which must succeed.
fn render(extra: &[&str]) {
    let scene = turntable();
    let args = [&["render", scene.as_str()][..], &SIZE, extra].concat();
    let o = glint(&args);
    assert!(o.status.success(), "{args:?}: {}", stderr(&o));
}

fn frame(dir: &Path, name: &str, n: u32) -> PathBuf {
    dir.join(format!("{name}_{n:04}.png"))
}

#[track_caller]
fn assert_same_file(a: &Path, b: &Path) {
    assert!(std::fs::read(a).unwrap() == std::fs::read(b).unwrap(), "{} and {} differ", a.display(), b.display());
}

fn files(dir: &Path) -> Vec<String> {
    let mut names: Vec<String> = std::fs::read_dir(dir).unwrap().map(|e| e.unwrap().file_name().to_string_lossy().into_owned()).collect();
    names.sort();
    names
}

/// docs/scale-out.md's frame split on one machine: two processes rendering
/// 0..2 and 2..4 at the same time write the files one process writes for 0..4.
#[test]
fn frame_ranges_split_across_concurrent_processes_equal_one_run() {
    let dir = tempfile::tempdir().unwrap();
    let one = dir.path().join("one_%04d.png");
    render(&["--frames", "0..4", "-o", path(&one), "--spp", "2"]);
    let split = dir.path().join("split_%04d.png");
    let scene = turntable();
    let running: Vec<_> = ["0..2", "2..4"]
        .iter()
        .map(|range| {
            Command::new(env!("CARGO_BIN_EXE_glint"))
                .args([&["render", scene.as_str(), "--frames", range, "-o", path(&split), "--spp", "2"][..], &SIZE].concat())
                .spawn()
                .expect("glint starts")
        })
        .collect();
    for mut process in running {
        assert!(process.wait().unwrap().success());
    }
    for n in 0..4 {
        assert_same_file(&frame(dir.path(), "one", n), &frame(dir.path(), "split", n));
    }
    // The frames differ: the animation moves.
    assert!(std::fs::read(frame(dir.path(), "one", 0)).unwrap() != std::fs::read(frame(dir.path(), "one", 1)).unwrap());
    // One frame alone, into a plain name, is that frame's file too.
    let alone = dir.path().join("alone.png");
    render(&["--frames", "3", "-o", path(&alone), "--spp", "2"]);
    assert_same_file(&frame(dir.path(), "one", 3), &alone);
    // Without --frames, an animated scene renders frame 0.
    let still = dir.path().join("still.png");
    render(&["-o", path(&still), "--spp", "2"]);
    assert_same_file(&frame(dir.path(), "one", 0), &still);
}

/// The depth view maps depth by the farthest point of the scene seen from
/// each frame's own eye, whatever frame a process starts with.
#[test]
fn a_frame_s_depth_view_does_not_depend_on_the_range() {
    let dir = tempfile::tempdir().unwrap();
    let range = dir.path().join("range_%04d.png");
    render(&["--frames", "0..3", "-o", path(&range), "--view", "depth"]);
    let alone = dir.path().join("alone.png");
    render(&["--frames", "2", "-o", path(&alone), "--view", "depth"]);
    assert_same_file(&frame(dir.path(), "range", 2), &alone);
}

/// A frame rendered in shards and stitched, with an AOV, is the frame of a
/// whole render.
#[test]
fn frames_compose_with_shards_and_aovs() {
    let dir = tempfile::tempdir().unwrap();
    let whole = dir.path().join("whole_%04d.png");
    let whole_depth = dir.path().join("whole_depth_%04d.pfm");
    render(&["--frames", "5..7", "-o", path(&whole), "--aov", &format!("depth={}", path(&whole_depth))]);
    for shard in 0..2 {
        let part = dir.path().join(format!("part{shard}_%04d.png"));
        let depth = dir.path().join(format!("part{shard}_depth_%04d.pfm"));
        let aov = format!("depth={}", path(&depth));
        render(&["--frames", "5..7", "-o", path(&part), "--aov", &aov, "--shard", &format!("{shard}/2")]);
    }
    for (name, ext) in [("", "png"), ("_depth", "pfm")] {
        let parts: Vec<String> = (0..2).map(|s| path(&dir.path().join(format!("part{s}{name}_0006.{ext}"))).to_string()).collect();
        let stitched = dir.path().join(format!("stitched{name}.{ext}"));
        let o = glint(&["stitch", &parts[0], &parts[1], "-o", path(&stitched)]);
        assert!(o.status.success(), "{}", stderr(&o));
        assert_same_file(&dir.path().join(format!("whole{name}_0006.{ext}")), &stitched);
    }
}

/// Frames written as PPM hold the samples of the same frames written as PNG.
#[test]
fn frames_are_written_as_ppm_too() {
    let dir = tempfile::tempdir().unwrap();
    render(&["--frames", "1..3", "-o", path(&dir.path().join("png_%04d.png"))]);
    render(&["--frames", "1..3", "-o", path(&dir.path().join("ppm_%04d.ppm"))]);
    assert_eq!(files(dir.path()), ["png_0001.png", "png_0002.png", "ppm_0001.ppm", "ppm_0002.ppm"]);
    for n in 1..3 {
        let ppm = std::fs::read(dir.path().join(format!("ppm_{n:04}.ppm"))).unwrap();
        let header = b"P6\n64 48\n255\n";
        assert!(ppm.starts_with(header));
        let png = image::open(frame(dir.path(), "png", n)).unwrap().to_rgb8().into_raw();
        assert!(ppm[header.len()..] == png[..], "frame {n}");
    }
}

/// Every mistake is one line and a usage error before any rendering: no
/// file is written.
#[test]
fn bad_frame_requests_are_refused_before_rendering() {
    let dir = tempfile::tempdir().unwrap();
    let out = |name: &str| path(&dir.path().join(name)).to_string();
    let first = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../scenes/first.toml").to_str().unwrap().to_string();
    let turntable = turntable();
    let cases: Vec<(Vec<String>, &str)> = vec![
        (
            vec!["--frames".into(), "0..4".into(), "-o".into(), out("f.png")],
            "4 frames need one file each: put the frame number in the name, as in f_%04d.png",
        ),
        (
            vec!["--frames".into(), "0..2".into(), "-o".into(), out("f_%04d.png"), "--aov".into(), format!("depth={}", out("d.pfm"))],
            "d.pfm: 2 frames need one file each",
        ),
        (
            vec!["--frames".into(), "40..49".into(), "-o".into(), out("f_%04d.png")],
            "--frames 40..49: the animation has 48 frames, 0..48 (frames 0 to 47)",
        ),
        (vec!["--frames".into(), "48..".into(), "-o".into(), out("f_%04d.png")], "--frames 48..: the animation has 48 frames"),
        (
            vec!["--frames".into(), "0..=3".into(), "-o".into(), out("f_%04d.png")],
            "the end of A..B is excluded, as in Rust, and ..= is not accepted: write 0..4 for frames 0 to 3",
        ),
        (vec!["--frames".into(), "3..1".into(), "-o".into(), out("f_%04d.png")], "`3..1` holds no frame"),
        (vec!["-o".into(), out("f_%04d.png")], "the name has a frame number, but no --frames says which frames to render"),
        (vec!["--frames".into(), "0..2".into(), "-o".into(), out("f_%s.png")], "a `%` in an output name starts its frame number"),
        (vec!["--frames".into(), "0..2".into(), "-o".into(), out("f_%04d.png"), "--fps".into(), "30".into()], "--video"),
    ];
    for (args, want) in cases {
        let full = [&["render".to_string(), turntable.clone()][..], &args].concat();
        let o = glint(&full.iter().map(String::as_str).collect::<Vec<_>>());
        let text = stderr(&o);
        assert_eq!(o.status.code(), Some(2), "{full:?}: {text}");
        assert!(text.contains(want), "{full:?}\n{text}");
        assert!(text.starts_with("glint: ") && !text.contains("panicked"), "{text}");
    }
    let o = glint(&["render", &first, "--frames", "0..2", "-o", &out("g_%d.png")]);
    assert_eq!(o.status.code(), Some(2));
    assert_eq!(stderr(&o), "glint: --frames: the scene has no [animation] to take frames from (see docs/scene-format.md)\n");
    assert!(files(dir.path()).is_empty(), "{:?}", files(dir.path()));
}

/// A PATH holding only `ffmpeg` (or nothing).
#[cfg(unix)]
fn path_with(dir: &Path, ffmpeg: Option<&str>) -> String {
    if let Some(script) = ffmpeg {
        use std::os::unix::fs::PermissionsExt;
        let exe = dir.join("ffmpeg");
        std::fs::write(&exe, script).unwrap();
        std::fs::set_permissions(&exe, std::fs::Permissions::from_mode(0o755)).unwrap();
    }
    path(dir).to_string()
}

#[cfg(unix)]
#[test]
fn a_video_needs_ffmpeg_and_gets_the_frames_in_order() {
    let dir = tempfile::tempdir().unwrap();
    let (bin, frames) = (dir.path().join("bin"), dir.path().join("frames"));
    std::fs::create_dir_all(&bin).unwrap();
    std::fs::create_dir_all(&frames).unwrap();
    let pattern = frames.join("t_%04d.png");
    let video = frames.join("t.mp4");
    let scene = turntable();
    let run = |path_var: &str, extra: &[&str]| {
        let args =
            [&["render", scene.as_str(), "--frames", "1..3", "-o", path(&pattern), "--video", path(&video)][..], &SIZE, extra].concat();
        Command::new(env!("CARGO_BIN_EXE_glint")).args(&args).env("PATH", path_var).output().unwrap()
    };
    // No ffmpeg: refused before rendering.
    let o = run(&path_with(&bin, None), &[]);
    assert_eq!(o.status.code(), Some(2), "{}", stderr(&o));
    assert!(stderr(&o).contains("making a video needs ffmpeg, which is not on PATH"), "{}", stderr(&o));
    assert!(files(&frames).is_empty());
    // A video needs whole PNG frames.
    let exr = frames.join("t_%04d.exr");
    let fake = path_with(&bin, Some("#!/bin/sh\nexit 1\n"));
    let o = Command::new(env!("CARGO_BIN_EXE_glint"))
        .args([&["render", scene.as_str(), "--frames", "1..3", "-o", path(&exr), "--video", path(&video)][..], &SIZE].concat())
        .env("PATH", &fake)
        .output()
        .unwrap();
    assert!(stderr(&o).contains("from PNG files"), "{}", stderr(&o));
    let o = run(&fake, &["--shard", "0/2"]);
    assert!(stderr(&o).contains("a video needs whole frames"), "{}", stderr(&o));
    assert!(files(&frames).is_empty());

    // A stand-in ffmpeg that records its arguments and writes the file it is given last.
    let args_file = dir.path().join("args.txt");
    let recorder = format!("#!/bin/sh\nprintf '%s\\n' \"$@\" > '{}'\nfor last; do :; done\necho video > \"$last\"\n", path(&args_file));
    let o = run(&path_with(&bin, Some(&recorder)), &["--fps", "12.5"]);
    assert!(o.status.success(), "{}", stderr(&o));
    assert_eq!(std::fs::read_to_string(&video).unwrap(), "video\n");
    let args = std::fs::read_to_string(&args_file).unwrap();
    let args: Vec<&str> = args.lines().collect();
    let after = |flag: &str| args[args.iter().position(|a| *a == flag).unwrap() + 1];
    assert_eq!((after("-framerate"), after("-start_number"), after("-i"), after("-frames:v")), ("12.5", "1", path(&pattern), "2"));
    assert_eq!(files(&frames), ["t.mp4", "t_0001.png", "t_0002.png"]);

    // ffmpeg failing: its message, and no video, not even a partial one.
    std::fs::remove_file(&video).unwrap();
    let failing = "#!/bin/sh\nfor last; do :; done\necho half > \"$last\"\necho 'Unknown encoder' >&2\nexit 1\n";
    let o = run(&path_with(&bin, Some(failing)), &[]);
    assert_eq!(o.status.code(), Some(5), "{}", stderr(&o));
    assert!(stderr(&o).contains("ffmpeg failed (exit status: 1): Unknown encoder"), "{}", stderr(&o));
    assert_eq!(files(&frames), ["t_0001.png", "t_0002.png"]);
}
