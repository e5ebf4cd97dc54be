//! The viewer's inspect mode driven headless by egui_kittest on the GPU: a
//! Ctrl-click pins a pixel, its ray tree shows in the side panel and is drawn
//! over the image, hovering a node highlights its ray, and the tree follows a
//! moved light. No adapter is a failure, never a skip.

mod support;

use egui::{Modifiers, Pos2};
use egui_kittest::kittest::Queryable;
use egui_kittest::Harness;
use glam::Vec3;
use glint_encoding::gpu_types::{NO_RAY, RAY_EYE, RAY_REFLECT, RAY_SHADOW};
use glint_gpu::shaders::ShaderSource;
use glint_viewer::ViewerApp;
use image::Rgba;
use support::{click_with, harness, screen_pos, settle, wait_for, write_scene, RED_SPHERE, SCENE};

/// A point of the tree's reflected ray far enough from the pinned pixel's
/// marker to be the ray's own line, and where it is drawn.
fn reflected_ray_point(app: &ViewerApp) -> Pos2 {
    let tree = app.inspected_tree().unwrap();
    let ray = tree.rays.iter().find(|r| r.kind == RAY_REFLECT).expect("a reflected ray");
    let start = screen_pos(app, Vec3::from(ray.origin));
    (1..200)
        .map(|i| screen_pos(app, Vec3::from(ray.origin) + Vec3::from(ray.dir) * (i as f32 * 0.02)))
        .find(|p| p.distance(start) > 25.0)
        .expect("the reflected ray leaves the marker")
}

fn window_pixel(h: &mut Harness<'_, ViewerApp>, p: Pos2) -> Rgba<u8> {
    *h.render().unwrap().get_pixel(p.x as u32, p.y as u32)
}

#[test]
fn a_ctrl_click_shows_the_pixels_ray_tree_and_draws_it_over_the_image() {
    let dir = tempfile::tempdir().unwrap();
    let mirror = SCENE.replace("shininess = 40\n", "shininess = 40\nreflect = 0.5\n");
    let mut h = harness(Some(write_scene(dir.path(), &mirror)), ShaderSource::Embedded);
    settle(&mut h);
    // Up and left of the sphere's centre, where the reflection turns away from the eye.
    let sphere = screen_pos(h.state(), RED_SPHERE) + egui::vec2(-40.0, -40.0);
    let before = h.render().unwrap();

    click_with(&mut h, sphere, Modifiers::COMMAND);
    wait_for(&mut h, "the ray tree", |app| app.inspected_tree().is_some());
    h.step();
    assert_eq!(h.state().selected_object(), None, "a Ctrl-click inspects, it does not select");
    let tree = h.state().inspected_tree().unwrap().clone();
    let eye = &tree.rays[0];
    assert_eq!((eye.kind, eye.parent, eye.object), (RAY_EYE, NO_RAY, 1), "the eye ray hits the red sphere");
    assert!(tree.rays.iter().any(|r| r.kind == RAY_SHADOW && r.parent == 0), "a shadow ray to the light");

    // The tree in the side panel, in the words of `glint probe`.
    h.get_by_label_contains("#0 eye ray hits object 2 (sphere, material \"red\")");
    h.get_by_label_contains("shadow ray to light 1: lit");
    h.get_by_label_contains("#2 reflect ray");
    h.get_by_label_contains("hits object 2 (sphere, material \"red\") at t = ");

    // The reflected ray is drawn in its colour over what was there.
    let on_ray = reflected_ray_point(h.state());
    let under = *before.get_pixel(on_ray.x as u32, on_ray.y as u32);
    let drawn = window_pixel(&mut h, on_ray);
    assert!(drawn[2] > 200 && drawn[0] < 160 && drawn != under, "the reflected ray's blue at {on_ray:?}: {drawn:?}, under it {under:?}");

    // Hovering its node highlights it.
    h.get_by_label_contains("#2 reflect ray").hover();
    h.step();
    h.step();
    assert_eq!(h.state().highlighted_ray(), Some(2));
    let highlighted = window_pixel(&mut h, on_ray);
    assert!(highlighted[0] > 200 && highlighted[1] < 100, "the highlighted ray is magenta: {highlighted:?}");

    // The pinned pixel's tree follows the light.
    let pixel = h.state().inspected_pixel();
    h.get_all_by_label("x").next().expect("the light's x slider").set_value_accesskit(3.0);
    h.step();
    let light = Vec3::new(3.0, 5.0, 4.0);
    wait_for(&mut h, "the tree to follow the light", |app| {
        app.inspected_tree().unwrap().rays.iter().any(|r| {
            r.kind == RAY_SHADOW && r.parent == 0 && (light - Vec3::from(r.origin)).normalize().dot(Vec3::from(r.dir)) > 0.9999
        })
    });
    assert_eq!(h.state().inspected_pixel(), pixel, "the pixel stays pinned");

    // Inspect mode off lets go of the pixel and clears the overlay.
    h.get_by_label("inspect mode (I)").click();
    h.step();
    h.step();
    assert!(h.state().inspected_tree().is_none());
    settle(&mut h);
}
