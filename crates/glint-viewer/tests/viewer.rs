//! The viewer driven headless by egui_kittest on the GPU (a software adapter in CI): it
//! loads and renders a scene, sliders and clicks change the image and the
//! selection, files reload, and the whole window matches a snapshot under FLIP.
//! No adapter is a failure, never a skip.
//!
//! `GLINT_BLESS=1` rewrites the snapshot in tests/snapshots/.

mod support;

use std::path::{Path, PathBuf};
use std::sync::Arc;
use std::time::Duration;

use egui::Pos2;
use egui_kittest::kittest::Queryable;
use glam::Vec3;
use glint_gpu::shaders::{ShaderSource, SOURCES};
use support::{click, harness, image_of, mean_difference, press, screen_pos, settle, wait_for, write_scene, RED_SPHERE, SCENE};

/// eframe opens the device that `glint render` opens: the same profile, with
/// subgroups exactly where it walks eye tiles (on CI's software adapter, it
/// does), and WebGPU's default limits but for those of a scene's size, which
/// it cannot raise later. On any adapter.
#[test]
fn the_viewer_opens_the_device_its_profile_expects() {
    let state = egui_kittest::wgpu::create_render_state(glint_viewer::wgpu_setup(), egui_wgpu::RendererOptions::PREDICTABLE);
    let gpu = glint_gpu::Gpu::new().unwrap_or_else(|e| panic!("GPU tests need an adapter (a software adapter in CI): {e}"));
    let profile = glint_gpu::DeviceProfile::of_device(&state.device).unwrap();
    assert_eq!(profile, gpu.profile());
    assert_eq!(state.device.features().contains(wgpu::Features::SUBGROUP), profile.eye_tiles, "{profile:?}");
    if state.adapter.get_info().name.contains("llvmpipe") {
        assert!(profile.eye_tiles, "{profile:?}");
    }
    let (limits, defaults) = (state.device.limits(), wgpu::Limits::default());
    assert_eq!(limits.max_storage_buffers_per_shader_stage, defaults.max_storage_buffers_per_shader_stage);
    assert_eq!(limits.max_texture_dimension_2d, state.adapter.limits().max_texture_dimension_2d);
}

#[test]
fn loads_and_renders_a_scene() {
    let dir = tempfile::tempdir().unwrap();
    let mut h = harness(Some(write_scene(dir.path(), SCENE)), ShaderSource::Embedded);
    settle(&mut h);
    assert_eq!(h.state().scene().unwrap().primitive_count(), 3);
    h.get_by_label_contains("3 primitives");
    h.get_by_label_contains(&format!("{0}/{0} spp", h.state().target_samples()));
    let (w, hgt) = h.state().render_size().unwrap();
    let rect = h.state().image_rect().unwrap();
    assert!((w as f32 - rect.width()).abs() <= 1.0 && (hgt as f32 - rect.height()).abs() <= 1.0, "one pixel per point at scale 1");
    assert!(((w as f32 / hgt as f32) - 1.6).abs() < 0.01, "the scene's aspect ratio: {w}×{hgt}");

    // The red sphere is red and the sky is the background.
    let image = image_of(&mut h);
    let at = |p: Pos2| *image.get_pixel((p.x - rect.min.x) as u32, (p.y - rect.min.y) as u32);
    let red = at(screen_pos(h.state(), RED_SPHERE));
    assert!(red[0] > 120 && red[1] < 80 && red[2] < 80, "{red:?}");
    let sky = at(rect.min + egui::vec2(4.0, 4.0));
    // [0.3, 0.4, 0.6] in sRGB.
    for (c, want) in [149u8, 170, 204].into_iter().enumerate() {
        assert!(sky[c].abs_diff(want) <= 3, "{sky:?}");
    }
}

#[test]
fn moving_a_light_slider_changes_the_image() {
    let dir = tempfile::tempdir().unwrap();
    let mut h = harness(Some(write_scene(dir.path(), SCENE)), ShaderSource::Embedded);
    settle(&mut h);
    let before = image_of(&mut h);
    h.get_all_by_label("x").next().expect("the light's x slider").set_value_accesskit(3.0);
    h.step();
    settle(&mut h);
    assert_eq!(h.state().scene().unwrap().lights[0].kind, glint_scene::LightKind::Point { position: Vec3::new(3.0, 5.0, 4.0) });
    let after = image_of(&mut h);
    let diff = mean_difference(&before, &after);
    assert!(diff > 2.0, "the light moved from left to right, the image hardly changed: {diff}");
}

