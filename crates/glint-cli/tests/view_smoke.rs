//! `glint view` for real: under Xvfb (`xvfb-run`, which `bash .ci/setup --tests`
//! installs) the binary opens its window, renders the showcase for a few
//! seconds and exits cleanly when the window is asked to close, as a window
//! manager's close button asks (WM_DELETE_WINDOW). It is started with no scene
//! from a directory without `scenes/`: the showcase is built into the binary.

use std::ffi::OsStr;
use std::io::{BufRead, BufReader, Read};
use std::os::unix::process::CommandExt;
use std::path::Path;
use std::process::{Child, Command, Stdio};
use std::time::{Duration, Instant};

use x11rb::connection::Connection;
use x11rb::protocol::xproto::{
    AtomEnum, ClientMessageEvent, ConnectionExt, EventMask, ImageFormat, MapState, Window,
};
use x11rb::rust_connection::RustConnection;

const SCREEN: (u16, u16) = (1280, 800);

/// Ends the whole process group (xvfb-run, Xvfb, glint) if the test fails early.
/// The directory holds the server's auth file: given one, xvfb-run makes no
/// temporary directory of its own, whose removal once failed a CI run
/// ("problem while cleaning up temporary directory", exit 5 for glint's 3).
struct Group(Child, tempfile::TempDir);

impl Drop for Group {
    fn drop(&mut self) {
        if let Ok(None) = self.0.try_wait() {
            let _ = Command::new("kill").args(["-KILL", &format!("-{}", self.0.id())]).status();
            let _ = self.0.wait();
        }
    }
}

/// Runs `command` under a virtual X server in `dir`, in a process group of its
/// own, its output piped, with the environment changed by `env` (a `None`
/// value removes the variable).
fn under_xvfb(command: &[&OsStr], dir: &Path, env: &[(&str, Option<&OsStr>)]) -> Group {
    let screen = format!("-screen 0 {}x{}x24 -ac", SCREEN.0, SCREEN.1);
    let auth = tempfile::tempdir().unwrap();
    let mut xvfb = Command::new("xvfb-run");
    for (name, value) in env {
        match value {
            Some(value) => xvfb.env(name, value),
            None => xvfb.env_remove(name),
        };
    }
    let child = xvfb
        .args(["-a", "-s", &screen, "-f"])
        .arg(auth.path().join("Xauthority"))
        .args(command)
        .current_dir(dir)
        .stdin(Stdio::null())
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .process_group(0)
        .spawn()
        .expect("xvfb-run must be installed (bash .ci/setup --tests installs it)");
    Group(child, auth)
}

/// The top-level window whose title starts with "Glint", once it is shown.
fn find_window(conn: &RustConnection, root: Window) -> Option<Window> {
    let children = conn.query_tree(root).ok()?.reply().ok()?.children;
    children.into_iter().find(|&w| {
        let title = conn
            .get_property(false, w, AtomEnum::WM_NAME, AtomEnum::ANY, 0, 256)
            .ok()
            .and_then(|c| c.reply().ok())
            .map(|p| p.value)
            .unwrap_or_default();
        let shown = conn
            .get_window_attributes(w)
            .ok()
            .and_then(|c| c.reply().ok())
            .is_some_and(|a| a.map_state == MapState::VIEWABLE);
        title.starts_with(b"Glint") && shown
    })
}

/// The screen's pixels and how many of them show the showcase's sky.
fn screenshot(conn: &RustConnection, root: Window) -> (Vec<[u8; 3]>, usize) {
    let shot = conn.get_image(ImageFormat::Z_PIXMAP, root, 0, 0, SCREEN.0, SCREEN.1, !0).unwrap().reply().unwrap();
    // 24-bit depth comes as 32-bit BGRX pixels.
    let pixels: Vec<[u8; 3]> = shot.data.chunks_exact(4).map(|p| [p[2], p[1], p[0]]).collect();
    let sky = pixels.iter().filter(|p| p.iter().zip([196u8, 215, 237]).all(|(a, b)| a.abs_diff(b) <= 4)).count();
    (pixels, sky)
}

fn save(pixels: &[[u8; 3]], path: &Path) {
    let (w, h) = (u32::from(SCREEN.0), u32::from(SCREEN.1));
    image::RgbImage::from_fn(w, h, |x, y| image::Rgb(pixels[(y * w + x) as usize])).save(path).unwrap();
}

