use bytemuck::Zeroable;
use glam::{DVec3, Vec3};
use glint_encoding::gpu_types::{GpuPrim, PROJECTION_PERSPECTIVE};
use glint_scene::test_rng::Rng;

use super::*;

const WIDTH: u32 = 48;
const HEIGHT: u32 = 36;

/// A camera at the origin looking down −z, as `scene_uniforms` packs one.
fn camera(projection: u32) -> GpuCamera {
    let (half_width, half_height) = if projection == PROJECTION_ORTHOGRAPHIC { (4.0, 3.0) } else { (0.8, 0.6) };
    GpuCamera {
        eye: [0.0; 3],
        projection,
        u: [1.0, 0.0, 0.0],
        half_width,
        v: [0.0, 1.0, 0.0],
        half_height,
        w: [0.0, 0.0, 1.0],
        _pad: 0.0,
    }
}

/// The eye ray through pixel `(x, y)`'s centre, as shaders/lib/camera.wgsl makes it.
fn eye_ray(c: &GpuCamera, x: u32, y: u32) -> (Vec3, Vec3) {
    let us = -c.half_width + 2.0 * c.half_width * (x as f32 + 0.5) / WIDTH as f32;
    let vs = c.half_height - 2.0 * c.half_height * (y as f32 + 0.5) / HEIGHT as f32;
    let (u, v, w) = (Vec3::from(c.u), Vec3::from(c.v), Vec3::from(c.w));
    if c.projection == PROJECTION_ORTHOGRAPHIC {
        (Vec3::from(c.eye) + us * u + vs * v, -w)
    } else {
        (Vec3::from(c.eye), (-w + us * u + vs * v).normalize())
    }
}

/// The ray's hit distance on the triangle (Möller–Trumbore in f64), if any.
fn hit(origin: Vec3, dir: Vec3, [a, b, c]: [Vec3; 3]) -> Option<f64> {
    let (o, d) = (origin.as_dvec3(), dir.as_dvec3());
    let (a, e1, e2): (DVec3, DVec3, DVec3) = (a.as_dvec3(), (b - a).as_dvec3(), (c - a).as_dvec3());
    let p = d.cross(e2);
    let det = e1.dot(p);
    if det.abs() < 1e-12 {
        return None;
    }
    let s = o - a;
    let u = s.dot(p) / det;
    let q = s.cross(e1);
    let v = d.dot(q) / det;
    let t = e2.dot(q) / det;
    (u >= -1e-9 && v >= -1e-9 && u + v <= 1.0 + 1e-9 && t > 0.0).then_some(t)
}

/// Random triangles around the eye: in view, off to the sides, crossing the
/// eye's plane and behind it, small and large.
fn triangles(rng: &mut Rng) -> Vec<[Vec3; 3]> {
    (0..300)
        .map(|_| {
            let centre = rng.vec3(-6.0, 6.0) - Vec3::new(0.0, 0.0, 4.0);
            let size = if rng.f32() < 0.2 { 5.0 } else { 0.6 };
            [centre + size * rng.unit(), centre + size * rng.unit(), centre + size * rng.unit()]
        })
        .collect()
}

/// Every other triangle packed as a polygon of its three vertices, whose
/// footprint is its vertices in the scene's points.
fn footprints(triangles: &[[Vec3; 3]]) -> Footprints {
    let v = |p: Vec3| [p.x, p.y, p.z, 0.0];
    let mut points = Vec::new();
    let prims: Vec<GpuPrim> = triangles
        .iter()
        .enumerate()
        .map(|(i, t)| {
            if i % 2 == 0 {
                return GpuPrim { a: v(t[0]), b: v(t[1]), c: v(t[2]), kind_material: PRIM_TRIANGLE, ..GpuPrim::zeroed() };
            }
            let first = points.len() as u32;
            points.extend(t.map(v));
            GpuPrim { kind_material: PRIM_POLYGON, first, count: 3, ..GpuPrim::zeroed() }
        })
        .collect();
    let bounds: Vec<(Vec3, Vec3)> = triangles.iter().map(|t| (t[0].min(t[1]).min(t[2]), t[0].max(t[1]).max(t[2]))).collect();
    let scene = GpuScene { prims, nodes: Vec::new(), grids: Vec::new(), bvh_root: 0, materials: Vec::new(), lights: Vec::new(), points, light_count: 0 };
    Footprints::new(&scene, &bounds)
}

