//! Eye-ray tiles: for each block of `EYE_TILE_WIDTH` × `EYE_TILE_HEIGHT`
//! pixels, the primitives an eye ray through one of its pixel centres can hit,
//! nearest first. A perspective grid of one cell in depth (Hunt & Mark,
//! "Ray-specialized acceleration structures for ray tracing", 2008), built on
//! the host for each view.
//!
//! Why: a software rasteriser runs a SIMD group's lanes through the BVH each on its own
//! path, loading every node and primitive once per lane. The lanes of a tile's
//! SIMD group instead walk one short list together, so each primitive is loaded
//! once for all of them (shaders/fast/eye_tiles.wgsl), and the walk stops when
//! every ray has hit something nearer than the next primitive can be.
//!
//! A primitive is listed in every tile with a pixel centre in its projection's
//! bounding rectangle, grown for rounding; one that reaches behind the eye (or
//! into the eye's plane) is listed everywhere. Each entry carries a distance no hit on
//! it can be nearer than, with room for rounding, and a tile's entries are in
//! order of it.

use glam::Vec3;
use glint_encoding::gpu_types::{GpuCamera, GpuScene, EYE_TILE_HEIGHT, EYE_TILE_WIDTH, PRIM_POLYGON, PRIM_TRIANGLE, PROJECTION_ORTHOGRAPHIC};

/// The most entries the lists may hold per tile on average: beyond that a
/// tile's list costs its rays more than the BVH walk (gears at 512×512, the
/// most crowded classic scene, holds 37).
pub const MAX_MEAN_ENTRIES: usize = 64;

/// Pixels by which a primitive's projected rectangle is grown, besides a
/// share of its coordinates: far more than the rounding of the projection
/// and of the eye rays, so an eye ray's hit is always in its list.
const MARGIN_PIXELS: f32 = 1.0 / 64.0;
const MARGIN_SHARE: f32 = 1.0 / 65536.0;

/// The share of an entry's distance kept back for rounding: a computed hit
/// distance may fall short of the true one (grazing rays most), and the walk
/// must not stop before a primitive the BVH walk would have tested.
const NEAR_SLACK: f32 = 0.01;

/// What the host keeps of the BVH's primitives, in the kernels' order, to bin
/// them for any view: each one's bounds, and the points whose projections
/// bound its own: a triangle's or polygon's vertices (tighter than its box's
/// corners), else its box's corners.
#[derive(Debug, Clone, Default)]
pub struct Footprints {
    prims: Vec<Footprint>,
    points: Vec<Vec3>,
}

#[derive(Debug, Clone)]
struct Footprint {
    lo: Vec3,
    hi: Vec3,
    points: std::ops::Range<usize>,
}

/// The tiles' lists as the kernel reads them, one array of words: first two
/// per tile (row by row), the index of its first entry and the number of
/// entries; then each tile's entries, their primitive indices followed by
/// their distances (as `f32` bits).
#[derive(Debug, Clone, PartialEq)]
pub struct EyeTiles {
    pub words: Vec<u32>,
    pub tiles_across: u32,
    pub tiles_down: u32,
}

impl Footprints {
    /// `scene`'s primitives as packed (the BVH's first, in its order) and
    /// `bounds`, the bounds of those BVH primitives in the same order.
    pub fn new(scene: &GpuScene, bounds: &[(Vec3, Vec3)]) -> Footprints {
        let vertex = |v: &[f32; 4]| Vec3::new(v[0], v[1], v[2]);
        let mut points = Vec::new();
        let prims = bounds
            .iter()
            .zip(&scene.prims)
            .map(|(&(lo, hi), p)| {
                let first = points.len();
                match p.kind() {
                    PRIM_TRIANGLE => points.extend([&p.a, &p.b, &p.c].map(vertex)),
                    PRIM_POLYGON => points.extend(scene.points[p.first as usize..(p.first + p.count) as usize].iter().map(vertex)),
                    _ => points.extend(corners(lo, hi)),
                }
                Footprint { lo, hi, points: first..points.len() }
            })
            .collect();
        Footprints { prims, points }
    }