#[test]
fn the_viewer_renders_under_xvfb_and_closes_cleanly() {
    let elsewhere = tempfile::tempdir().unwrap();
    let shell = r#"echo "$DISPLAY"; exec "$0" view"#;
    let mut group = under_xvfb(&["sh".as_ref(), "-c".as_ref(), shell.as_ref(), env!("CARGO_BIN_EXE_glint").as_ref()], elsewhere.path(), &[]);
    let mut stderr = group.0.stderr.take().unwrap();
    let stderr = std::thread::spawn(move || {
        let mut text = String::new();
        let _ = stderr.read_to_string(&mut text);
        text
    });
    let mut display = String::new();
    BufReader::new(group.0.stdout.take().unwrap()).read_line(&mut display).unwrap();
    let display = display.trim().to_string();
    assert!(display.starts_with(':'), "xvfb-run gave no display: {display:?}");

    let (conn, screen_num) = x11rb::connect(Some(&display)).expect("connect to Xvfb");
    let root = conn.setup().roots[screen_num].root;
    let start = Instant::now();
    let window = loop {
        if let Some(w) = find_window(&conn, root) {
            break w;
        }
        if let Ok(Some(status)) = group.0.try_wait() {
            panic!("glint view exited before showing a window ({status}): {}", stderr.join().unwrap());
        }
        assert!(start.elapsed() < Duration::from_secs(120), "no Glint window appeared");
        std::thread::sleep(Duration::from_millis(200));
    };

    // Wait for the rendered showcase: its sky, [0.55, 0.68, 0.85] in sRGB,
    // fills a good part of the image once the kernels are compiled.
    let out = Path::new(env!("CARGO_TARGET_TMPDIR")).join("view-smoke.png");
    let start = Instant::now();
    loop {
        let (pixels, sky) = screenshot(&conn, root);
        if sky > 20_000 {
            break;
        }
        if start.elapsed() > Duration::from_secs(120) {
            save(&pixels, &out);
            panic!("the rendered showcase is not on screen ({sky} sky pixels); see {}", out.display());
        }
        assert!(group.0.try_wait().unwrap().is_none(), "glint view died: {}", stderr.join().unwrap());
        std::thread::sleep(Duration::from_millis(500));
    }
    // Keep it rendering for a few seconds.
    std::thread::sleep(Duration::from_secs(3));
    assert!(group.0.try_wait().unwrap().is_none(), "glint view died while rendering: {}", stderr.join().unwrap());
    save(&screenshot(&conn, root).0, &out);

    let atom = |name: &[u8]| conn.intern_atom(false, name).unwrap().reply().unwrap().atom;
    let (protocols, delete) = (atom(b"WM_PROTOCOLS"), atom(b"WM_DELETE_WINDOW"));
    let close = ClientMessageEvent::new(32, window, protocols, [delete, x11rb::CURRENT_TIME, 0, 0, 0]);
    conn.send_event(false, window, EventMask::NO_EVENT, close).unwrap();
    conn.flush().unwrap();

    let start = Instant::now();
    let status = loop {
        if let Some(status) = group.0.try_wait().unwrap() {
            break status;
        }
        assert!(start.elapsed() < Duration::from_secs(30), "glint view did not exit after the close request");
        std::thread::sleep(Duration::from_millis(100));
    };
    let stderr = stderr.join().unwrap();
    assert!(status.success(), "glint view exited with {status}: {stderr}");
    assert!(!stderr.contains("panicked"), "{stderr}");
}

/// `glint view --first-image FILE` under Xvfb, in its own process group.
fn first_image(scene: &Path, env: &[(&str, Option<&OsStr>)]) -> std::process::Output {
    let glint = env!("CARGO_BIN_EXE_glint").as_ref();
    let mut group = under_xvfb(&[glint, "view".as_ref(), "--first-image".as_ref(), scene.as_os_str()], Path::new("."), env);
    let (stdout, stderr) = (group.0.stdout.take().unwrap(), group.0.stderr.take().unwrap());
    let read = |mut pipe: Box<dyn Read + Send>| {
        std::thread::spawn(move || {
            let mut bytes = Vec::new();
            let _ = pipe.read_to_end(&mut bytes);
            bytes
        })
    };
    let (stdout, stderr) = (read(Box::new(stdout)), read(Box::new(stderr)));
    let start = Instant::now();
    let status = loop {
        if let Some(status) = group.0.try_wait().unwrap() {
            break status;
        }
        assert!(start.elapsed() < Duration::from_secs(180), "glint view --first-image did not exit");
        std::thread::sleep(Duration::from_millis(100));
    };
    std::process::Output { status, stdout: stdout.join().unwrap(), stderr: stderr.join().unwrap() }
}

