//! What the `glint test` suites share: the binary, Chromium to load their
//! reports, and a small scene.
#![allow(dead_code)] // each test binary uses a different part of this module

use std::path::Path;
use std::process::{Command, Output};

pub fn glint(args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_glint")).args(args).output().expect("glint runs")
}

pub fn stdout(o: &Output) -> String {
    String::from_utf8_lossy(&o.stdout).into_owned()
}

pub fn stderr(o: &Output) -> String {
    String::from_utf8_lossy(&o.stderr).into_owned()
}

/// Chromium (or Google Chrome: `.ci/chromium` picks) as the environment runs
/// it: headless, no sandbox, no GPU, no network services, a fresh profile.
pub fn chromium(args: &[&str]) -> Output {
    let profile = tempfile::tempdir().unwrap();
    let user_data = format!("--user-data-dir={}", profile.path().display());
    Command::new(concat!(env!("CARGO_MANIFEST_DIR"), "/../../.ci/chromium"))
        .args([
            "--headless",
            "--no-sandbox",
            "--disable-gpu",
            "--disable-background-networking",
            "--disable-component-update",
            "--disable-sync",
            "--no-first-run",
            &user_data,
        ])
        .args(args)
        .output()
        .expect("Chromium or Google Chrome runs (bash .ci/setup --tests installs Chromium)")
}

pub fn arg(path: &Path) -> &str {
    path.to_str().unwrap()
}

/// A small scene: a red sphere on a grey floor under one light.
pub const SPHERE: &str = r#"
[image]
width = 48
height = 36
background = [0.1, 0.2, 0.4]

[camera]
eye = [0, 1.5, 5]
look_at = [0, 0.5, 0]
fov = 45

[[light]]
type = "point"
position = [3, 5, 4]

[material.red]
color = [0.9, 0.15, 0.1]
kd = 0.8
ks = 0.3

[material.grey]
color = [0.6, 0.6, 0.6]
kd = 0.9

[[object]]
type = "sphere"
center = [0, 0.8, 0]
radius = 0.8
material = "red"

[[object]]
type = "polygon"
vertices = [[-4, 0, -4], [-4, 0, 4], [4, 0, 4], [4, 0, -4]]
material = "grey"
"#;
