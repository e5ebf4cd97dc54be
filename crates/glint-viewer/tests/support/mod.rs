//! What the viewer's headless tests share: a scene, a harness running the
//! viewer on the GPU, and ways to wait for it, click it and look at its image.

// Each test binary uses its own part of this.
#![allow(dead_code)]

use std::path::{Path, PathBuf};
use std::time::{Duration, Instant};

use egui::{Event, Modifiers, PointerButton, Pos2};
use egui_kittest::kittest::Queryable;
use egui_kittest::Harness;
use glam::Vec3;
use glint_gpu::shaders::ShaderSource;
use glint_viewer::{ViewerApp, ViewerOptions};
use image::RgbaImage;

/// Long enough for a software adapter to compile the kernels on a busy machine.
pub const TIMEOUT: Duration = Duration::from_secs(120);

pub const SCENE: &str = r#"
[image]
width = 320
height = 200
background = [0.3, 0.4, 0.6]

[camera]
eye = [0, 1.5, 6]
look_at = [0, 0.8, 0]
fov = 40

[ambient]
intensity = 0.15

[[light]]
type = "point"
position = [-3, 5, 4]

[material.floor]
color = [0.8, 0.8, 0.75]

[material.red]
color = [0.9, 0.15, 0.1]
ks = 0.5
shininess = 40

[[object]]
type = "polygon"
vertices = [[-4, 0, -4], [4, 0, -4], [4, 0, 4], [-4, 0, 4]]
material = "floor"

[[object]]
type = "sphere"
center = [-0.9, 0.8, 0]
radius = 0.8
material = "red"

[[object]]
type = "sphere"
center = [1.1, 0.6, 0.5]
radius = 0.6
"#;

pub const RED_SPHERE: Vec3 = Vec3::new(-0.9, 0.8, 0.0);

pub fn write_scene(dir: &Path, text: &str) -> PathBuf {
    let path = dir.join("scene.toml");
    std::fs::write(&path, text).unwrap();
    path
}

pub fn harness(scene: Option<PathBuf>, shaders: ShaderSource) -> Harness<'static, ViewerApp> {
    Harness::builder()
        .with_size([1100.0, 760.0])
        .wgpu_setup(glint_viewer::wgpu_setup())
        .build_eframe(move |cc| ViewerApp::new(cc, ViewerOptions { scene, shaders, scene_text: None, first_image: None }).unwrap_or_else(|e| panic!("{e}")))
}

/// Steps frames until `done` holds, failing after `TIMEOUT`.
pub fn wait_for(h: &mut Harness<'_, ViewerApp>, what: &str, done: impl Fn(&ViewerApp) -> bool) {
    let start = Instant::now();
    while !done(h.state()) {
        assert!(start.elapsed() < TIMEOUT, "timed out waiting for {what}; errors: {:?}", h.state().errors());
        h.step();
        std::thread::sleep(Duration::from_millis(2));
    }
}

/// Steps until every sample of the current state is in and shown, and once
/// more so the panels show it too.
pub fn settle(h: &mut Harness<'_, ViewerApp>) {
    h.step();
    wait_for(h, "the image to converge", ViewerApp::is_converged);
    h.step();
}

/// The image part of the rendered window.
pub fn image_of(h: &mut Harness<'_, ViewerApp>) -> RgbaImage {
    let rect = h.state().image_rect().expect("an image is shown");
    let window = h.render().unwrap();
    image::imageops::crop_imm(&window, rect.min.x.ceil() as u32, rect.min.y.ceil() as u32, rect.width() as u32 - 1, rect.height() as u32 - 1)
        .to_image()
}

pub fn mean_difference(a: &RgbaImage, b: &RgbaImage) -> f64 {
    assert_eq!(a.dimensions(), b.dimensions());
    let sum: u64 = a.pixels().zip(b.pixels()).map(|(p, q)| (0..3).map(|c| p[c].abs_diff(q[c]) as u64).sum::<u64>()).sum();
    sum as f64 / (a.width() * a.height() * 3) as f64
}

/// Where the world point `p` is drawn, in points.
pub fn screen_pos(app: &ViewerApp, p: Vec3) -> Pos2 {
    let (rect, (w, h)) = (app.image_rect().unwrap(), app.render_size().unwrap());
    let (x, y) = app.scene().unwrap().camera.project(w, h, p.as_dvec3()).unwrap();
    rect.min + egui::vec2(x as f32 / w as f32, y as f32 / h as f32) * rect.size()
}

/// Clicks at `pos`, then steps once more so the panels show the outcome.
pub fn click(h: &mut Harness<'_, ViewerApp>, pos: Pos2) {
    click_with(h, pos, Modifiers::NONE);
}

/// Clicks at `pos` holding `modifiers`, then steps once more so the panels show the outcome.
pub fn click_with(h: &mut Harness<'_, ViewerApp>, pos: Pos2, modifiers: Modifiers) {
    h.event(Event::ModifiersChanged(modifiers));
    h.event(Event::PointerMoved(pos));
    for pressed in [true, false] {
        h.event(Event::PointerButton { pos, button: PointerButton::Primary, pressed, modifiers });
    }
    h.event(Event::ModifiersChanged(Modifiers::NONE));
    h.step();
    h.step();
}

/// Clicks the button labelled `label`, scrolling the panel to it first.
pub fn press(h: &mut Harness<'_, ViewerApp>, label: &str) {
    h.get_by_label(label).scroll_to_me();
    // The scroll starts a frame or two later and is animated: wait for the
    // button to come to rest.
    h.run_steps(3);
    let mut rect = None;
    while rect != Some(h.get_by_label(label).rect()) {
        rect = Some(h.get_by_label(label).rect());
        h.step();
    }
    h.get_by_label(label).click();
    h.step();
}
