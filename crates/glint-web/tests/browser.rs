//! The page in a real browser: builds it (web/build.sh), serves it on
//! 127.0.0.1, and drives headless Chromium's WebGPU with real input events
//! (browser/drive.cjs, Playwright from npm on Debian's Chromium). The
//! showcase must equal the native renderer's image under the golden suite's
//! FLIP criteria; an OBJ opened by the file picker renders as natively; a
//! light dragged through the UI changes the image, and the TOML the page
//! saves then renders natively as the page showed it; a dropped NFF renders;
//! bad files are the CLI's one-line messages; a probed pixel shows its ray
//! tree; a link's scene, camera and samples per pixel (several, so that
//! samples must keep coming after the first) render as natively. No WebGPU is
//! a failure, never a skip.

use std::io::Read;
use std::net::{TcpListener, TcpStream};
use std::path::{Path, PathBuf};
use std::process::{Child, Command, Stdio};
use std::time::{Duration, Instant};

use glint_golden::{judge, measure, Criteria, LinearImage, Metric, Verdict};
use glint_gpu::shaders::ShaderSource;
use glint_gpu::{Acceleration, Gpu, RenderOptions, Renderer};
use glint_scene::Scene;
use glint_web::{catalogue, fragment};

/// The Playwright the driver uses, installed under target/ by npm.
const PLAYWRIGHT: &str = "playwright-core@1.65.1";

fn root() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../..")
}

/// Runs `command` to its end within `limit`, failing with its output otherwise.
fn run(what: &str, command: &mut Command, limit: Duration) -> String {
    let mut child = command.stdout(Stdio::piped()).stderr(Stdio::piped()).spawn().unwrap_or_else(|e| panic!("{what}: cannot start: {e}"));
    let (mut stdout, mut stderr) = (child.stdout.take().unwrap(), child.stderr.take().unwrap());
    let out = std::thread::spawn(move || {
        let mut text = String::new();
        let _ = stdout.read_to_string(&mut text);
        text
    });
    let err = std::thread::spawn(move || {
        let mut text = String::new();
        let _ = stderr.read_to_string(&mut text);
        text
    });
    let status = wait(&mut child, limit);
    let (out, err) = (out.join().unwrap(), err.join().unwrap());
    match status {
        Some(status) if status.success() => out,
        Some(status) => panic!("{what} failed ({status}):\n{}", without_progress(&out, &err)),
        None => panic!("{what} did not finish within {} s:\n{}", limit.as_secs(), without_progress(&out, &err)),
    }
}

/// A failed command's output without cargo's progress lines, whose hundreds
/// of `Compiling …` would push the error itself out of a CI log's excerpt.
fn without_progress(out: &str, err: &str) -> String {
    let progress = ["Compiling ", "Downloading ", "Downloaded ", "Updating ", "Locking ", "Adding ", "Checking ", "Fresh "];
    let kept: Vec<&str> = out.lines().chain(err.lines()).filter(|l| !progress.iter().any(|p| l.trim_start().starts_with(p))).collect();
    kept.join("\n")
}

/// The child's exit status, or `None` (and the child killed) after `limit`.
fn wait(child: &mut Child, limit: Duration) -> Option<std::process::ExitStatus> {
    let deadline = Instant::now() + limit;
    while Instant::now() < deadline {
        if let Some(status) = child.try_wait().expect("the child can be waited for") {
            return Some(status);
        }
        std::thread::sleep(Duration::from_millis(100));
    }
    let _ = child.kill();
    let _ = child.wait();
    None
}

/// A static file server on a free port of 127.0.0.1, stopped when dropped.
struct Server {
    child: Child,
    url: String,
}

impl Server {
    fn start(dir: &Path) -> Self {
        let port = TcpListener::bind("127.0.0.1:0").unwrap().local_addr().unwrap().port();
        let child = Command::new("python3")
            .args(["-m", "http.server", &port.to_string(), "--bind", "127.0.0.1", "--directory"])
            .arg(dir)
            .stdout(Stdio::null())
            .stderr(Stdio::null())
            .spawn()
            .expect("python3 serves the page");
        let server = Server { child, url: format!("http://127.0.0.1:{port}/") };
        let deadline = Instant::now() + Duration::from_secs(30);
        while TcpStream::connect(("127.0.0.1", port)).is_err() {
            assert!(Instant::now() < deadline, "the server on port {port} did not start");
            std::thread::sleep(Duration::from_millis(100));
        }
        server
    }
}

impl Drop for Server {
    fn drop(&mut self) {
        let _ = self.child.kill();
        let _ = self.child.wait();
    }
}

/// The link the test opens: a camera of its own on whitted1980, and samples
/// enough that the page must keep adding them after the first.
const LINK: &str = "scene=whitted1980.toml&eye=2.5,3,7&look=0,1,-1&up=0,1,0&fov=35&spp=8";

