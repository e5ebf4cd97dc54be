use bytemuck::Zeroable;
use glam::{DVec3, Vec3};
use crate::gpu_bvh::GpuBvh;
use crate::gpu_types::{self, GpuPrim, PROJECTION_PERSPECTIVE};
use glint_scene::bvh::Bvh;
use glint_scene::test_rng::Rng;
use glint_scene::{polygon_split, spd, Camera, Projection, Scene};

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
    let scene = GpuScene { prims, nodes: Vec::new(), grids: Vec::new(), bvh_root: 0, materials: Vec::new(), lights: Vec::new(), points, light_count: 0, planes: (0, 0) };
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


#[test]
fn binning_lists_what_the_reference_binning_lists() {
    let mut rng = Rng(29);
    let random = footprints(&triangles(&mut rng));
    for projection in [PROJECTION_PERSPECTIVE, PROJECTION_ORTHOGRAPHIC] {
        let lists = random.bin(&camera(projection), WIDTH, HEIGHT);
        assert!(lists.is_some() && lists == reference_bin(&random, &camera(projection), WIDTH, HEIGHT), "random triangles around the eye");
    }
    let mut binned = 0;
    for name in ["gears", "tetra", "balls", "mount", "teapot"] {
        let mut scene = glint_scene::load(format!("{}{name}", spd::PREFIX).as_ref()).unwrap();
        let footprints = scene_footprints(&scene);
        let (lo, hi) = gpu_types::primitive_bounds(&scene).iter().fold((Vec3::MAX, Vec3::MIN), |(lo, hi), b| (lo.min(b.0), hi.max(b.1)));
        let own = scene.camera;
        // Balls', mount's and the teapot's eye inside their bounds, some of
        // them beside or behind it.
        let inside = Camera { eye: own.eye.lerp((lo + hi) / 2.0, 0.6), ..own };
        let from_above = Camera { eye: hi + Vec3::Y, look_at: lo, up: Vec3::X, projection: Projection::Orthographic { height: (hi - lo).length() } };
        for camera in [own, inside, from_above] {
            scene.camera = camera;
            for (width, height) in [(512, 512), (100, 75)] {
                let camera = gpu_types::scene_uniforms(&scene, width, height, 0, Default::default()).camera;
                let (fast, reference) = (footprints.bin(&camera, width, height), reference_bin(&footprints, &camera, width, height));
                assert!(fast == reference, "{name} seen from {:?} at {width}x{height}", scene.camera);
                binned += usize::from(fast.is_some());
            }
        }
    }
    assert!(binned >= 25, "only {binned} of 30 views were binned");
}

#[test]
fn a_convex_outline_in_order_is_the_hull_the_monotone_chain_finds() {
    let mut rng = Rng(41);
    let (mut taken, mut sorted, mut hull) = (0, Vec::new(), Vec::new());
    for round in 0..4000 {
        // Corners on an ellipse, in order round it from a random start, either
        // way round; some of them slivers, some far off the image.
        let n = 3 + round % 8;
        let (centre, size) = ([rng.f32() * 600.0 - 50.0, rng.f32() * 600.0 - 50.0], [0.5 + rng.f32() * 40.0, 0.01 + rng.f32() * 40.0]);
        let mut angles: Vec<f32> = (0..n).map(|_| rng.f32() * std::f32::consts::TAU).collect();
        angles.sort_by(f32::total_cmp);
        if round % 2 == 0 {
            angles.reverse();
        }
        angles.rotate_left(round % n);
        let corners: Vec<[f64; 2]> = angles.iter().map(|a| [f64::from(centre[0] + size[0] * a.cos()), f64::from(centre[1] + size[1] * a.sin())]).collect();
        let mut chain = Vec::new();
        sorted.clone_from(&corners);
        monotone_chain(&mut sorted, &mut chain);
        if convex_in_order(&corners, &mut hull) {
            taken += 1;
            assert_eq!(hull, chain, "corners {corners:?}");
        }
    }
    assert!(taken > 3000, "only {taken} of 4000 outlines were taken as they are");
    // A star turns the same way at every corner, but goes round twice.
    let star: Vec<[f64; 2]> = (0..5).map(|k| f64::from(k * 2) * std::f64::consts::TAU / 5.0).map(|a| [100.0 + 50.0 * a.cos(), 100.0 + 50.0 * a.sin()]).collect();
    assert!(!convex_in_order(&star, &mut hull));
}