    /// The lists for `camera` at `width` × `height`, or `None` when they would
    /// be too long to beat the BVH (`MAX_MEAN_ENTRIES`).
    pub fn bin(&self, camera: &GpuCamera, width: u32, height: u32) -> Option<EyeTiles> {
        let view = View::new(camera, width, height);
        let (across, down) = (width.div_ceil(EYE_TILE_WIDTH) as usize, height.div_ceil(EYE_TILE_HEIGHT) as usize);
        let tiles = across * down;
        // Binned nearest first, so every tile's entries come out in that order.
        let near: Vec<f32> = self.prims.iter().map(|f| view.near(f)).collect();
        let mut order: Vec<u32> = (0..self.prims.len() as u32).collect();
        order.sort_unstable_by(|&a, &b| near[a as usize].total_cmp(&near[b as usize]).then(a.cmp(&b)));
        // Each primitive's tiles, one run of `covered` each.
        let (mut covered, mut runs, mut projected) = (Vec::new(), Vec::with_capacity(self.prims.len()), Vec::new());
        for f in &self.prims {
            let start = covered.len();
            view.cover(&self.points[f.points.clone()], across, down, &mut projected, &mut covered);
            runs.push(start..covered.len());
        }
        let mut counts = vec![0usize; tiles];
        for &tile in &covered {
            counts[tile as usize] += 1;
        }
        let entries: usize = counts.iter().sum();
        if entries > MAX_MEAN_ENTRIES * tiles || 2 * tiles + 2 * entries > u32::MAX as usize {
            return None;
        }
        let mut words = vec![0u32; 2 * tiles + 2 * entries];
        let mut next = 2 * tiles;
        for (tile, &count) in counts.iter().enumerate() {
            words[2 * tile] = next as u32;
            words[2 * tile + 1] = 0;
            next += 2 * count;
        }
        for &i in &order {
            for &tile in &covered[runs[i as usize].clone()] {
                let tile = tile as usize;
                let (first, filled) = (words[2 * tile] as usize, words[2 * tile + 1] as usize);
                words[first + filled] = i;
                words[first + counts[tile] + filled] = near[i as usize].to_bits();
                words[2 * tile + 1] += 1;
            }
        }
        Some(EyeTiles { words, tiles_across: across as u32, tiles_down: down as u32 })
    }
}

impl EyeTiles {
    /// Tile `(x, y)`'s entries: primitive indices and their distances.
    pub fn entries(&self, x: u32, y: u32) -> (&[u32], impl Iterator<Item = f32> + '_) {
        let tile = (y * self.tiles_across + x) as usize;
        let (first, count) = (self.words[2 * tile] as usize, self.words[2 * tile + 1] as usize);
        (&self.words[first..first + count], self.words[first + count..first + 2 * count].iter().map(|&w| f32::from_bits(w)))
    }
}

/// The camera as the kernels make eye rays (shaders/lib/camera.wgsl), for
/// projecting points onto the image.
struct View {
    eye: Vec3,
    u: Vec3,
    v: Vec3,
    w: Vec3,
    half_width: f32,
    half_height: f32,
    orthographic: bool,
    width: f32,
    height: f32,
}

impl View {
    fn new(camera: &GpuCamera, width: u32, height: u32) -> View {
        View {
            eye: camera.eye.into(),
            u: camera.u.into(),
            v: camera.v.into(),
            w: camera.w.into(),
            half_width: camera.half_width,
            half_height: camera.half_height,
            orthographic: camera.projection == PROJECTION_ORTHOGRAPHIC,
            width: width as f32,
            height: height as f32,
        }
    }

    /// A distance below any eye ray's hit on the primitive: the eye's distance
    /// to its box (an eye ray's direction has unit length), or for parallel
    /// rays, which start in the eye's plane, the box's depth in front of it.
    fn near(&self, f: &Footprint) -> f32 {
        let distance = if self.orthographic {
            corners(f.lo, f.hi).iter().map(|&c| (c - self.eye).dot(-self.w)).fold(f32::MAX, f32::min)
        } else {
            self.eye.clamp(f.lo, f.hi).distance(self.eye)
        };
        distance - NEAR_SLACK * distance.abs()
    }

