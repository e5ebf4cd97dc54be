//! No ray slips between primitives that share an edge or a vertex: cameras
//! inside closed meshes at random positions and orientations see no background
//! in the depth view, at 512 × 512, and the Cornell box's seams hold.

mod support;

use glam::Vec3;
use glint_encoding::gpu_types::{View, MISS};
use glint_gpu::{Acceleration, RenderOptions};
use glint_scene::{Camera, Material, Object, Projection, RenderSettings, Scene, Shape};

/// A scene of `shapes`, one object each, seen by `camera` at 512 × 512.
fn scene(shapes: Vec<Shape>, camera: Camera) -> Scene {
    Scene {
        width: 512,
        height: 512,
        background: Vec3::X,
        camera,
        ambient: Vec3::ONE,
        lights: Vec::new(),
        materials: vec![Material::default()],
        objects: shapes.into_iter().map(|shape| Object { material: 0, shapes: vec![shape] }).collect(),
        depth_cue: None,
        render: RenderSettings::default(),
        animation: None,
        warnings: Vec::new(),
    }
}

/// Pixels (x, y) whose primary ray found nothing.
fn misses(scene: &Scene) -> Vec<(u32, u32)> {
    let options = RenderOptions { view: View::Depth, ..RenderOptions::default() };
    let (depth, _) = support::render_options(scene, Acceleration::Bvh, options);
    let width = depth.width as usize;
    depth.linear.iter().enumerate().filter(|(_, p)| p[0] >= MISS).map(|(i, _)| ((i % width) as u32, (i / width) as u32)).collect()
}

/// A small deterministic generator (SplitMix64), so failures reproduce.
struct Rng(u64);