#[test]
fn every_eye_ray_finds_what_it_hits_in_its_tile_no_nearer_than_listed() {
    let mut rng = Rng(17);
    let triangles = triangles(&mut rng);
    for projection in [PROJECTION_PERSPECTIVE, PROJECTION_ORTHOGRAPHIC] {
        let camera = camera(projection);
        let tiles = footprints(&triangles).bin(&camera, WIDTH, HEIGHT).expect("a few hundred triangles fit");
        let mut hits = 0;
        for y in 0..HEIGHT {
            for x in 0..WIDTH {
                let (origin, dir) = eye_ray(&camera, x, y);
                let (listed, near) = tiles.entries(x / EYE_TILE_WIDTH, y / EYE_TILE_HEIGHT);
                let near: Vec<f32> = near.collect();
                for (i, triangle) in triangles.iter().enumerate() {
                    let Some(t) = hit(origin, dir, *triangle) else { continue };
                    hits += 1;
                    let entry = listed.iter().position(|&p| p == i as u32);
                    let entry = entry.unwrap_or_else(|| panic!("pixel ({x}, {y}) hits triangle {i}, which its tile does not list"));
                    assert!(f64::from(near[entry]) <= t, "triangle {i} listed {} away but hit at {t}", near[entry]);
                }
            }
        }
        assert!(hits > 1000, "the scene is in view ({hits} hits)");
    }
}

#[test]
fn a_tile_lists_nearest_first_and_only_what_its_rays_may_reach() {
    let mut rng = Rng(5);
    let triangles = triangles(&mut rng);
    let tiles = footprints(&triangles).bin(&camera(PROJECTION_PERSPECTIVE), WIDTH, HEIGHT).unwrap();
    assert_eq!((tiles.tiles_across, tiles.tiles_down), (WIDTH / EYE_TILE_WIDTH, HEIGHT / EYE_TILE_HEIGHT));
    let mut total = 0;
    for y in 0..tiles.tiles_down {
        for x in 0..tiles.tiles_across {
            let (listed, near) = tiles.entries(x, y);
            let near: Vec<f32> = near.collect();
            assert!(near.windows(2).all(|w| w[0] <= w[1]), "tile ({x}, {y}) is not nearest first: {near:?}");
            total += listed.len();
        }
    }
    let behind = triangles.iter().enumerate().filter(|(_, t)| t.iter().all(|p| p.z > 0.0)).map(|(i, _)| i as u32);
    for i in behind {
        assert!((0..tiles.tiles_down).all(|y| (0..tiles.tiles_across).all(|x| !tiles.entries(x, y).0.contains(&i))), "triangle {i} is behind the eye");
    }
    // Binned by footprint, not everywhere: the lists hold a fraction of all pairs.
    let tile_count = (tiles.tiles_across * tiles.tiles_down) as usize;
    assert!(total < triangles.len() * tile_count / 3, "{total} entries of {} pairs", triangles.len() * tile_count);
}

#[test]
fn a_tile_beyond_a_triangle_s_edge_does_not_list_it() {
    // A thin diagonal sliver across the image: its bounding rectangle reaches
    // every tile, its outline those along the diagonal.
    let camera = camera(PROJECTION_ORTHOGRAPHIC);
    let sliver = [Vec3::new(-4.0, -3.0, -1.0), Vec3::new(4.0, 3.0, -1.0), Vec3::new(4.0, 2.9, -1.0)];
    let tiles = footprints(&[sliver]).bin(&camera, WIDTH, HEIGHT).unwrap();
    let listed = tiles_whose_list(&tiles, |list| !list.is_empty());
    let all = (tiles.tiles_across * tiles.tiles_down) as usize;
    assert!(listed > 0 && listed < all / 2, "{listed} of {all} tiles list the sliver");
    // Packed as a polygon, the same.
    let polygon = footprints(&[sliver, sliver]).bin(&camera, WIDTH, HEIGHT).unwrap();
    assert_eq!(tiles_whose_list(&polygon, |list| list.len() == 2), listed);
}

/// How many of `tiles` list what `wanted` asks.
fn tiles_whose_list(tiles: &EyeTiles, wanted: impl Fn(&[u32]) -> bool) -> usize {
    (0..tiles.tiles_down).flat_map(|y| (0..tiles.tiles_across).map(move |x| (x, y))).filter(|&(x, y)| wanted(tiles.entries(x, y).0)).count()
}

#[test]
fn lists_longer_than_the_bvh_repays_are_not_built() {
    // Every triangle fills the view: each tile would list all of them.
    let wall = |z: f32| [Vec3::new(-500.0, -500.0, z), Vec3::new(500.0, -500.0, z), Vec3::new(0.0, 500.0, z)];
    let crowded: Vec<[Vec3; 3]> = (0..=MAX_MEAN_ENTRIES).map(|k| wall(-1.0 - k as f32)).collect();
    let camera = camera(PROJECTION_PERSPECTIVE);
    assert!(footprints(&crowded).bin(&camera, WIDTH, HEIGHT).is_none());
    assert!(footprints(&crowded[1..]).bin(&camera, WIDTH, HEIGHT).is_some());
}