/// The files the test opens in the page, by name.
const FILES: [(&str, &[u8]); 8] = [
    ("dropped.nff", b"v\nfrom 0 0 5\nat 0 0 0\nup 0 1 0\nangle 40\nhither 0.01\nresolution 160 120\nb 0.2 0.3 0.5\nl 0.6 0.5 2.5\nf 1 0.3 0.2 0.8 0.2 20 0 1\ns 0 0 0 1\n"),
    ("broken.toml", b"[image]\nwidth = 64\nheight = 48\n\n[camera]\neye = [0, 1]\nlook_at = [0, 0, 0]\n"),
    ("empty.nff", b""),
    ("garbage.obj", b"\x89PNG\r\n\x1a\n\x00\x00\x00\rIHDR\xff\xfe\x00"),
    ("cube.obj", b"mtllib cube.mtl\nusemtl red\nv 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n"),
    ("notes.mtl", b"newmtl red\nKd 1 0 0\n"),
    ("picked.obj", b"mtllib picked.mtl\nusemtl green\nv -1 -1 0\nv 1 -1 0\nv 1 1 0\nv -1 1 0\nv 0 0 1.2\nf 1 2 5\nf 2 3 5\nf 3 4 5\nf 4 1 5\n"),
    ("picked.mtl", b"newmtl green\nKd 0.2 0.8 0.3\nKs 0.3 0.3 0.3\nNs 20\n"),
];

/// What the CLI says about `name`: its load error, or its warnings.
fn cli_messages(name: &str, bytes: &[u8]) -> Vec<String> {
    glint_scene::opened_files::provide(name, bytes);
    let one_line = |e: &dyn std::fmt::Display| e.to_string().split_whitespace().collect::<Vec<_>>().join(" ");
    match glint_scene::load(Path::new(name)) {
        Ok(scene) => scene.warnings.iter().map(|w| one_line(w)).collect(),
        Err(e) => vec![one_line(&e)],
    }
}

/// The native renderer's image of `scene` at `width` x `height`, `spp`
/// samples per pixel accumulated as the viewer does: one through each pixel's
/// centre, or more jittered without a fixed count.
fn native_image(mut scene: Scene, (width, height): (u32, u32), spp: u32) -> LinearImage {
    (scene.width, scene.height) = (width, height);
    let gpu = Gpu::new().unwrap_or_else(|e| panic!("the native image needs an adapter (lavapipe in CI): {e}"));
    let renderer = Renderer::new(gpu.device, gpu.queue, &ShaderSource::Embedded).unwrap();
    let prepared = renderer.prepare(&scene, width, height, Acceleration::Bvh).unwrap();
    let options = RenderOptions { spp: if spp == 1 { 1 } else { 0 }, ..RenderOptions::default() };
    renderer.clear_rows(&prepared.buffers, 0..height);
    for sample in 0..spp {
        renderer.trace_rows(&prepared.buffers, sample, &options, 0..height).unwrap();
    }
    let image = renderer.resolve(&prepared.buffers, &RenderOptions::default()).unwrap();
    LinearImage::from_render(&image, glint_gpu::Format::Png)
}

fn parse_toml(name: &str, text: &str) -> Scene {
    glint_scene::toml_scene::parse(text, Path::new(name)).unwrap_or_else(|e| panic!("{e}"))
}

/// `tested` held against `reference` by the golden suite's FLIP criteria.
fn flip(reference: &LinearImage, tested: &LinearImage) -> Verdict {
    let measured = measure(reference, tested).unwrap_or_else(|e| panic!("{e:?}"));
    judge(&measured, &Criteria::for_metric(Metric::Flip))
}

fn read_png(path: &Path) -> LinearImage {
    glint_golden::read(path).unwrap_or_else(|e| panic!("{e:?}"))
}