#[test]
fn clicking_a_sphere_selects_it_and_its_material_is_editable() {
    let dir = tempfile::tempdir().unwrap();
    let mut h = harness(Some(write_scene(dir.path(), SCENE)), ShaderSource::Embedded);
    settle(&mut h);
    let pos = screen_pos(h.state(), RED_SPHERE);
    click(&mut h, pos);
    assert_eq!(h.state().selected_object(), Some(1));
    h.get_by_label_contains("Object 2: sphere");
    h.get_by_label_contains("material “red”");
    settle(&mut h);

    let before = image_of(&mut h);
    h.get_all_by_label("k_d diffuse").next().unwrap().set_value_accesskit(0.1);
    h.step();
    settle(&mut h);
    let red = h.state().scene().unwrap().materials.iter().find(|m| m.name == "red").unwrap();
    assert_eq!(red.diffuse, 0.1);
    assert!(mean_difference(&before, &image_of(&mut h)) > 0.5, "a darker sphere changes the image");

    // The sky holds nothing to select.
    let sky = h.state().image_rect().unwrap().min + egui::vec2(5.0, 5.0);
    click(&mut h, sky);
    assert_eq!(h.state().selected_object(), None);
}

/// The kernels first carry only the scene's own terms (its light does not
/// fade); an edit beyond them switches to the kernels with every term.
#[test]
fn a_light_made_to_fade_fades() {
    let dir = tempfile::tempdir().unwrap();
    let mut h = harness(Some(write_scene(dir.path(), SCENE)), ShaderSource::Embedded);
    settle(&mut h);
    let before = image_of(&mut h);
    h.get_by_label("attenuation").click();
    h.run_steps(2);
    h.get_by_label("1/d²").click();
    h.step();
    settle(&mut h);
    assert!(h.state().errors().is_empty(), "{:?}", h.state().errors());
    assert_eq!(h.state().scene().unwrap().lights[0].attenuation, glint_scene::Attenuation::InverseSquare);
    let diff = mean_difference(&before, &image_of(&mut h));
    assert!(diff > 2.0, "a light 6 units away at 1/d² is much dimmer, the image hardly changed: {diff}");
}

/// The canvas's kernels are compiled for the view it opens in; any other view
/// gets its own, and the first view's image comes back as it was.
#[test]
fn another_view_renders_and_the_shaded_view_comes_back() {
    let dir = tempfile::tempdir().unwrap();
    let mut h = harness(Some(write_scene(dir.path(), SCENE)), ShaderSource::Embedded);
    settle(&mut h);
    let shaded = image_of(&mut h);
    for (view, changed) in [("normals", true), ("shaded", false)] {
        h.get_by_label("view").click();
        h.run_steps(2);
        h.get_by_label(view).click();
        h.step();
        settle(&mut h);
        assert!(h.state().errors().is_empty(), "{:?}", h.state().errors());
        let diff = mean_difference(&shaded, &image_of(&mut h));
        assert_eq!(diff > 10.0, changed, "the {view} view against the first shaded image: {diff}");
        assert!(changed || diff < 0.5, "the shaded view again: {diff}");
    }
}

