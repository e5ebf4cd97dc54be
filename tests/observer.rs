//! The observer's picture on a real probe: the overlay that `glint probe
//! --observer` and the viewer's observer mode draw starts the eye ray at the
//! eye, through the probed pixel's centre on the view window, and ends every
//! segment where the probe kernel found its ray's hit, for a perspective and
//! an orthographic camera.

mod support;

use glam::{DVec3, Vec3};
use glint_encoding::gpu_types::{NO_RAY, RAY_EYE, RAY_REFRACT, RAY_SHADOW};
use glint_gpu::probe::RayTree;
use glint_observer::{object_bounds, Ink, Observer, Overlay, OverlayOptions, ProbedPixel, RayId};
use glint_scene::camera_frame::CameraFrame;
use glint_scene::{Camera, Projection, Scene, MAX_DEPTH_LIMIT};

/// A glass ball in front of a red one over a floor, the light up and left.
const GLASS: &str = r#"
[image]
width = 32
height = 20

[camera]
eye = [0, 1, 5]
look_at = [0, 0.3, 0]
fov = 40

[[light]]
type = "point"
position = [-3, 5, 4]

[material.glass]
color = [0.05, 0.05, 0.05]
kd = 0.05
reflect = 0.1
transmit = 0.85
ior = 1.5

[material.red]
color = [0.9, 0.2, 0.1]

[[object]]
type = "sphere"
center = [0, 0.4, 1]
radius = 0.6
material = "glass"

[[object]]
type = "sphere"
center = [0.3, 0.4, -2]
radius = 0.7
material = "red"

[[object]]
type = "polygon"
vertices = [[-5, -0.2, -5], [-5, -0.2, 5], [5, -0.2, 5], [5, -0.2, -5]]
"#;

/// Probed under the device's profile and the plain profile alike.
fn probe(scene: &Scene, x: u32, y: u32) -> RayTree {
    support::Probing::new(scene).probe(x, y)
}

fn overlay_of(scene: &Scene, pixel: (u32, u32), tree: &RayTree) -> (CameraFrame, Overlay) {
    let frame = CameraFrame::new(&scene.camera, scene.width, scene.height).unwrap();
    let options = OverlayOptions { max_depth: MAX_DEPTH_LIMIT, grid: true };
    let overlay = Overlay::new(scene, &frame, object_bounds(scene), &[ProbedPixel { pixel, rays: &tree.rays }], options);
    (frame, overlay)
}

fn at(v: [f32; 3]) -> DVec3 {
    Vec3::from(v).as_dvec3()
}

#[track_caller]
fn assert_on_line(p: DVec3, a: DVec3, b: DVec3, what: &str) {
    let along = (b - a).normalize();
    let off = (p - a) - (p - a).dot(along) * along;
    assert!(off.length() < 1e-4, "{what}: {p} is {} off the line {a} to {b}", off.length());
}

/// Every ray is drawn once, from its origin; a ray that hit something ends at
/// the probe's hit point, with a dot and a normal there.
#[track_caller]
fn assert_segments_end_at_the_hits(tree: &RayTree, overlay: &Overlay) {
    for (id, ray) in tree.rays.iter().enumerate() {
        let drawn: Vec<_> = overlay.segments.iter().filter(|s| s.ray == Some(RayId { tree: 0, ray: id })).collect();
        assert_eq!(drawn.len(), 1, "ray #{id}");
        let segment = drawn[0];
        assert_eq!(segment.a, at(ray.origin), "ray #{id} starts at its origin");
        assert!((segment.b - segment.a).normalize().dot(at(ray.dir)) > 1.0 - 1e-6, "ray #{id} goes its way");
        if ray.kind != RAY_SHADOW && ray.object != NO_RAY {
            assert_eq!(segment.b, at(ray.point), "ray #{id} ends at its hit");
            assert!(overlay.dots.iter().any(|d| d.ink == Ink::Hit && d.at == segment.b), "a dot at #{id}'s hit");
            assert!(overlay.segments.iter().any(|s| s.ink == Ink::Normal && s.a == segment.b), "a normal at #{id}'s hit");
        }
    }
}

#[test]
fn the_eye_ray_leaves_the_eye_through_the_pixel_centre_and_the_glass_tree_ends_at_its_hits() {
    let scene = support::parse(GLASS);
    // The glass ball's middle: the ray refracts in and out again.
    let pixel = (16, 10);
    let tree = probe(&scene, pixel.0, pixel.1);
    assert!(tree.rays.iter().filter(|r| r.kind == RAY_REFRACT).count() >= 2, "into the glass and out: {:?}", tree.rays.len());
    let (frame, overlay) = overlay_of(&scene, pixel, &tree);

    let eye = overlay.segments.iter().find(|s| s.ray == Some(RayId { tree: 0, ray: 0 })).unwrap();
    assert_eq!((tree.rays[0].kind, eye.ink), (RAY_EYE, Ink::EyeRay));
    assert!((eye.a - frame.e).length() < 1e-6, "the eye ray leaves e");
    assert_on_line(frame.pixel_centre(pixel.0, pixel.1), eye.a, eye.b, "the pixel's centre on the window");
    let centre = frame.pixel_centre(pixel.0, pixel.1);
    assert!(((centre - frame.e).dot(-frame.w) - frame.d).abs() < 1e-9, "the window is at distance d");
    assert_segments_end_at_the_hits(&tree, &overlay);
    for ray in tree.rays.iter().filter(|r| r.kind == RAY_SHADOW) {
        let parent = &tree.rays[ray.parent as usize];
        assert!((at(ray.origin) - at(parent.point)).length() < 1e-3, "a shadow ray leaves its parent's hit");
    }

    // Seen from the side, up and to the right: the window's corners land
    // where the observer's own camera puts them, inside its picture.
    let observer = Observer {
        camera: Camera { eye: Vec3::new(6.0, 3.0, 6.0), look_at: Vec3::new(0.0, 0.5, 2.0), up: Vec3::Y, projection: Projection::Perspective { fov_y_degrees: 45.0 } },
        width: 640,
        height: 480,
    };
    for corner in frame.corners() {
        let seen = observer.project(corner).unwrap();
        let (x, y) = observer.camera.project(640, 480, corner).unwrap();
        assert!((seen.x - x).abs() < 1e-9 && (seen.y - y).abs() < 1e-9);
        assert!((0.0..640.0).contains(&x) && (0.0..480.0).contains(&y), "corner {corner} at ({x}, {y})");
    }
    let window: Vec<_> = overlay.segments.iter().filter(|s| s.ink == Ink::Window).map(|s| s.a).collect();
    assert_eq!(window, frame.corners().to_vec());
}

#[test]
fn an_orthographic_cameras_eye_ray_starts_on_its_window_and_runs_along_minus_w() {
    let mut scene = support::parse(GLASS);
    scene.camera.projection = Projection::Orthographic { height: 3.0 };
    let pixel = (20, 12);
    let tree = probe(&scene, pixel.0, pixel.1);
    let (frame, overlay) = overlay_of(&scene, pixel, &tree);
    let eye = overlay.segments.iter().find(|s| s.ray == Some(RayId { tree: 0, ray: 0 })).unwrap();
    assert!((eye.a - frame.pixel_centre(pixel.0, pixel.1)).length() < 1e-5, "{} is not the pixel's centre", eye.a);
    assert!((eye.b - eye.a).normalize().dot(-frame.w) > 1.0 - 1e-6, "parallel to −w");
    assert_segments_end_at_the_hits(&tree, &overlay);
}
