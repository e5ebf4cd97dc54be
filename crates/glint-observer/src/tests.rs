use bytemuck::Zeroable;
use glam::{DVec2, DVec3, Vec3};

use super::*;
use glint_encoding::gpu_types::PROBE_SHADOW_TRACED;

/// A camera at the origin looking down −z with a 90° field of view: its 2 x 2
/// pixel window has corners (±1, ±1, −1).
fn camera() -> Camera {
    Camera { eye: Vec3::ZERO, look_at: Vec3::NEG_Z, up: Vec3::Y, projection: Projection::Perspective { fov_y_degrees: 90.0 } }
}

/// 4 units behind the camera, looking the same way: (x, y, −1) lands at
/// (50 + 10x, 50 − 10y) of its 100 x 100 image.
fn observer() -> Observer {
    Observer { camera: Camera { eye: Vec3::new(0.0, 0.0, 4.0), ..camera() }, width: 100, height: 100 }
}

fn scene() -> Scene {
    let text = "[image]\nwidth = 2\nheight = 2\n\n[camera]\neye = [0, 0, 0]\nlook_at = [0, 0, -1]\nfov = 90\n\n[[light]]\ntype = \"point\"\nposition = [0, 3, 0]\n\n[[object]]\ntype = \"sphere\"\ncenter = [2, 2, -5]\nradius = 1\n";
    glint_scene::toml_scene::parse(text, std::path::Path::new("observer.toml")).unwrap()
}

fn ray(kind: u32, parent: u32, depth: u32, origin: DVec3, dir: DVec3) -> ProbeRay {
    ProbeRay { kind, parent, depth, origin: origin.as_vec3().into(), dir: dir.normalize().as_vec3().into(), object: NO_RAY, ..ProbeRay::zeroed() }
}

fn hitting(mut r: ProbeRay, point: DVec3, normal: DVec3) -> ProbeRay {
    r.object = 0;
    r.point = point.as_vec3().into();
    r.shading = normal.as_vec3().into();
    r.t = (point - Vec3::from(r.origin).as_dvec3()).length() as f32;
    r
}

/// Pixel (1, 0)'s tree: the eye ray hits (2, 2, −4) (through the pixel's
/// centre (0.5, 0.5, −1)), a lit shadow ray to the light, a blocked one, and
/// a reflected ray that misses.
fn tree(frame: &CameraFrame) -> Vec<ProbeRay> {
    let centre = frame.pixel_centre(1, 0);
    let hit = centre * 4.0;
    let eye = hitting(ray(RAY_EYE, NO_RAY, 1, frame.e, centre - frame.e), hit, DVec3::Z);
    let light = DVec3::new(0.0, 3.0, 0.0);
    let mut lit = ray(RAY_SHADOW, 0, 0, hit, light - hit);
    (lit.flags, lit.distance) = (PROBE_SHADOW_TRACED, (light - hit).length() as f32);
    let mut blocked = ray(RAY_SHADOW, 0, 0, hit, DVec3::X);
    (blocked.flags, blocked.t) = (PROBE_SHADOW_TRACED | PROBE_BLOCKED, 0.5);
    let reflect = ray(RAY_REFLECT, 0, 2, hit, DVec3::Z);
    vec![eye, lit, blocked, reflect]
}

fn overlay(rays: &[ProbeRay], options: OverlayOptions) -> (CameraFrame, Overlay) {
    let frame = CameraFrame::new(&camera(), 2, 2).unwrap();
    let bounds = (Vec3::splat(-3.0), Vec3::splat(3.0));
    let overlay = Overlay::new(&scene(), &frame, bounds, &[ProbedPixel { pixel: (1, 0), rays }], options);
    (frame, overlay)
}

fn ray_segment(overlay: &Overlay, id: usize) -> Option<&Segment> {
    overlay.segments.iter().find(|s| s.ray == Some(RayId { tree: 0, ray: id }))
}

const ALL: OverlayOptions = OverlayOptions { max_depth: 5, grid: true };

#[track_caller]
fn assert_near(a: DVec3, b: DVec3) {
    assert!((a - b).length() < 1e-5, "{a} is not {b}");
}

#[test]
fn the_window_corners_project_where_the_observer_sees_them() {
    let frame = CameraFrame::new(&camera(), 2, 2).unwrap();
    let seen = frame.corners().map(|c| observer().project(c).unwrap());
    let expected = [(40.0, 40.0), (60.0, 40.0), (60.0, 60.0), (40.0, 60.0)].map(|(x, y)| DVec2::new(x, y));
    for (s, e) in seen.iter().zip(expected) {
        assert!(s.distance(e) < 1e-9, "{seen:?}");
    }
    assert!((observer().cell_size(&frame) - 10.0).abs() < 1e-9, "a pixel is 1 unit, 10 of the observer's pixels");
    let (_, overlay) = overlay(&[], ALL);
    let window: Vec<_> = overlay.segments.iter().filter(|s| s.ink == Ink::Window).map(|s| s.a).collect();
    assert_eq!(window, frame.corners().to_vec());
}

