//! `glint test` end to end on the GPU (a software adapter in CI; no adapter is a
//! failure, never a skip): a fresh folder fails for want of goldens, `--bless`
//! creates them, re-runs pass and write the same bytes, a changed golden fails
//! with JUnit XML and an HTML report that headless Chromium loads with its
//! images.

mod suite;

use std::collections::BTreeMap;
use std::path::{Path, PathBuf};
use std::process::Output;

use quick_xml::events::Event;
use suite::{arg, chromium, glint, stderr, stdout, SPHERE};

/// The same picture as NFF: 40 × 30.
const NFF: &str = "v\nfrom 0 1.5 5\nat 0 0.5 0\nup 0 1 0\nangle 45\nhither 0.01\nresolution 40 30\n\
b 0.1 0.2 0.4\nl 3 5 4\nf 0.2 0.8 0.3 0.6 0 0 0 1\ns 0 0.8 0 0.8\n";

fn scene_folder() -> tempfile::TempDir {
    let dir = tempfile::tempdir().unwrap();
    std::fs::write(dir.path().join("sphere.toml"), SPHERE).unwrap();
    std::fs::write(dir.path().join("ball.nff"), NFF).unwrap();
    dir
}

fn lines(o: &Output) -> Vec<String> {
    stdout(o).lines().map(str::to_string).collect()
}

/// Every file under `dir` with its bytes.
fn files(dir: &Path) -> BTreeMap<PathBuf, Vec<u8>> {
    std::fs::read_dir(dir).unwrap().map(|e| e.unwrap().path()).filter(|p| p.is_file()).map(|p| (p.clone(), std::fs::read(&p).unwrap())).collect()
}

#[test]
fn a_fresh_folder_fails_then_blesses_then_passes_with_the_same_bytes() {
    let dir = scene_folder();
    let folder = arg(dir.path());

    let o = glint(&["test", folder]);
    assert_eq!(o.status.code(), Some(1), "{}", stderr(&o));
    assert_eq!(
        lines(&o),
        [
            format!("FAIL    ball: no golden: {}", dir.path().join("ball.png").display()),
            format!("FAIL    sphere: no golden: {}", dir.path().join("sphere.png").display()),
            "0 passed, 2 failed".to_string(),
        ]
    );

    let o = glint(&["test", folder, "--bless"]);
    assert_eq!(o.status.code(), Some(0), "{}{}", stdout(&o), stderr(&o));
    assert_eq!(lines(&o).last().map(String::as_str), Some("2 passed, 0 failed"));
    assert!(lines(&o)[0].starts_with("blessed ball: wrote "), "{}", stdout(&o));
    assert_eq!(image::open(dir.path().join("sphere.png")).unwrap().to_rgb8().dimensions(), (48, 36));
    assert_eq!(image::open(dir.path().join("ball.png")).unwrap().to_rgb8().dimensions(), (40, 30));
    let blessed = files(dir.path());

    let o = glint(&["test", folder]);
    assert_eq!(o.status.code(), Some(0), "{}{}", stdout(&o), stderr(&o));
    let out = lines(&o);
    assert_eq!(out.len(), 3, "{out:?}");
    assert_eq!(out[0], "ok      ball: flip 0 <= 0.01, 0% of pixels above 0.2 (at most 0.5%)");
    assert_eq!(out[2], "2 passed, 0 failed");

    // Blessing again by name rewrites the golden, with the same bytes.
    let o = glint(&["test", folder, "--bless", "--case", "sphere"]);
    assert_eq!(lines(&o), [format!("blessed sphere: wrote {}", dir.path().join("sphere.png").display()), "1 passed, 0 failed".into()]);
    assert_eq!(files(dir.path()), blessed, "re-blessing changed bytes");
}