#[test]
fn the_camera_orbits_flies_and_frames_the_scene() {
    let dir = tempfile::tempdir().unwrap();
    let mut h = harness(Some(write_scene(dir.path(), SCENE)), ShaderSource::Embedded);
    settle(&mut h);
    let start = h.state().scene().unwrap().camera;
    let before = image_of(&mut h);

    // Dragging the image orbits about the look-at point.
    let centre = h.state().image_rect().unwrap().center();
    h.drag_at(centre);
    h.step();
    h.hover_at(centre + egui::vec2(80.0, 0.0));
    h.step();
    h.drop_at(centre + egui::vec2(80.0, 0.0));
    h.step();
    let orbited = h.state().scene().unwrap().camera;
    assert_eq!(orbited.look_at, start.look_at);
    assert!((orbited.eye.distance(orbited.look_at) - start.eye.distance(start.look_at)).abs() < 1e-3);
    assert!(orbited.eye.x < start.eye.x - 1.0, "dragging right turns the scene right: {}", orbited.eye);
    settle(&mut h);
    let orbited_image = image_of(&mut h);
    assert!(mean_difference(&before, &orbited_image) > 2.0);

    // W flies forwards.
    h.key_down(egui::Key::W);
    h.run_steps(5);
    h.key_up(egui::Key::W);
    h.step();
    let flown = h.state().scene().unwrap().camera;
    let forward = (orbited.look_at - orbited.eye).normalize();
    assert!((flown.eye - orbited.eye).dot(forward) > 0.0, "{} → {}", orbited.eye, flown.eye);
    settle(&mut h);
    assert!(mean_difference(&orbited_image, &image_of(&mut h)) > 1.0, "the image follows the flight");

    // Reset brings back the file's camera; orthographic keeps it valid.
    press(&mut h, "Reset");
    assert_eq!(h.state().scene().unwrap().camera, start);
    h.get_by_label("orthographic").click();
    h.step();
    press(&mut h, "Frame all");
    let framed = h.state().scene().unwrap().camera;
    assert!(matches!(framed.projection, glint_scene::Projection::Orthographic { .. }));
    assert!(framed.basis().is_some());
    settle(&mut h);
}

/// A file dropped on the window.
#[derive(Debug)]
struct Dropped(PathBuf);

impl egui::DroppedFile for Dropped {
    fn path(&self) -> &Path {
        &self.0
    }

    fn bytes(&self) -> Result<Vec<u8>, String> {
        std::fs::read(&self.0).map_err(|e| e.to_string())
    }
}

#[test]
fn a_dropped_file_opens_and_an_edited_file_reloads() {
    let dir = tempfile::tempdir().unwrap();
    let path = write_scene(dir.path(), SCENE);
    let mut h = harness(None, ShaderSource::Embedded);
    h.step();
    h.get_by_label_contains("Drop a scene file");
    h.input_mut().dropped_files.push(Arc::new(Dropped(path.clone())));
    h.step();
    settle(&mut h);
    assert_eq!(h.state().scene().unwrap().primitive_count(), 3);

    // An edit on disk is picked up, keeping the view.
    std::thread::sleep(Duration::from_millis(20));
    std::fs::write(&path, SCENE.replace("radius = 0.6\n", "radius = 0.6\n\n[[object]]\ntype = \"sphere\"\ncenter = [0, 2, -2]\nradius = 0.3\n")).unwrap();
    wait_for(&mut h, "the edited file to load", |app| app.scene().is_some_and(|s| s.primitive_count() == 4));

    // A broken file shows its error on one line and keeps the last good scene.
    std::fs::write(&path, SCENE.replace("radius = 0.8", "radius = -1")).unwrap();
    wait_for(&mut h, "the error", |app| !app.errors().is_empty());
    let error = &h.state().errors()[0];
    assert!(error.contains("scene.toml:") && error.contains("radius") && !error.contains('\n'), "{error}");
    assert_eq!(h.state().scene().unwrap().primitive_count(), 4);
    settle(&mut h);
}

/// A Rayshade file opens by its extension, as an NFF does.
#[test]
fn a_dropped_rayshade_file_opens() {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("tetra_s2.ray");
    let db = glint_scene::spd::database("tetra").unwrap();
    std::fs::write(&path, db.generate_as(Some(2), glint_scene::spd::Format::Rayshade).unwrap()).unwrap();
    let mut h = harness(None, ShaderSource::Embedded);
    h.step();
    h.input_mut().dropped_files.push(Arc::new(Dropped(path)));
    h.step();
    settle(&mut h);
    assert_eq!(h.state().scene().unwrap().primitive_count(), 16, "tetra size 2: 4² triangles");
    assert!(h.state().errors().is_empty(), "{:?}", h.state().errors());
}