impl Rng {
    fn unit(&mut self) -> f32 {
        self.0 = self.0.wrapping_add(0x9E37_79B9_7F4A_7C15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
        ((z ^ (z >> 31)) >> 40) as f32 / (1u64 << 24) as f32
    }

    fn range(&mut self, lo: f32, hi: f32) -> f32 {
        lo + (hi - lo) * self.unit()
    }

    fn point_in(&mut self, lo: Vec3, hi: Vec3) -> Vec3 {
        Vec3::new(self.range(lo.x, hi.x), self.range(lo.y, hi.y), self.range(lo.z, hi.z))
    }

    fn direction(&mut self) -> Vec3 {
        loop {
            let v = self.point_in(Vec3::splat(-1.0), Vec3::ONE);
            if (0.01..1.0).contains(&v.length_squared()) {
                return v.normalize();
            }
        }
    }
}

/// Cameras inside the box [lo, hi]: first at its centre looking along each
/// axis, so that the diagonals of faces centred on the view fall on pixel
/// centres; then at random positions, directions, up vectors and fields of view.
fn cameras_inside(seed: u64, count: usize, lo: Vec3, hi: Vec3) -> Vec<Camera> {
    let mut rng = Rng(seed);
    let center = (lo + hi) / 2.0;
    let axes = [Vec3::X, Vec3::Y, Vec3::Z, -Vec3::X, -Vec3::Y, -Vec3::Z];
    let centred = axes.iter().map(|&dir| Camera {
        eye: center,
        look_at: center + dir,
        up: Vec3::new(dir.z.abs(), dir.x.abs(), dir.y.abs()),
        projection: Projection::Perspective { fov_y_degrees: 90.0 },
    });
    let random = (0..count).map(|_| {
        let eye = rng.point_in(lo, hi);
        let dir = rng.direction();
        let mut up = rng.direction();
        if up.cross(dir).length() < 0.1 {
            up = dir.any_orthonormal_vector();
        }
        Camera { eye, look_at: eye + dir, up, projection: Projection::Perspective { fov_y_degrees: rng.range(30.0, 120.0) } }
    });
    centred.chain(random).collect()
}

fn triangle(a: Vec3, b: Vec3, c: Vec3) -> Shape {
    Shape::Triangle { vertices: [a, b, c], normals: None }
}

/// Each quad (corners in order) as two triangles split along its v0–v2 diagonal.
fn triangulated(quads: &[[Vec3; 4]]) -> Vec<Shape> {
    quads.iter().flat_map(|q| [triangle(q[0], q[1], q[2]), triangle(q[0], q[2], q[3])]).collect()
}

/// The six faces of the box [lo, hi], wound outwards.
fn box_faces(lo: Vec3, hi: Vec3) -> Vec<[Vec3; 4]> {
    let corner = |x: bool, y: bool, z: bool| Vec3::new(if x { hi.x } else { lo.x }, if y { hi.y } else { lo.y }, if z { hi.z } else { lo.z });
    let (f, t) = (false, true);
    vec![
        [corner(f, f, f), corner(f, f, t), corner(f, t, t), corner(f, t, f)],
        [corner(t, f, f), corner(t, t, f), corner(t, t, t), corner(t, f, t)],
        [corner(f, f, f), corner(t, f, f), corner(t, f, t), corner(f, f, t)],
        [corner(f, t, f), corner(f, t, t), corner(t, t, t), corner(t, t, f)],
        [corner(f, f, f), corner(f, t, f), corner(t, t, f), corner(t, f, f)],
        [corner(f, f, t), corner(t, f, t), corner(t, t, t), corner(f, t, t)],
    ]
}

#[track_caller]
fn assert_no_leaks(shapes: &[Shape], cameras: &[Camera], what: &str) {
    for (i, camera) in cameras.iter().enumerate() {
        let holes = misses(&scene(shapes.to_vec(), *camera));
        assert!(holes.is_empty(), "{what}, camera {i} {camera:?}: {} rays leak, first at {:?}", holes.len(), &holes[..holes.len().min(5)]);
    }
}

#[test]
fn a_cube_of_twelve_triangles_holds_every_ray() {
    let (lo, hi) = (Vec3::splat(-1.0), Vec3::ONE);
    assert_no_leaks(&triangulated(&box_faces(lo, hi)), &cameras_inside(1, 24, lo * 0.95, hi * 0.95), "cube");
}

#[test]
fn a_closed_polygonal_box_holds_every_ray() {
    // Off-centre and not a cube, so no face is a power-of-two size.
    let (lo, hi) = (Vec3::new(-1.3, -0.7, 2.1), Vec3::new(2.9, 1.7, 3.3));
    let faces = box_faces(lo, hi).into_iter().map(|q| Shape::Polygon { vertices: q.to_vec() }).collect::<Vec<_>>();
    let inset = (hi - lo) * 0.02;
    assert_no_leaks(&faces, &cameras_inside(2, 24, lo + inset, hi - inset), "polygonal box");
}

#[test]
fn an_icosphere_holds_every_ray() {
    let center = Vec3::new(0.3, -0.2, 0.1);
    let shapes = glint_scene::icosphere::icosphere(center, 2.0, 3, 0.0);
    // Well inside: the sphere's flat faces come no closer than ~0.99 of the radius.
    let cameras = cameras_inside(3, 24, center - Vec3::splat(1.1), center + Vec3::splat(1.1));
    assert_no_leaks(&shapes, &cameras, "icosphere");
}

/// The Cornell box as measured at Cornell (millimetres): floor, ceiling, back
/// and side walls, and the two blocks, every quad as two triangles; with
/// `closed`, a front wall as well.
fn cornell_box(closed: bool) -> Vec<Shape> {
    let v = |x: f32, y: f32, z: f32| Vec3::new(x, y, z);
    let mut quads = vec![
        [v(552.8, 0.0, 0.0), v(0.0, 0.0, 0.0), v(0.0, 0.0, 559.2), v(549.6, 0.0, 559.2)],
        [v(556.0, 548.8, 0.0), v(556.0, 548.8, 559.2), v(0.0, 548.8, 559.2), v(0.0, 548.8, 0.0)],
        [v(549.6, 0.0, 559.2), v(0.0, 0.0, 559.2), v(0.0, 548.8, 559.2), v(556.0, 548.8, 559.2)],
        [v(0.0, 0.0, 559.2), v(0.0, 0.0, 0.0), v(0.0, 548.8, 0.0), v(0.0, 548.8, 559.2)],
        [v(552.8, 0.0, 0.0), v(549.6, 0.0, 559.2), v(556.0, 548.8, 559.2), v(556.0, 548.8, 0.0)],
        // Short block.
        [v(130.0, 165.0, 65.0), v(82.0, 165.0, 225.0), v(240.0, 165.0, 272.0), v(290.0, 165.0, 114.0)],
        [v(290.0, 0.0, 114.0), v(290.0, 165.0, 114.0), v(240.0, 165.0, 272.0), v(240.0, 0.0, 272.0)],
        [v(130.0, 0.0, 65.0), v(130.0, 165.0, 65.0), v(290.0, 165.0, 114.0), v(290.0, 0.0, 114.0)],
        [v(82.0, 0.0, 225.0), v(82.0, 165.0, 225.0), v(130.0, 165.0, 65.0), v(130.0, 0.0, 65.0)],
        [v(240.0, 0.0, 272.0), v(240.0, 165.0, 272.0), v(82.0, 165.0, 225.0), v(82.0, 0.0, 225.0)],
        // Tall block.
        [v(423.0, 330.0, 247.0), v(265.0, 330.0, 296.0), v(314.0, 330.0, 456.0), v(472.0, 330.0, 406.0)],
        [v(423.0, 0.0, 247.0), v(423.0, 330.0, 247.0), v(472.0, 330.0, 406.0), v(472.0, 0.0, 406.0)],
        [v(472.0, 0.0, 406.0), v(472.0, 330.0, 406.0), v(314.0, 330.0, 456.0), v(314.0, 0.0, 456.0)],
        [v(314.0, 0.0, 456.0), v(314.0, 330.0, 456.0), v(265.0, 330.0, 296.0), v(265.0, 0.0, 296.0)],
        [v(265.0, 0.0, 296.0), v(265.0, 330.0, 296.0), v(423.0, 330.0, 247.0), v(423.0, 0.0, 247.0)],
    ];
    if closed {
        quads.push([v(552.8, 0.0, 0.0), v(556.0, 548.8, 0.0), v(0.0, 548.8, 0.0), v(0.0, 0.0, 0.0)]);
    }
    triangulated(&quads)
}

#[test]
fn the_closed_cornell_room_holds_every_ray() {
    // Inside the room, above the blocks' tops so no camera starts in a block.
    let cameras = cameras_inside(4, 24, Vec3::new(20.0, 340.0, 20.0), Vec3::new(530.0, 530.0, 540.0));
    assert_no_leaks(&cornell_box(true), &cameras, "Cornell room");
}

/// The regression the seams first showed: the classic view through the open
/// front, where every pixel the f64 reference sees a wall in must show one.
/// Only the outline of the box may differ (a ray grazing the front edge).
#[test]
fn the_cornell_box_seams_leak_no_pixel_the_reference_fills() {
    let camera = Camera {
        eye: Vec3::new(278.0, 273.0, -800.0),
        look_at: Vec3::new(278.0, 273.0, 0.0),
        up: Vec3::Y,
        projection: Projection::Perspective { fov_y_degrees: 39.3 },
    };
    let scene = scene(cornell_box(false), camera);
    let reference = glint_reference::Tracer::new(&scene);
    let (w, h) = (scene.width, scene.height);
    let reference_hits = |x: i64, y: i64| {
        let ray = camera.ray(w, h, x as f64 + 0.5, y as f64 + 0.5).expect("a valid camera");
        reference.nearest_hit(ray.origin, ray.direction, 0.0, f64::INFINITY).is_some()
    };
    let interior = |x: u32, y: u32| {
        let (x, y) = (i64::from(x), i64::from(y));
        (-1..=1).all(|dy| (-1..=1).all(|dx| reference_hits(x + dx, y + dy)))
    };
    let missed = misses(&scene);
    let leaks: Vec<_> = missed.iter().copied().filter(|&(x, y)| interior(x, y)).collect();
    assert!(leaks.is_empty(), "{} rays pass between the Cornell box's triangles, first at {:?}", leaks.len(), &leaks[..leaks.len().min(5)]);
    // The box fills most of the view, so the test crosses every seam.
    assert!(missed.len() < 512 * 512 / 10, "{} misses: the box is out of view", missed.len());
}

/// One pixel whose ray runs from `eye` exactly towards `target` (a 1 × 1
/// image's only pixel centre is the view direction): whether it hits.
fn ray_hits(shapes: &[Shape], eye: Vec3, target: Vec3) -> bool {
    let up = (target - eye).any_orthonormal_vector();
    let camera = Camera { eye, look_at: target, up, projection: Projection::Perspective { fov_y_degrees: 10.0 } };
    let mut one_pixel = scene(shapes.to_vec(), camera);
    (one_pixel.width, one_pixel.height) = (1, 1);
    misses(&one_pixel).is_empty()
}

/// A fan of seven faces around a shared centre vertex, on a shallow cone so
/// no two faces are coplanar, as triangles or as three-sided polygons.
fn fan(as_polygons: bool) -> (Vec3, Vec<Vec3>, Vec<Shape>) {
    let centre = Vec3::new(0.1, -0.2, 0.7);
    let ring: Vec<Vec3> = (0..7)
        .map(|k| {
            let a = k as f32 * std::f32::consts::TAU / 7.0 + 0.3;
            Vec3::new(a.cos() * (1.0 + 0.1 * k as f32), a.sin(), 0.2 * (k % 3) as f32)
        })
        .collect();
    let shapes = (0..7)
        .map(|k| {
            let face = [centre, ring[k], ring[(k + 1) % 7]];
            if as_polygons { Shape::Polygon { vertices: face.to_vec() } } else { triangle(face[0], face[1], face[2]) }
        })
        .collect();
    (centre, ring, shapes)
}

#[test]
fn rays_aimed_at_shared_vertices_and_edges_of_a_fan_always_hit() {
    let mut rng = Rng(5);
    let mut failures = Vec::new();
    for as_polygons in [false, true] {
        let (centre, ring, shapes) = fan(as_polygons);
        // The centre vertex all faces share and points on the spokes two faces
        // share, rounded to f32 as a scene would hold them. (The ring is the
        // fan's outline, where a ray may rightly pass.)
        let mut targets = vec![centre];
        for spoke in &ring {
            targets.extend((0..6).map(|_| centre + rng.range(0.02, 0.98) * (*spoke - centre)));
        }
        let mut missed = Vec::new();
        for &target in &targets {
            for _ in 0..4 {
                // From in front of the fan at a random angle, seeing every face
                // from its front: then no spoke is on the fan's outline.
                let eye = loop {
                    let eye = target + Vec3::new(rng.range(-1.0, 1.0), rng.range(-1.0, 1.0), rng.range(0.5, 2.0)) * 3.0;
                    let front = |k: usize| (ring[k] - centre).cross(ring[(k + 1) % 7] - centre).dot(eye - centre) > 0.0;
                    if (0..7).all(front) {
                        break eye;
                    }
                };
                if !ray_hits(&shapes, eye, target) {
                    missed.push((eye, target));
                }
            }
        }
        let kind = if as_polygons { "polygons" } else { "triangles" };
        if !missed.is_empty() {
            failures.push(format!("{kind}: {} of {} rays missed, e.g. {:?}", missed.len(), targets.len() * 4, missed[0]));
        }
    }
    assert!(failures.is_empty(), "rays aimed at shared edges and vertices missed:\n{}", failures.join("\n"));
}

#[test]
fn a_concave_polygon_covers_the_same_pixels_as_its_triangulation() {
    // A five-pointed star in a tilted plane: one concave polygon, or ten
    // triangles fanned from its centre (the star is star-shaped about it).
    let centre = Vec3::new(0.2, 0.1, -0.3);
    let (e1, e2) = (Vec3::new(1.0, 0.2, 0.3).normalize(), Vec3::new(-0.1, 1.0, 0.4).normalize());
    let outline: Vec<Vec3> = (0..10)
        .map(|k| {
            let a = k as f32 * std::f32::consts::TAU / 10.0;
            let r = if k % 2 == 0 { 1.5 } else { 0.6 };
            centre + r * (a.cos() * e1 + a.sin() * e2)
        })
        .collect();
    let polygon = vec![Shape::Polygon { vertices: outline.clone() }];
    let fan: Vec<Shape> = (0..10).map(|k| triangle(centre, outline[k], outline[(k + 1) % 10])).collect();
    let normal = e1.cross(e2);
    let mut rng = Rng(6);
    for i in 0..6 {
        let eye = centre + (normal * rng.range(1.0, 3.0) * if i % 2 == 0 { 1.0 } else { -1.0 } + rng.direction()) * 2.0;
        let camera = Camera { eye, look_at: centre, up: e2, projection: Projection::Perspective { fov_y_degrees: 60.0 } };
        let whole = misses(&scene(polygon.clone(), camera));
        let triangulated = misses(&scene(fan.clone(), camera));
        assert!(whole.len() > 1000 && whole.len() < 512 * 512 - 1000, "camera {i}: the star is not in view");
        assert_eq!(whole, triangulated, "camera {i}: the polygon and its triangles cover different pixels");
    }
}