#[test]
fn a_changed_golden_fails_with_junit_xml_and_a_report() {
    let dir = scene_folder();
    let folder = arg(dir.path());
    let o = glint(&["test", folder, "--bless"]);
    assert_eq!(o.status.code(), Some(0), "{}{}", stdout(&o), stderr(&o));
    // Paint a 4 × 3 block of the sphere's golden white at (20, 10).
    let golden = dir.path().join("sphere.png");
    let mut image = image::open(&golden).unwrap().to_rgb8();
    for y in 10..13 {
        for x in 20..24 {
            image.put_pixel(x, y, image::Rgb([255, 255, 255]));
        }
    }
    image.save(&golden).unwrap();

    let out = tempfile::tempdir().unwrap();
    let junit = out.path().join("junit.xml");
    let report = out.path().join("report");
    let o = glint(&["test", folder, "--junit", arg(&junit), "--report", arg(&report)]);
    assert_eq!(o.status.code(), Some(1), "{}{}", stdout(&o), stderr(&o));
    let out_lines = lines(&o);
    assert!(out_lines[0].starts_with("ok      ball: "), "{out_lines:?}");
    assert!(out_lines[1].starts_with("FAIL    sphere: flip "), "{out_lines:?}");
    assert!(out_lines[1].contains(" of pixels above 0.2 (more than the 0.5% allowed), worst ("), "{out_lines:?}");
    assert_eq!(out_lines[2], "1 passed, 1 failed");

    check_junit(&std::fs::read_to_string(&junit).unwrap(), dir.path());
    check_report_in_chromium(&report);

    // Same inputs, same bytes: the XML, the page and its images.
    let first = (std::fs::read(&junit).unwrap(), files(&report));
    let again = glint(&["test", folder, "--junit", arg(&junit), "--report", arg(&report)]);
    assert_eq!(again.status.code(), Some(1));
    assert_eq!(stdout(&again), stdout(&o));
    assert_eq!((std::fs::read(&junit).unwrap(), files(&report)), first, "a re-run wrote different bytes");

    // Blessing writes only the failing golden.
    let ball = std::fs::read(dir.path().join("ball.png")).unwrap();
    let o = glint(&["test", folder, "--bless"]);
    assert_eq!(o.status.code(), Some(0));
    assert!(lines(&o)[0].starts_with("ok      ball") && lines(&o)[1].starts_with("blessed sphere"), "{}", stdout(&o));
    assert_eq!(std::fs::read(dir.path().join("ball.png")).unwrap(), ball);
}

/// The elements JUnit's schema requires: testsuites, a testsuite with name,
/// tests and failures, testcases with name and classname, and a failure
/// element inside each failed testcase.
fn check_junit(xml: &str, folder: &Path) {
    let mut reader = quick_xml::Reader::from_str(xml);
    let mut open: Vec<String> = Vec::new();
    let mut testcases = Vec::new();
    let mut failures = Vec::new();
    let mut suites = 0;
    loop {
        let (element, empty) = match reader.read_event().unwrap() {
            Event::Start(e) => (e, false),
            Event::Empty(e) => (e, true),
            Event::End(_) => {
                open.pop();
                continue;
            }
            Event::Eof => break,
            _ => continue,
        };
        let name = String::from_utf8(element.name().as_ref().to_vec()).unwrap();
        let attributes: BTreeMap<String, String> = element
            .attributes()
            .map(|a| {
                let a = a.unwrap();
                let value = a.normalized_value(quick_xml::XmlVersion::Implicit1_0).unwrap().into_owned();
                (String::from_utf8(a.key.as_ref().to_vec()).unwrap(), value)
            })
            .collect();
        let parent = open.last().cloned();
        match name.as_str() {
            "testsuites" => assert_eq!(parent, None),
            "testsuite" => {
                suites += 1;
                assert_eq!(parent.as_deref(), Some("testsuites"));
                let folder_name = folder.file_name().unwrap().to_str().unwrap();
                assert_eq!(attributes.get("name").map(String::as_str), Some(folder_name));
                assert_eq!(attributes.get("tests").map(String::as_str), Some("2"));
                assert_eq!(attributes.get("failures").map(String::as_str), Some("1"));
            }
            "testcase" => {
                assert_eq!(parent.as_deref(), Some("testsuite"));
                assert!(attributes.contains_key("classname"), "{attributes:?}");
                testcases.push(attributes["name"].clone());
            }
            "failure" => {
                assert_eq!(parent.as_deref(), Some("testcase"));
                assert!(attributes["message"].starts_with("flip "), "{attributes:?}");
                failures.push(testcases.last().cloned().unwrap());
            }
            other => panic!("unexpected element {other}"),
        }
        if !empty {
            open.push(name);
        }
    }
    assert!(open.is_empty(), "unclosed: {open:?}");
    assert_eq!(suites, 1);
    assert_eq!(testcases, ["ball", "sphere"]);
    assert_eq!(failures, ["sphere"]);
}