/// `scene`'s footprints as `Renderer::prepare` makes them.
fn scene_footprints(scene: &Scene) -> Footprints {
    let scene = polygon_split::split_large_polygons(scene);
    let bounds = gpu_types::primitive_bounds(&scene);
    let bvh = Bvh::build(&bounds);
    let packed = gpu_types::pack(&scene, &bvh.order, GpuBvh::encode(&bvh).unwrap());
    Footprints::new(&packed, &bvh.order.iter().map(|&i| bounds[i as usize]).collect::<Vec<_>>())
}

/// The lists as binning first made them, to check the fast binning against:
/// every tile of each primitive's rectangle tested against every edge of its
/// outline (the monotone chain's hull of its sorted corners), and each tile's
/// list sorted on its own.
fn reference_bin(footprints: &Footprints, camera: &GpuCamera, width: u32, height: u32) -> Option<EyeTiles> {
    let view = View::new(camera, width, height);
    let (across, down) = (width.div_ceil(EYE_TILE_WIDTH) as usize, height.div_ceil(EYE_TILE_HEIGHT) as usize);
    let near: Vec<f32> = footprints.prims.iter().map(|f| view.near(f)).collect();
    let projections = view.project_all(&footprints.points);
    let mut lists = vec![Vec::new(); across * down];
    let mut outline = Outline::default();
    for (i, f) in footprints.prims.iter().enumerate() {
        let tiles: Vec<usize> = match view.reach(&footprints.corners[f.corners.clone()], &projections, across, down, &mut outline.projected) {
            Reach::Nowhere => Vec::new(),
            Reach::Everywhere => (0..across * down).collect(),
            Reach::Within { columns, rows, margin } => {
                let mut points: Vec<[f64; 2]> = outline.projected.iter().map(|p| [f64::from(p[0]), f64::from(p[1])]).collect();
                let mut hull = Vec::new();
                monotone_chain(&mut points, &mut hull);
                let edges: Option<Vec<Edge>> = has_inside(&hull).then(|| (0..hull.len()).map(|i| edge(hull[i], hull[(i + 1) % hull.len()])).collect());
                let tiles = rows.flat_map(|y| columns.clone().map(move |x| (x, y)));
                tiles.filter(|&(x, y)| edges.as_ref().is_none_or(|edges| !beyond_an_edge(edges, tile_centres(x, y), margin))).map(|(x, y)| y * across + x).collect()
            }
        };
        for tile in tiles {
            lists[tile].push(i as u32);
        }
    }
    if lists.iter().map(Vec::len).sum::<usize>() > MAX_MEAN_ENTRIES * lists.len() {
        return None;
    }
    let mut words = Vec::new();
    let mut first = 2 * lists.len();
    for list in &mut lists {
        list.sort_by(|&a, &b| near[a as usize].total_cmp(&near[b as usize]).then(a.cmp(&b)));
        words.extend([first as u32, list.len() as u32]);
        first += list.len();
    }
    for list in &lists {
        words.extend(list);
    }
    words.extend(near.iter().map(|d| d.to_bits()));
    Some(EyeTiles { words, tiles_across: across as u32, tiles_down: down as u32 })
}

/// Tile `(x, y)`'s first and last pixel centres, `[x0, y0, x1, y1]`.
fn tile_centres(x: usize, y: usize) -> [f64; 4] {
    let (w, h) = (f64::from(EYE_TILE_WIDTH), f64::from(EYE_TILE_HEIGHT));
    [x as f64 * w + 0.5, y as f64 * h + 0.5, x as f64 * w + w - 0.5, y as f64 * h + h - 0.5]
}

/// Whether every point of the rectangle `[x0, y0, x1, y1]` lies farther than
/// `margin` outside one of `edges`.
fn beyond_an_edge(edges: &[Edge], [x0, y0, x1, y1]: [f64; 4], margin: f64) -> bool {
    edges.iter().any(|&(a, n)| {
        let nearest = [if n[0] > 0.0 { x0 } else { x1 }, if n[1] > 0.0 { y0 } else { y1 }];
        (nearest[0] - a[0]) * n[0] + (nearest[1] - a[1]) * n[1] > margin
    })
}