    /// Appends to `covered` the tiles with a pixel centre whose eye ray can
    /// hit what `points` bound: none when all of it is behind the eye, where
    /// no eye ray goes. Those its projection's bounding rectangle reaches,
    /// less those wholly beyond one of the edges of its convex hull.
    /// `projected` is room.
    fn cover(&self, points: &[Vec3], across: usize, down: usize, projected: &mut Vec<[f32; 2]>, covered: &mut Vec<u32>) {
        let mut all = || covered.extend(0..(across * down) as u32);
        let in_front = |p: Vec3| (p - self.eye).dot(-self.w) > 1e-6 * (p - self.eye).length();
        if !points.iter().any(|&p| in_front(p)) {
            return;
        }
        // A point beside or behind the eye projects to no point of the image:
        // the primitive may then cross any eye ray.
        if !self.orthographic && !points.iter().all(|&p| in_front(p)) {
            return all();
        }
        projected.clear();
        projected.extend(points.iter().map(|&p| self.project(p)));
        let (mut lo, mut hi) = ([f32::MAX; 2], [f32::MIN; 2]);
        for pixel in projected.iter() {
            for axis in 0..2 {
                lo[axis] = lo[axis].min(pixel[axis]);
                hi[axis] = hi[axis].max(pixel[axis]);
            }
        }
        if !(lo.iter().chain(&hi).all(|x| x.is_finite())) {
            return all();
        }
        let margin = MARGIN_PIXELS + MARGIN_SHARE * lo.iter().chain(&hi).fold(0.0f32, |m, x| m.max(x.abs()));
        // Tile t's pixel centres run from side·t + ½ to side·t + side − ½.
        let range = |axis: usize, side: u32, count: usize| {
            let side = side as f32;
            let first = ((lo[axis] - margin - (side - 0.5)) / side).ceil().max(0.0);
            let last = ((hi[axis] + margin - 0.5) / side).floor().min(count as f32 - 1.0);
            if first > last { 0..0 } else { first as usize..last as usize + 1 }
        };
        let edges = hull_edges(projected);
        let (w, h) = (f64::from(EYE_TILE_WIDTH), f64::from(EYE_TILE_HEIGHT));
        for y in range(1, EYE_TILE_HEIGHT, down) {
            for x in range(0, EYE_TILE_WIDTH, across) {
                let centres = [x as f64 * w + 0.5, y as f64 * h + 0.5, x as f64 * w + w - 0.5, y as f64 * h + h - 0.5];
                if edges.as_ref().is_none_or(|edges| !beyond_an_edge(edges, centres, f64::from(margin))) {
                    covered.push((y * across + x) as u32);
                }
            }
        }
    }

    /// Where on the image (in pixels, (0, 0) its top-left corner) the eye ray
    /// through `p`, a point in front of the eye, passes.
    fn project(&self, p: Vec3) -> [f32; 2] {
        let q = p - self.eye;
        let (us, vs) = if self.orthographic { (q.dot(self.u), q.dot(self.v)) } else {
            let depth = q.dot(-self.w);
            (q.dot(self.u) / depth, q.dot(self.v) / depth)
        };
        [(us + self.half_width) / (2.0 * self.half_width) * self.width, (self.half_height - vs) / (2.0 * self.half_height) * self.height]
    }
}

/// The edges of the convex hull of `projected` (Andrew's monotone chain) as
/// lines `(a, n)` through point a with unit normal n pointing out of it, if
/// the hull has an inside.
fn hull_edges(projected: &[[f32; 2]]) -> Option<Vec<([f64; 2], [f64; 2])>> {
    let mut points: Vec<[f64; 2]> = projected.iter().map(|p| [f64::from(p[0]), f64::from(p[1])]).collect();
    points.sort_by(|a, b| a[0].total_cmp(&b[0]).then(a[1].total_cmp(&b[1])));
    let cross = |o: [f64; 2], a: [f64; 2], b: [f64; 2]| (a[0] - o[0]) * (b[1] - o[1]) - (a[1] - o[1]) * (b[0] - o[0]);
    let mut hull: Vec<[f64; 2]> = Vec::with_capacity(2 * points.len());
    for pass in [points.clone(), points.into_iter().rev().collect()] {
        let start = hull.len();
        for p in pass {
            while hull.len() >= start + 2 && cross(hull[hull.len() - 2], hull[hull.len() - 1], p) <= 0.0 {
                hull.pop();
            }
            hull.push(p);
        }
        hull.pop();
    }
    let n = hull.len();
    let area: f64 = (0..n).map(|i| hull[i][0] * hull[(i + 1) % n][1] - hull[(i + 1) % n][0] * hull[i][1]).sum();
    if n < 3 || area < 1e-6 {
        return None;
    }
    // Counter-clockwise: outward is to the right of each edge.
    let edges = (0..n).map(|i| {
        let (a, b) = (hull[i], hull[(i + 1) % n]);
        let (dx, dy) = (b[0] - a[0], b[1] - a[1]);
        let length = dx.hypot(dy);
        (a, [dy / length, -dx / length])
    });
    Some(edges.collect())
}

/// Whether every point of the rectangle `[x0, y0, x1, y1]` lies farther than
/// `margin` outside one of `edges`.
fn beyond_an_edge(edges: &[([f64; 2], [f64; 2])], [x0, y0, x1, y1]: [f64; 4], margin: f64) -> bool {
    edges.iter().any(|&(a, n)| {
        let nearest = [if n[0] > 0.0 { x0 } else { x1 }, if n[1] > 0.0 { y0 } else { y1 }];
        (nearest[0] - a[0]) * n[0] + (nearest[1] - a[1]) * n[1] > margin
    })
}

fn corners(lo: Vec3, hi: Vec3) -> [Vec3; 8] {
    std::array::from_fn(|k| Vec3::new([lo.x, hi.x][k & 1], [lo.y, hi.y][(k >> 1) & 1], [lo.z, hi.z][(k >> 2) & 1]))
}

#[cfg(test)]
mod tests;
