//! The viewer's observer mode driven headless by egui_kittest on the GPU: the
//! pinned pixel's tree and camera freeze, the camera orbits away, the overlay
//! draws the frozen frame and tree from there (the hovered ray highlighted),
//! a row of pixels is followed, and leaving gives the camera back. No adapter
//! is a failure, never a skip.

mod support;

use egui::{Key, Modifiers, Pos2};
use egui_kittest::kittest::Queryable;
use egui_kittest::Harness;
use glam::{DVec2, DVec3};
use glint_gpu::shaders::ShaderSource;
use glint_observer::{clip_to_box, Ink, RayId};
use glint_scene::camera_frame::CameraFrame;
use glint_viewer::ViewerApp;
use support::{click_with, harness, screen_pos, settle, wait_for, write_scene, RED_SPHERE, SCENE};

fn orbit(h: &mut Harness<'_, ViewerApp>, by: egui::Vec2) {
    let centre = h.state().image_rect().unwrap().center();
    h.drag_at(centre);
    h.step();
    h.hover_at(centre + by);
    h.step();
    h.drop_at(centre + by);
    h.step();
}

/// Where the overlay's point `p` (in the observer's pixels) is on the window.
fn on_window(app: &ViewerApp, p: DVec2) -> Pos2 {
    let (rect, (w, h)) = (app.image_rect().unwrap(), app.render_size().unwrap());
    rect.min + egui::vec2(p.x as f32 / w as f32, p.y as f32 / h as f32) * rect.size()
}

fn enter(h: &mut Harness<'_, ViewerApp>) {
    h.key_press(Key::O);
    wait_for(h, "observer mode", |app| app.observed().is_some());
    h.step();
}

#[test]
fn observer_mode_freezes_the_tree_and_its_camera_and_draws_them_from_the_moved_camera() {
    let dir = tempfile::tempdir().unwrap();
    let mirror = SCENE.replace("shininess = 40\n", "shininess = 40\nreflect = 0.5\n");
    let mut h = harness(Some(write_scene(dir.path(), &mirror)), ShaderSource::Embedded);
    settle(&mut h);
    let sphere = screen_pos(h.state(), RED_SPHERE) + egui::vec2(-40.0, -40.0);
    click_with(&mut h, sphere, Modifiers::COMMAND);
    wait_for(&mut h, "the ray tree", |app| app.inspected_tree().is_some());
    let camera = h.state().scene().unwrap().camera;
    let pixel = h.state().inspected_pixel().unwrap();
    let tree = h.state().inspected_tree().unwrap().clone();

    enter(&mut h);
    orbit(&mut h, egui::vec2(160.0, 40.0));
    settle(&mut h);
    let (frozen, pixels) = h.state().observed().unwrap();
    assert_eq!((frozen, pixels), (camera, vec![pixel]), "the camera that traced the tree, and its pixel");
    assert_ne!(h.state().scene().unwrap().camera, camera, "the view's camera moved away");
    assert_eq!(h.state().inspected_tree(), Some(&tree), "the tree is frozen, not probed again from the observer");

    // Drawn from the observer: the frozen frame, its window and the eye ray
    // from the frozen eye through the pixel's centre on it.
    let (observer, overlay) = h.state().overlay().unwrap();
    assert_eq!(observer.camera, h.state().scene().unwrap().camera);
    let (w, ht) = h.state().render_size().unwrap();
    let frame = CameraFrame::new(&camera, w, ht).unwrap();
    let window: Vec<DVec3> = overlay.segments.iter().filter(|s| s.ink == Ink::Window).map(|s| s.a).collect();
    assert_eq!(window, frame.corners().to_vec());
    let eye = overlay.segments.iter().find(|s| s.ray == Some(RayId { tree: 0, ray: 0 })).unwrap();
    assert!((eye.a - camera.eye.as_dvec3()).length() < 1e-5);
    let (along, centre) = ((eye.b - eye.a).normalize(), frame.pixel_centre(pixel.0, pixel.1) - eye.a);
    assert!((centre - centre.dot(along) * along).length() < 1e-4, "the eye ray passes the pixel's centre on the window");
    assert!(overlay.segments.iter().any(|s| s.ray.is_some() && s.ink == Ink::Reflect), "the reflected ray");

    // Hovering the eye ray's node highlights it where the observer sees it.
    h.get_by_label_contains("#0 eye ray").hover();
    h.step();
    h.step();
    assert_eq!(h.state().highlighted_ray(), Some(0));
    let (a, b) = observer.project_segment(eye.a, eye.b).unwrap();
    let size = DVec2::new(f64::from(w), f64::from(ht));
    let (a, b) = clip_to_box(a, b, DVec2::ZERO, size).expect("the eye ray is in sight");
    let middle = on_window(h.state(), (a + b) / 2.0);
    let drawn = *h.render().unwrap().get_pixel(middle.x as u32, middle.y as u32);
    assert!(drawn[0] > 200 && drawn[1] < 100 && drawn[2] > 200, "the highlighted eye ray is magenta at {middle:?}: {drawn:?}");

    // The depth slider leaves out the reflection.
    h.get_all_by_label("deepest rays drawn").next().expect("the depth slider").set_value_accesskit(1.0);
    h.step();
    h.step();
    let (_, shallow) = h.state().overlay().unwrap();
    assert!(shallow.segments.iter().all(|s| s.ink != Ink::Reflect));

    // Leaving gives the camera back, and the pixel stays pinned.
    h.key_press(Key::O);
    h.step();
    h.step();
    assert!(h.state().observed().is_none());
    assert_eq!(h.state().scene().unwrap().camera, camera);
    assert_eq!(h.state().inspected_pixel(), Some(pixel));
    settle(&mut h);
}

#[test]
fn a_row_follows_pixels_across_the_image_on_the_pinned_pixels_row() {
    let dir = tempfile::tempdir().unwrap();
    let mut h = harness(Some(write_scene(dir.path(), SCENE)), ShaderSource::Embedded);
    settle(&mut h);
    let sphere = screen_pos(h.state(), RED_SPHERE);
    click_with(&mut h, sphere, Modifiers::COMMAND);
    wait_for(&mut h, "the ray tree", |app| app.inspected_tree().is_some());
    h.step();
    let pixel = h.state().inspected_pixel().unwrap();
    h.get_by_label("its row").click();
    h.step();
    enter(&mut h);
    let (_, pixels) = h.state().observed().unwrap();
    assert_eq!(pixels[0], pixel);
    assert!(pixels.len() >= 9 && pixels.iter().all(|p| p.1 == pixel.1), "{pixels:?}");
    let (_, overlay) = h.state().overlay().unwrap();
    let eye_rays = overlay.segments.iter().filter(|s| s.ink == Ink::EyeRay).count();
    assert_eq!(eye_rays, pixels.len(), "an eye ray per pixel");
    let camera = h.state().observed().unwrap().0;
    orbit(&mut h, egui::vec2(-120.0, 0.0));
    // Inspect mode off ends observer mode too, with the camera given back.
    h.get_by_label("inspect mode (I)").click();
    h.step();
    h.step();
    assert!(h.state().observed().is_none());
    assert_eq!(h.state().scene().unwrap().camera, camera);
    settle(&mut h);
}