#[test]
fn the_page_renders_edits_opens_files_and_probes_in_headless_chromium() {
    let root = root();
    let work = root.join("target/web-test");
    let site = work.join("site");
    let started = Instant::now();
    run("web/build.sh", Command::new("bash").arg(root.join("web/build.sh")).arg(&site), Duration::from_secs(45 * 60));
    eprintln!("built the page in {:.0} s", started.elapsed().as_secs_f64());
    let node = work.join("node");
    let playwright = node.join("node_modules/playwright-core");
    if !playwright.join("package.json").exists() {
        let mut install = Command::new("npm");
        install.args(["install", "--no-save", "--no-audit", "--no-fund", "--prefix"]).arg(&node).arg(PLAYWRIGHT);
        run("npm install playwright-core", &mut install, Duration::from_secs(600));
    }
    let files = tempfile::tempdir().unwrap();
    for (name, bytes) in FILES {
        std::fs::write(files.path().join(name), bytes).unwrap();
    }
    let out = tempfile::tempdir().unwrap();
    let server = Server::start(&site);
    let driven = run(
        "the browser driver",
        Command::new("node")
            .arg(Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/browser/drive.cjs"))
            .arg(&server.url)
            .arg(out.path())
            .arg(files.path())
            .arg(LINK)
            .env("GLINT_PLAYWRIGHT", &playwright),
        Duration::from_secs(20 * 60),
    );
    drop(server);
    eprintln!("{driven}");
    let results: serde_json::Value = serde_json::from_slice(&std::fs::read(out.path().join("results.json")).unwrap()).unwrap();
    eprintln!("first image {} ms, {} ms/frame", results["first_image_ms"], results["frame_ms"]);
    eprintln!("the link: {}", results["link"]);

    // The showcase equals the native image of the same size.
    let page = read_png(&out.path().join("showcase.png"));
    let showcase = parse_toml("showcase.toml", include_str!("../../../scenes/showcase.toml"));
    let same = flip(&native_image(showcase, (page.width, page.height), 1), &page);
    assert!(same.passed(), "the page's showcase differs from the native image: {}", same.summary());

    // The OBJ and MTL opened by the file picker render as natively.
    assert_eq!(results["picked"]["scene"], "picked.obj");
    assert_eq!((&results["picked"]["errors"], &results["picked"]["warnings"]), (&serde_json::json!([]), &serde_json::json!([])));
    for (name, bytes) in &FILES[6..] {
        glint_scene::opened_files::provide(name, *bytes);
    }
    let picked = read_png(&out.path().join("picked.png"));
    let obj = glint_scene::load(Path::new("picked.obj")).unwrap();
    let same = flip(&native_image(obj, (picked.width, picked.height), 1), &picked);
    assert!(same.passed(), "the picked OBJ differs from the native image: {}", same.summary());

    // The probed pixel's tree, as the side panel heads it.
    let tree: Vec<&str> = results["tree"].as_array().unwrap().iter().filter_map(|l| l.as_str()).collect();
    assert!(tree[0].starts_with("pixel (") && tree.iter().any(|l| l.contains("eye")), "{tree:?}");

    // The dropped NFF rendered, without a problem.
    assert_eq!(results["dropped"]["scene"], "dropped.nff");
    assert_eq!(results["dropped"]["errors"], serde_json::json!([]));
    let dropped = read_png(&out.path().join("dropped.png"));

    // Dragging its light (not the camera) changed the image.
    let moved = &results["light_moved"];
    assert_eq!(moved["link_before"], moved["link_after"], "the drag moved the camera, not the light");
    let moved = read_png(&out.path().join("light-moved.png"));
    assert!(!flip(&dropped, &moved).passed(), "moving the light {} left the image as it was", results["light_moved"]);

    // The TOML saved then holds the scene as edited: natively it renders as
    // the page showed it, with the light moved.
    let saved = std::fs::read_to_string(out.path().join("light-moved.toml")).unwrap();
    assert_eq!(results["moved_toml"]["suggested"], "dropped-view.toml");
    let same = flip(&native_image(parse_toml("light-moved.toml", &saved), (moved.width, moved.height), 1), &moved);
    assert!(same.passed(), "the saved TOML renders otherwise than the page showed it: {}\n{saved}", same.summary());

    // The link's camera is the page's, and its samples came, each of them
    // as natively.
    let link = fragment::decode(LINK).unwrap().unwrap();
    let shown = fragment::decode(results["link"]["link"].as_str().unwrap()).unwrap();
    assert_eq!(shown.as_ref(), Some(&link), "the page took the link's {LINK} as {}", results["link"]);
    assert_eq!(results["link"]["errors"], serde_json::json!([]));
    let spp = link.spp.unwrap();
    assert_eq!(results["link"]["samples"], spp);
    let linked = read_png(&out.path().join("link.png"));
    let mut scene = parse_toml(&link.scene, catalogue::built_in(&link.scene).unwrap().text);
    scene.camera = link.camera.unwrap();
    let same = flip(&native_image(scene, (linked.width, linked.height), spp), &linked);
    assert!(same.passed(), "the link's image differs from the native one: {}", same.summary());

    // Each bad file is what the CLI says about it, in the page. An OBJ's
    // missing MTL is a warning, whose reason is the page's own.
    let cube = results["bad"]["cube.obj"][0].as_str().unwrap_or_default();
    assert!(cube.starts_with("cube.obj:1: cannot read material library `cube.mtl` (not among the files opened"), "{cube}");
    for (name, bytes) in &FILES[1..4] {
        let said: Vec<&str> = results["bad"][name].as_array().unwrap().iter().filter_map(|l| l.as_str()).collect();
        let cli = cli_messages(name, bytes);
        assert!(!cli.is_empty() && cli.iter().all(|m| said.contains(&m.as_str())), "{name}: the page said {said:?}, the CLI says {cli:?}");
    }
    let mtl: Vec<&str> = results["bad"]["notes.mtl"].as_array().unwrap().iter().filter_map(|l| l.as_str()).collect();
    assert!(mtl.iter().any(|m| m.starts_with("notes.mtl: unknown scene format")), "{mtl:?}");
}
