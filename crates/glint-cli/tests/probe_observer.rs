//! `glint probe --observer EYE LOOK_AT -o tree.png`, end to end: the picture
//! is written whole at the observer's size with the overlay drawn where the
//! observer sees it, the frame it draws is the one printed, and every bad
//! input is one line, a failing exit code and no file.

use std::path::{Path, PathBuf};
use std::process::{Command, Output};

fn glint(args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_glint")).args(args).output().expect("glint runs")
}

fn tutorial() -> String {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../../scenes/tutorial.toml").to_string_lossy().into_owned()
}

fn stderr(o: &Output) -> String {
    String::from_utf8_lossy(&o.stderr).into_owned()
}

fn files_in(dir: &Path) -> Vec<PathBuf> {
    std::fs::read_dir(dir).unwrap().map(|e| e.unwrap().path()).collect()
}

#[test]
fn the_observers_picture_shows_the_eye_where_the_observer_looks_and_the_printed_frame_is_the_drawn_one() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("tree.png");
    let scene = tutorial();
    // The observer looks straight at the tutorial camera's eye (0, 1, 4).
    let args = ["probe", &scene, "178", "96", "--json", "--observer", "-3,2.5,6", "0,1,4", "--observer-width", "200", "--observer-height", "150"];
    let o = glint(&[&args[..], &["-o", out.to_str().unwrap()]].concat());
    assert!(o.status.success(), "{}", stderr(&o));
    let picture = image::open(&out).unwrap().to_rgb8();
    assert_eq!(picture.dimensions(), (200, 150));
    assert_eq!(picture.get_pixel(100, 75).0, [255, 255, 255], "the eye's white dot at the picture's centre");
    assert_eq!(files_in(dir.path()), [out], "no temporary file is left");

    let report: serde_json::Value = serde_json::from_slice(&o.stdout).unwrap();
    let camera = &report["camera"];
    assert_eq!(camera["e"], serde_json::json!([0.0, 1.0, 4.0]));
    let (r, t) = (camera["r"].as_f64().unwrap(), camera["t"].as_f64().unwrap());
    assert_eq!((camera["l"].as_f64(), camera["b"].as_f64(), camera["d"].as_f64()), (Some(-r), Some(-t), Some(1.0)));
    assert!((t - 20f64.to_radians().tan()).abs() < 1e-6 && (r - t * 320.0 / 200.0).abs() < 1e-6, "t = tan(fov/2), r = t·aspect");

    // The same probe without --observer prints the same frame.
    let plain = glint(&["probe", &scene, "178", "96", "--json"]);
    let plain: serde_json::Value = serde_json::from_slice(&plain.stdout).unwrap();
    assert_eq!(plain["camera"], report["camera"]);
}

#[test]
fn bad_observer_inputs_are_one_line_a_failing_exit_and_no_picture() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("tree.png");
    let out = out.to_str().unwrap();
    let missing = dir.path().join("no/such/dir/tree.png");
    let scene = tutorial();
    let cases: [(&[&str], &str); 6] = [
        (&["--observer", "3,2", "0,0,0", "-o", out], "`3,2` is not a point: give three numbers x,y,z"),
        (&["--observer", "3,a,5", "0,0,0", "-o", out], "`3,a,5` is not a point"),
        (&["--observer", "1,1,1", "1,1,1", "-o", out], "--observer: the eye [1, 1, 1] is the point it looks at"),
        (&["--observer", "3,2,5", "0,0,0", "-o", missing.to_str().unwrap()], "cannot write there"),
        (&["--observer", "3,2,5", "0,0,0", "-o", &out.replace(".png", ".exr")], "the observer's picture is a PNG"),
        (&["--observer", "3,2,5", "0,0,0", "--observer-fov", "180", "-o", out], "--observer-fov 180: give a field of view from 1 to 179 degrees"),
    ];
    for (extra, expected) in cases {
        let o = glint(&[&["probe", &scene, "178", "96"][..], extra].concat());
        let message = stderr(&o);
        assert!(!o.status.success() && o.status.code() != Some(101), "{extra:?}: {message}");
        assert!(message.starts_with("glint: ") && message.contains(expected), "{extra:?}: {message}");
        assert_eq!(message.lines().filter(|l| !l.is_empty() && !l.starts_with("For more information")).count(), 1, "{extra:?}: {message}");
        assert!(files_in(dir.path()).is_empty(), "{extra:?} left {:?}", files_in(dir.path()));
    }
    let o = glint(&["probe", &scene, "178", "96", "-o", out]);
    assert_eq!(o.status.code(), Some(2), "-o alone needs --observer: {}", stderr(&o));
}