#[test]
fn a_shader_error_is_shown_and_the_last_good_pipeline_keeps_running() {
    let shaders = tempfile::tempdir().unwrap();
    for name in SOURCES {
        let to = shaders.path().join(name);
        std::fs::create_dir_all(to.parent().unwrap()).unwrap();
        std::fs::copy(ShaderSource::source_dir().join(name), to).unwrap();
    }
    let dir = tempfile::tempdir().unwrap();
    let mut h = harness(Some(write_scene(dir.path(), SCENE)), ShaderSource::Dir(shaders.path().into()));
    settle(&mut h);
    let good = image_of(&mut h);

    let shade = shaders.path().join("lib/shade.wgsl");
    let source = std::fs::read_to_string(&shade).unwrap();
    std::fs::write(&shade, format!("{source}\nfn broken( {{\n")).unwrap();
    wait_for(&mut h, "the shader error", |app| !app.errors().is_empty());
    let error = h.state().errors()[0].clone();
    assert!(error.contains("shaders/lib/shade.wgsl:"), "{error}");

    // Still rendering with the old kernels: a change converges again.
    h.get_all_by_label("x").next().unwrap().set_value_accesskit(2.0);
    h.step();
    settle(&mut h);
    assert!(mean_difference(&good, &image_of(&mut h)) > 1.0);

    // Fixing the file brings new kernels and clears the error.
    std::fs::write(&shade, &source).unwrap();
    wait_for(&mut h, "the fixed shader", |app| app.errors().is_empty());
    settle(&mut h);
}

#[test]
fn saves_the_image_and_the_scene() {
    let dir = tempfile::tempdir().unwrap();
    let mut h = harness(Some(write_scene(dir.path(), SCENE)), ShaderSource::Embedded);
    settle(&mut h);
    h.get_all_by_label("x").next().unwrap().set_value_accesskit(1.5);
    h.step();
    settle(&mut h);
    press(&mut h, "Save image");
    press(&mut h, "Save scene as");
    h.get_by_label_contains("scene-view.toml");

    let png = image::open(dir.path().join("scene-view.png")).unwrap();
    assert_eq!((png.width(), png.height()), h.state().render_size().unwrap());
    let saved = glint_scene::load(&dir.path().join("scene-view.toml")).unwrap();
    let scene = h.state().scene().unwrap();
    assert_eq!(saved.camera, scene.camera);
    assert_eq!(saved.lights, scene.lights);
    assert_eq!(saved.materials, scene.materials);
    assert_eq!(saved.objects, scene.objects);
}

/// The whole window, compared with tests/snapshots/viewer.png by FLIP.
#[test]
fn the_window_matches_its_snapshot() {
    let dir = tempfile::tempdir().unwrap();
    let mut h = harness(Some(write_scene(dir.path(), SCENE)), ShaderSource::Embedded);
    settle(&mut h);
    let pos = screen_pos(h.state(), RED_SPHERE);
    click(&mut h, pos);
    settle(&mut h);
    // Timings and the adapter's name vary, and so does the temporary path.
    let masked: Vec<egui::Rect> = [h.get_by_label_contains("primitives"), h.get_by_label("file")]
        .into_iter()
        .chain(h.get_all_by_label_contains("scene.toml"))
        .map(|n| n.rect().expand(2.0))
        .collect();
    for rect in masked {
        h.mask(rect);
    }
    let now = h.render().unwrap();
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/snapshots/viewer.png");
    if std::env::var_os("GLINT_BLESS").is_some() {
        now.save(&path).unwrap();
        return;
    }
    let want = image::open(&path)
        .unwrap_or_else(|e| panic!("{}: {e} (run with GLINT_BLESS=1 to write it)", path.display()))
        .into_rgb8();
    let now = image::DynamicImage::ImageRgba8(now).into_rgb8();
    assert_eq!(now.dimensions(), want.dimensions(), "window size");
    let flip = |img: &image::RgbImage| nv_flip::FlipImageRgb8::with_data(img.width(), img.height(), img);
    let error = nv_flip::flip(flip(&want), flip(&now), nv_flip::DEFAULT_PIXELS_PER_DEGREE);
    let mean = nv_flip::FlipPool::from_image(&error).mean();
    if mean > 0.003 {
        let out = std::env::temp_dir().join("glint-viewer-snapshot-now.png");
        now.save(&out).unwrap();
        panic!("the window differs from its snapshot: mean FLIP {mean:.4}; now: {}", out.display());
    }
}