fn check_report_in_chromium(report: &Path) {
    let index = report.join("index.html");
    let url = format!("file://{}", index.display());
    let o = chromium(&["--dump-dom", &url]);
    assert!(o.status.success(), "{}", stderr(&o));
    let dom = stdout(&o);
    assert!(dom.contains("<h1>glint test: "), "{dom}");
    let sources: Vec<&str> = dom.split("<img src=\"").skip(1).map(|rest| rest.split('"').next().unwrap()).collect();
    let expected = ["sphere-reference.png", "sphere-render.png", "sphere-diff.png", "sphere-reference-zoom.png", "sphere-render-zoom.png"];
    assert_eq!(sources, expected, "{dom}");
    for source in &sources {
        let image = image::open(report.join(source)).unwrap_or_else(|e| panic!("{source}: {e}"));
        assert!(image.width() >= 48, "{source}");
    }
    // The case's settings, and where it differs: the white block painted at (20, 10).
    assert!(dom.contains("<p>settings: view shaded, max depth 5, 1 spp, 48x36</p>"), "{dom}");
    let zoom = image::open(report.join("sphere-reference-zoom.png")).unwrap().to_rgb8();
    assert!(zoom.pixels().any(|p| p.0 == [255, 255, 255]), "the magnified golden shows the white block");

    // A screenshot shows the images drawn: the sphere's red and the sky's blue
    // are colours the page's own text and borders never use.
    let shot = report.join("screenshot.png");
    let o = chromium(&[&format!("--screenshot={}", shot.display()), "--window-size=1400,1000", &url]);
    assert!(o.status.success(), "{}", stderr(&o));
    let screenshot = image::open(&shot).unwrap().to_rgb8();
    std::fs::remove_file(&shot).unwrap();
    let count = |pred: fn(&[u8; 3]) -> bool| screenshot.pixels().filter(|p| pred(&p.0)).count();
    let red = count(|[r, g, b]| *r > 120 && *r > 2 * *g && *r > 2 * *b);
    let blue = count(|[r, g, b]| *b > 60 && *b > *r + 30 && *b > *g + 10);
    assert!(red > 500 && blue > 2000, "images not drawn: {red} red and {blue} blue pixels");
}