/// The seconds and the note (which kernels the software driver compiled) of a report
/// `first image after 0.81 s (quick kernels, 256 bits)`.
fn first_image_report(out: &std::process::Output) -> (f64, String) {
    let (stdout, stderr) = (String::from_utf8_lossy(&out.stdout), String::from_utf8_lossy(&out.stderr));
    assert!(out.status.success(), "{}: {stderr}", out.status);
    let report = stdout.trim().strip_prefix("first image after ").and_then(|rest| rest.split_once(" s"));
    let Some((seconds, note)) = report.and_then(|(s, note)| Some((s.parse::<f64>().ok()?, note.trim()))) else {
        panic!("expected `first image after N s`, got {stdout:?}");
    };
    (seconds, note.trim_start_matches('(').trim_end_matches(')').to_string())
}

#[test]
fn first_image_reports_the_start_up_and_closes_the_window() {
    let scene = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../scenes/first.toml");
    let (seconds, _) = first_image_report(&first_image(&scene, &[]));
    assert!(seconds > 0.0);
}

/// A scene's first viewing compiles quick kernels, which show its first image
/// sooner; once it has been viewed, the next session compiles optimised ones
/// for Mesa's cache. Without a cache every session is a first one.
#[test]
fn a_scene_viewed_before_gets_optimised_kernels() {
    let scene = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../scenes/first.toml");
    let cache = tempfile::tempdir().unwrap();
    let env = |cache_disabled: Option<&'static str>| {
        [
            (glint_gpu::ADAPTER_ENV, Some(OsStr::new("llvmpipe"))),
            ("XDG_CACHE_HOME", Some(cache.path().as_os_str())),
            (glint_gpu::lavapipe::SHADER_CACHE_ENV, None),
            ("MESA_SHADER_CACHE_DISABLE", cache_disabled.map(OsStr::new)),
            (glint_gpu::lavapipe::LAVAPIPE_WIDTH_ENV, None),
            (glint_gpu::lavapipe::LAVAPIPE_PERF_ENV, None),
        ]
    };
    let kernels = |cache_disabled| first_image_report(&first_image(&scene, &env(cache_disabled))).1;
    let quick = format!("quick kernels, {} bits", glint_gpu::lavapipe::width_for(0, true));
    assert_eq!(kernels(None), quick, "the first viewing");
    assert_eq!(kernels(None), format!("optimised kernels, {} bits", glint_gpu::lavapipe::LAVAPIPE_WIDTH), "the second viewing");
    assert_eq!(kernels(Some("true")), quick, "a viewing without a shader cache");
}

#[test]
fn first_image_of_a_broken_scene_is_its_error() {
    let dir = tempfile::tempdir().unwrap();
    let scene = dir.path().join("broken.toml");
    std::fs::write(&scene, "[camera]\neye = [0, 1\n").unwrap();
    let out = first_image(&scene, &[]);
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(3), "{stderr}");
    assert!(stderr.contains("broken.toml:2"), "the error names the file and line: {stderr}");
    assert!(out.stdout.is_empty(), "no time for an image never shown: {}", String::from_utf8_lossy(&out.stdout));
}

/// Mesa's shader cache does not tell kernels compiled at one SIMD width from
/// those compiled at another, and the viewer crashed loading the other
/// width's: glint gives each width a cache of its own.
#[test]
fn kernels_cached_at_one_vector_width_are_not_loaded_at_another() {
    let scene = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../scenes/first.toml");
    let cache = tempfile::tempdir().unwrap();
    for width in [Some("256".as_ref()), None] {
        let env = [
            ("XDG_CACHE_HOME", Some(cache.path().as_os_str())),
            (glint_gpu::lavapipe::SHADER_CACHE_ENV, None),
            ("MESA_SHADER_CACHE_DISABLE", None),
            (glint_gpu::lavapipe::LAVAPIPE_WIDTH_ENV, width),
            // Optimised kernels, which Glint compiles at its own width when
            // the environment chooses none (quick ones may be 256 bits too).
            (glint_gpu::lavapipe::LAVAPIPE_PERF_ENV, Some("".as_ref())),
        ];
        let out = first_image(&scene, &env);
        assert!(out.status.success(), "at width {width:?}: {}: {}", out.status, String::from_utf8_lossy(&out.stderr));
    }
}