#[test]
fn the_frame_has_the_eye_unit_axes_and_a_grid_line_between_pixels() {
    let (frame, with_grid) = overlay(&[], ALL);
    assert!(with_grid.dots.contains(&Dot { at: frame.e, ink: Ink::Eye }));
    assert!(with_grid.dots.contains(&Dot { at: DVec3::new(0.0, 3.0, 0.0), ink: Ink::Light }));
    for (axis, ink) in [(DVec3::X, Ink::AxisU), (DVec3::Y, Ink::AxisV), (DVec3::Z, Ink::AxisW)] {
        assert!(with_grid.segments.iter().any(|s| s.ink == ink && s.a == frame.e && (s.b - axis).length() < 1e-12), "{ink:?}");
    }
    let grid: Vec<_> = with_grid.segments.iter().filter(|s| s.ink == Ink::Grid).collect();
    assert_eq!(grid.len(), 2, "one line between the 2 columns, one between the 2 rows");
    assert_near(grid[0].a, DVec3::new(0.0, 1.0, -1.0));
    assert_near(grid[1].b, DVec3::new(1.0, 0.0, -1.0));
    let (_, without) = overlay(&[], OverlayOptions { grid: false, ..ALL });
    assert!(without.segments.iter().all(|s| s.ink != Ink::Grid));
    let pixel: Vec<_> = with_grid.segments.iter().filter(|s| s.ink == Ink::Pixel).map(|s| s.a).collect();
    assert_eq!(pixel, [(1.0, 0.0), (2.0, 0.0), (2.0, 1.0), (1.0, 1.0)].map(|(x, y)| frame.window_point(x, y)).to_vec());
}

#[test]
fn the_eye_ray_passes_through_the_pixel_centre_and_every_segment_ends_where_its_ray_does() {
    let frame = CameraFrame::new(&camera(), 2, 2).unwrap();
    let rays = tree(&frame);
    let (_, overlay) = overlay(&rays, ALL);
    let eye = ray_segment(&overlay, 0).unwrap();
    assert_eq!(eye.ink, Ink::EyeRay);
    let along = (eye.b - eye.a).normalize();
    let centre = frame.pixel_centre(1, 0) - eye.a;
    assert!((centre - centre.dot(along) * along).length() < 1e-6, "the eye ray meets the pixel's centre on the window");
    let hit = DVec3::new(2.0, 2.0, -4.0);
    assert_near(eye.b, hit);
    let lit = ray_segment(&overlay, 1).unwrap();
    assert_eq!((lit.ink, lit.a), (Ink::ShadowLit, eye.b));
    assert_near(lit.b, DVec3::new(0.0, 3.0, 0.0));
    let blocked = ray_segment(&overlay, 2).unwrap();
    assert_eq!(blocked.ink, Ink::ShadowBlocked);
    assert_near(blocked.b, hit + DVec3::X * 0.5);
    let reflect = ray_segment(&overlay, 3).unwrap();
    assert_eq!(reflect.ink, Ink::Reflect);
    // Where it leaves the bounds, grown by a tenth of their half-diagonal 3√3.
    assert_near(reflect.b, DVec3::new(2.0, 2.0, 3.0 + 0.3 * 3f64.sqrt()));
    assert!(overlay.dots.contains(&Dot { at: eye.b, ink: Ink::Hit }));
    let normal = overlay.segments.iter().find(|s| s.ink == Ink::Normal).unwrap();
    assert_eq!(normal.a, eye.b);
    assert!((normal.b - normal.a).normalize().dot(DVec3::Z) > 1.0 - 1e-9, "along the shading normal");
}

#[test]
fn the_depth_limit_leaves_out_deeper_rays_and_their_shadow_rays() {
    let frame = CameraFrame::new(&camera(), 2, 2).unwrap();
    let mut rays = tree(&frame);
    let mut deep_shadow = ray(RAY_SHADOW, 3, 0, DVec3::ZERO, DVec3::Y);
    deep_shadow.flags = PROBE_SHADOW_TRACED;
    rays.push(deep_shadow);
    let (_, overlay) = overlay(&rays, OverlayOptions { max_depth: 1, ..ALL });
    let drawn: Vec<usize> = overlay.segments.iter().filter_map(|s| s.ray).map(|id| id.ray).collect();
    assert_eq!(drawn, [0, 1, 2]);
}

#[test]
fn a_segment_passing_behind_the_observer_is_cut_at_its_near_plane() {
    let observer = observer();
    let (front, behind) = (DVec3::new(1.0, 1.0, -1.0), DVec3::new(1.0, 1.0, 10.0));
    let (a, b) = observer.project_segment(front, behind).unwrap();
    assert_eq!(a, observer.project(front).unwrap());
    // The cut end is far out along the line's own direction on screen, not
    // mirrored through the eye.
    let towards = observer.project(DVec3::new(1.0, 1.0, 3.0)).unwrap();
    assert!((b - a).normalize().dot((towards - a).normalize()) > 1.0 - 1e-9, "{a} {b} {towards}");
    assert!(b.is_finite() && b.distance(a) > towards.distance(a));
    assert_eq!(observer.project_segment(behind, behind + DVec3::X), None);
    assert_eq!(observer.project(behind), None);
}

#[test]
fn an_orthographic_camera_draws_parallel_eye_rays_from_its_window() {
    let ortho = Camera { projection: Projection::Orthographic { height: 2.0 }, ..camera() };
    let frame = CameraFrame::new(&ortho, 2, 2).unwrap();
    assert_eq!(frame.d, 0.0);
    assert_near(frame.ray_origin(1, 0), DVec3::new(0.5, 0.5, 0.0));
    assert_near(frame.ray_origin(0, 1), DVec3::new(-0.5, -0.5, 0.0));
}