#[test]
fn a_manifest_sets_render_options_metrics_and_float_goldens() {
    let dir = tempfile::tempdir().unwrap();
    std::fs::create_dir(dir.path().join("scenes")).unwrap();
    std::fs::write(dir.path().join("scenes/sphere.toml"), SPHERE).unwrap();
    let manifest = dir.path().join("suite.toml");
    std::fs::write(
        &manifest,
        r#"
[render]
spp = 4
filter = "tent"
seed = 3

[[case]]
scene = "scenes/sphere.toml"
golden = "goldens/sphere.png"
render = { fit = [24, 24] }

[[case]]
name = "sphere-linear"
scene = "scenes/sphere.toml"
golden = "goldens/sphere.exr"
render = { width = 20, height = 10 }
compare = { metric = "rmse", threshold = 1e-6 }

[[case]]
name = "sphere-normals"
scene = "scenes/sphere.toml"
golden = "goldens/normals.pfm"
render = { view = "normals" }
compare = { metric = "max", threshold = 0 }

[[case]]
name = "sphere-depth"
scene = "scenes/sphere.toml"
golden = "goldens/depth.exr"
render = { view = "depth" }
compare = { metric = "max", threshold = 0 }
"#,
    )
    .unwrap();
    // A golden written by `glint render` (a one-channel EXR for the depth view) matches.
    std::fs::create_dir(dir.path().join("goldens")).unwrap();
    let depth = dir.path().join("goldens/depth.exr");
    let o = glint(&["render", arg(&dir.path().join("scenes/sphere.toml")), "--view", "depth", "-o", arg(&depth), "-q"]);
    assert!(o.status.success(), "{}", stderr(&o));
    let o = glint(&["test", arg(&manifest), "--bless"]);
    assert_eq!(o.status.code(), Some(0), "{}{}", stdout(&o), stderr(&o));
    let out = lines(&o);
    assert_eq!(out.len(), 5, "{}", stdout(&o));
    assert!(out[2].starts_with("blessed sphere-normals") && out[3].starts_with("ok      sphere-depth: max 0 <= 0"), "{out:?}");
    assert_eq!(image::open(dir.path().join("goldens/sphere.png")).unwrap().to_rgb8().dimensions(), (24, 18));
    let exr = image::open(dir.path().join("goldens/sphere.exr")).unwrap().to_rgb32f();
    assert_eq!(exr.dimensions(), (20, 10));
    let (w, h, _) = glint_gpu::read_pfm(&std::fs::read(dir.path().join("goldens/normals.pfm")).unwrap()).unwrap();
    assert_eq!((w, h), (48, 36));

    let o = glint(&["test", arg(&manifest)]);
    assert_eq!(o.status.code(), Some(0), "{}{}", stdout(&o), stderr(&o));
    let out = lines(&o);
    assert!(out[1].starts_with("ok      sphere-linear: rmse 0 <= 0.000001"), "{out:?}");
    assert!(out[2].starts_with("ok      sphere-normals: max 0 <= 0"), "{out:?}");
    assert_eq!(out[4], "4 passed, 0 failed");

    let o = glint(&["test", arg(&manifest), "--case", "sphere-linear"]);
    assert_eq!(lines(&o), [out[1].clone(), "1 passed, 0 failed".into()]);
}

#[test]
fn suite_errors_are_one_line_with_their_exit_code() {
    let dir = scene_folder();
    std::fs::write(dir.path().join("broken.toml"), "[image]\nwidth = \"wide\"\n").unwrap();
    // A broken scene fails its case, and the others still run.
    let o = glint(&["test", arg(dir.path())]);
    assert_eq!(o.status.code(), Some(1));
    let out = lines(&o);
    assert!(out[1].starts_with(&format!("FAIL    broken: {}:2:", dir.path().join("broken.toml").display())), "{out:?}");
    assert_eq!(out.last().map(String::as_str), Some("0 passed, 3 failed"));

    let manifest = dir.path().join("m.toml");
    std::fs::write(&manifest, "[[case]]\nscene = \"sphere.toml\"\nrender = { spp = 0 }\n").unwrap();
    let empty = tempfile::tempdir().unwrap();
    let missing = dir.path().join("missing.toml");
    let cases: [(Vec<&str>, i32, String); 4] = [
        (vec![arg(&manifest)], 3, format!("glint: {}:3:", manifest.display())),
        (vec![arg(empty.path())], 3, "no scene files (.toml, .nff or .obj) in the directory".into()),
        (vec![arg(&missing)], 3, "missing.toml: cannot read manifest".into()),
        (vec![arg(dir.path()), "--case", "nope"], 2, "no case named `nope`".into()),
    ];
    for (extra, code, needle) in cases {
        let mut args = vec!["test"];
        args.extend(&extra);
        let o = glint(&args);
        assert_eq!(o.status.code(), Some(code), "{args:?}: {}", stderr(&o));
        assert!(stderr(&o).contains(&needle), "{args:?}: {}", stderr(&o));
        assert_eq!(stderr(&o).trim_end().lines().count(), 1, "{}", stderr(&o));
        assert_eq!(stdout(&o), "", "{args:?}");
    }
    let o = glint(&["test", arg(dir.path()), "--junit", "/no/such/dir/j.xml"]);
    assert_eq!(o.status.code(), Some(5), "{}", stderr(&o));
    assert!(stderr(&o).contains("glint: /no/such/dir/j.xml: cannot write: "), "{}", stderr(&o));
}
