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
//! bounding rectangle, grown for rounding, less the tiles beyond its outline;
//! one that reaches behind the eye (or into the eye's plane) is listed
//! everywhere. Each primitive has a distance no hit on it can be nearer than,
//! with room for rounding, and a tile's entries are in order of it.

use std::collections::HashMap;
use std::ops::Range;

use glam::Vec3;
use rayon::prelude::*;
use crate::gpu_types::{GpuCamera, GpuScene, EYE_TILE_HEIGHT, EYE_TILE_WIDTH, PRIM_POLYGON, PRIM_TRIANGLE, PROJECTION_ORTHOGRAPHIC};

/// The most entries the lists may hold per tile on average: beyond that a
/// tile's list costs its rays more than the BVH walk (gears at 512×512, the
/// most crowded classic scene, holds 37).
pub const MAX_MEAN_ENTRIES: usize = 64;

/// How many primitives a core takes at a time: enough to repay handing them
/// over.
const SHARE: usize = 1024;

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
/// corners), else its box's corners. Each point is kept once, so that a
/// vertex that neighbours share is projected once a view.
#[derive(Debug, Clone, Default)]
pub struct Footprints {
    prims: Vec<Footprint>,
    /// Each footprint's points, as indices into `points`.
    corners: Vec<u32>,
    points: Vec<Vec3>,
}

#[derive(Debug, Clone)]
struct Footprint {
    lo: Vec3,
    hi: Vec3,
    corners: Range<usize>,
    /// The corners are a triangle's or a polygon's, in order round it (a
    /// box's are not), so a convex one may be its own hull.
    in_order: bool,
}

/// The tiles' lists as the kernel reads them, one array of words: first two
/// per tile (row by row), the index of its first entry and the number of
/// entries; then each tile's entries, primitive indices; then, from where the
/// last tile's entries end, each primitive's distance (as `f32` bits), once
/// for all the tiles that list it.
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
        let (mut points, mut corners, mut index) = (Vec::new(), Vec::new(), HashMap::new());
        let prims = bounds
            .iter()
            .zip(&scene.prims)
            .map(|(&(lo, hi), p)| {
                let first = corners.len();
                let mut add = |point: Vec3| {
                    let i = *index.entry(point.to_array().map(f32::to_bits)).or_insert_with(|| {
                        points.push(point);
                        points.len() as u32 - 1
                    });
                    corners.push(i);
                };
                match p.kind() {
                    PRIM_TRIANGLE => [&p.a, &p.b, &p.c].map(vertex).into_iter().for_each(&mut add),
                    PRIM_POLYGON => scene.points[p.first as usize..(p.first + p.count) as usize].iter().map(vertex).for_each(&mut add),
                    _ => self::corners(lo, hi).into_iter().for_each(&mut add),
                }
                Footprint { lo, hi, corners: first..corners.len(), in_order: matches!(p.kind(), PRIM_TRIANGLE | PRIM_POLYGON) }
            })
            .collect();
        Footprints { prims, corners, points }
    }

    /// The lists for `camera` at `width` × `height`, or `None` when they would
    /// be too long to beat the BVH (`MAX_MEAN_ENTRIES`). Done for every view,
    /// so on every core (docs/decisions/048-cheaper-eye-tile-binning.md).
    pub fn bin(&self, camera: &GpuCamera, width: u32, height: u32) -> Option<EyeTiles> {
        // Handed to the pool once: each parallel step from outside it would
        // wake its threads and then this one again.
        rayon::scope(|_| self.bin_in_pool(camera, width, height))
    }

    fn bin_in_pool(&self, camera: &GpuCamera, width: u32, height: u32) -> Option<EyeTiles> {
        let view = View::new(camera, width, height);
        let (across, down) = (width.div_ceil(EYE_TILE_WIDTH) as usize, height.div_ceil(EYE_TILE_HEIGHT) as usize);
        let tiles = across * down;
        // The lists are filled in two halves of the tiles, each on a core.
        let middle = tiles / 2;
        let near: Vec<f32> = self.prims.iter().map(|f| view.near(f)).collect();
        let projections = view.project_all(&self.points);
        // Covered in the BVH's order, whose neighbours lie near in memory, a
        // share on whichever core is free.
        let (order, shares): (Vec<u32>, Vec<Covered>) = rayon::join(
            || nearest_first(&near),
            || {
                self.prims
                    .par_chunks(SHARE)
                    .map(|prims| {
                        let mut covered = Covered { tiles: Vec::new(), starts: Vec::with_capacity(2 * prims.len() + 1), outline: Outline::default() };
                        covered.starts.push(0);
                        for prim in prims {
                            let start = covered.tiles.len();
                            view.cover(self.corners_of(prim), &projections, across, down, &mut covered.outline, &mut covered.tiles);
                            // A primitive's tiles ascend, so those in each half are one stretch.
                            covered.starts.push(start + covered.tiles[start..].partition_point(|&tile| (tile as usize) < middle));
                            covered.starts.push(covered.tiles.len());
                        }
                        covered
                    })
                    .collect()
            },
        );
        let entries = shares.iter().map(|share| share.tiles.len()).sum::<usize>();
        let length = 2 * tiles + entries + near.len();
        if entries > MAX_MEAN_ENTRIES * tiles || length > u32::MAX as usize {
            return None;
        }
        let mut counts = vec![0u32; tiles];
        for &tile in shares.iter().flat_map(|share| &share.tiles) {
            counts[tile as usize] += 1;
        }
        let mut words = vec![0u32; length];
        let (heads, lists) = words.split_at_mut(2 * tiles);
        let (lists, distances) = lists.split_at_mut(entries);
        distances.iter_mut().zip(&near).for_each(|(word, near)| *word = near.to_bits());
        let mut first = 2 * tiles as u32;
        for (head, &count) in heads.chunks_exact_mut(2).zip(&counts) {
            head.copy_from_slice(&[first, count]);
            first += count;
        }
        // The entries of the first half of the tiles, then the second's.
        let fill = |half: usize, tiles: Range<usize>, lists: &mut [u32]| {
            let offset = heads.get(2 * tiles.start).map_or(0, |&first| first as usize);
            let mut next: Vec<usize> = tiles.clone().map(|tile| heads[2 * tile] as usize - offset).collect();
            // Binned nearest first, so every tile's entries come out in that order.
            for &i in &order {
                let share = &shares[i as usize / SHARE];
                let k = 2 * (i as usize % SHARE) + half;
                for tile in share.tiles[share.starts[k]..share.starts[k + 1]].iter().map(|&tile| tile as usize) {
                    let slot = &mut next[tile - tiles.start];
                    lists[*slot] = i;
                    *slot += 1;
                }
            }
        };
        let (low, high) = lists.split_at_mut(heads[2 * middle] as usize - 2 * tiles);
        rayon::join(|| fill(0, 0..middle, low), || fill(1, middle..tiles, high));
        Some(EyeTiles { words, tiles_across: across as u32, tiles_down: down as u32 })
    }

    /// `prim`'s corners, as indices into `points`, and whether they go round it in order.
    fn corners_of(&self, prim: &Footprint) -> (&[u32], bool) {
        (&self.corners[prim.corners.clone()], prim.in_order)
    }
}

/// A share of the primitives' tiles: the k-th one's are
/// `tiles[starts[2k]..starts[2k + 2]]`, those in the first half of the image's
/// tiles up to `starts[2k + 1]`. With the room their outlines took.
struct Covered {
    tiles: Vec<u32>,
    starts: Vec<usize>,
    outline: Outline,
}

/// The indices of `near` by distance, equal distances by index, as
/// `f32::total_cmp` orders them: a radix sort of 11 bits a pass, each pass
/// keeping the order of the one before among equal digits.
fn nearest_first(near: &[f32]) -> Vec<u32> {
    const DIGIT: u32 = 11;
    let keys: Vec<u32> = near.iter().map(|&d| sortable_bits(d)).collect();
    let (mut order, mut spare): (Vec<u32>, Vec<u32>) = ((0..near.len() as u32).collect(), vec![0; near.len()]);
    for shift in (0..32).step_by(DIGIT as usize) {
        let digit = |i: u32| (keys[i as usize] >> shift & ((1 << DIGIT) - 1)) as usize;
        let mut starts = [0usize; 1 << DIGIT];
        for &i in &order {
            starts[digit(i)] += 1;
        }
        let mut sum = 0;
        for start in &mut starts {
            (sum, *start) = (sum + *start, sum);
        }
        for &i in &order {
            spare[starts[digit(i)]] = i;
            starts[digit(i)] += 1;
        }
        std::mem::swap(&mut order, &mut spare);
    }
    order
}

impl EyeTiles {
    /// Tile `(x, y)`'s entries: primitive indices and their distances.
    pub fn entries(&self, x: u32, y: u32) -> (&[u32], impl Iterator<Item = f32> + '_) {
        let tile = (y * self.tiles_across + x) as usize;
        let (first, count) = (self.words[2 * tile] as usize, self.words[2 * tile + 1] as usize);
        let listed = &self.words[first..first + count];
        (listed, listed.iter().map(|&i| f32::from_bits(self.words[self.distances() + i as usize])))
    }

    /// Where the primitives' distances start: where the last tile's entries end.
    fn distances(&self) -> usize {
        let last = 2 * (self.tiles_across * self.tiles_down) as usize - 2;
        (self.words[last] + self.words[last + 1]) as usize
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
    /// hit what the points `corners` bound, row by row: those its projection's
    /// bounding rectangle reaches, less those wholly beyond one of the edges of
    /// its convex hull. `in_order`: the corners go round an outline.
    fn cover(&self, (corners, in_order): (&[u32], bool), projections: &Projections, across: usize, down: usize, outline: &mut Outline, covered: &mut Vec<u32>) {
        match self.reach(corners, projections, across, down, &mut outline.projected) {
            Reach::Nowhere => {}
            Reach::Everywhere => covered.extend(0..(across * down) as u32),
            Reach::Within { columns, rows, margin } => {
                outline.cut(&columns, &rows, margin, in_order);
                let cuts = &outline.cuts;
                if cuts.is_empty() {
                    return covered.extend(rows.flat_map(|y| (y * across + columns.start) as u32..(y * across + columns.end) as u32));
                }
                // Along a row, the tiles beyond an edge whose normal points
                // left lead it, those beyond one pointing right trail it, and
                // an edge along the row takes all or none (as in
                // `Outline::cut`): the rest are one run, from the first tile
                // not beyond a leading edge to the last not beyond a trailing one.
                for y in rows {
                    let (mut first, mut end) = (columns.start, columns.end);
                    for cut in cuts {
                        let row = cut.row_term(y);
                        let beyond = |x: usize| cut.column_term(x) + row > margin;
                        if cut.edge.1[0] > 0.0 {
                            while end > first && beyond(end - 1) {
                                end -= 1;
                            }
                        } else if cut.edge.1[0] < 0.0 {
                            while first < end && beyond(first) {
                                first += 1;
                            }
                        } else if beyond(first) {
                            end = first;
                        }
                        if first == end {
                            break;
                        }
                    }
                    covered.extend((y * across + first) as u32..(y * across + end) as u32);
                }
            }
        }
    }

    /// Where each of `points` projects, and whether it lies in front of the
    /// eye, on every core.
    fn project_all(&self, points: &[Vec3]) -> Projections {
        let (mut at, mut in_front) = (vec![[0.0; 2]; points.len()], vec![false; points.len()]);
        let shares = at.par_chunks_mut(SHARE).zip(in_front.par_chunks_mut(SHARE)).zip(points.par_chunks(SHARE));
        shares.for_each(|((at, in_front), points)| {
            for ((at, in_front), &p) in at.iter_mut().zip(in_front).zip(points) {
                let q = p - self.eye;
                let depth = q.dot(-self.w);
                *in_front = depth > 1e-6 * q.length();
                // A point beside or behind the eye projects to no point of
                // the image, unless the rays are parallel.
                *at = if *in_front || self.orthographic { self.project(q, depth) } else { [f32::NAN; 2] };
            }
        });
        (at, in_front)
    }

    /// Which tiles' eye rays may hit what the points `corners` bound, leaving
    /// their projections in `projected`: none when all of it is behind the
    /// eye, where no eye ray goes.
    fn reach(&self, corners: &[u32], (at, in_front): &Projections, across: usize, down: usize, projected: &mut Vec<[f32; 2]>) -> Reach {
        projected.clear();
        let mut ahead = 0;
        for &i in corners {
            let i = i as usize;
            ahead += usize::from(in_front[i]);
            if in_front[i] || self.orthographic {
                projected.push(at[i]);
            }
        }
        if ahead == 0 {
            return Reach::Nowhere;
        }
        // A point beside or behind the eye projects to no point of the image:
        // the primitive may then cross any eye ray.
        if ahead < corners.len() && !self.orthographic {
            return Reach::Everywhere;
        }
        let (mut lo, mut hi) = ([f32::MAX; 2], [f32::MIN; 2]);
        for pixel in projected.iter() {
            for axis in 0..2 {
                lo[axis] = lo[axis].min(pixel[axis]);
                hi[axis] = hi[axis].max(pixel[axis]);
            }
        }
        if !(lo.iter().chain(&hi).all(|x| x.is_finite())) {
            return Reach::Everywhere;
        }
        let margin = MARGIN_PIXELS + MARGIN_SHARE * lo.iter().chain(&hi).fold(0.0f32, |m, x| m.max(x.abs()));
        // Tile t's pixel centres run from side·t + ½ to side·t + side − ½.
        let range = |axis: usize, side: u32, count: usize| {
            let side = side as f32;
            let first = ((lo[axis] - margin - (side - 0.5)) / side).ceil().max(0.0);
            let last = ((hi[axis] + margin - 0.5) / side).floor().min(count as f32 - 1.0);
            if first > last { 0..0 } else { first as usize..last as usize + 1 }
        };
        let (columns, rows) = (range(0, EYE_TILE_WIDTH, across), range(1, EYE_TILE_HEIGHT, down));
        if columns.is_empty() || rows.is_empty() {
            return Reach::Nowhere;
        }
        Reach::Within { columns, rows, margin: f64::from(margin) }
    }

    /// Where on the image (in pixels, (0, 0) its top-left corner) the eye ray
    /// through `eye + q` passes, a point `depth` in front of the eye.
    fn project(&self, q: Vec3, depth: f32) -> [f32; 2] {
        let (us, vs) = if self.orthographic { (q.dot(self.u), q.dot(self.v)) } else { (q.dot(self.u) / depth, q.dot(self.v) / depth) };
        [(us + self.half_width) / (2.0 * self.half_width) * self.width, (self.half_height - vs) / (2.0 * self.half_height) * self.height]
    }
}

/// Where on the image each point projects, and whether it lies in front of
/// the eye.
type Projections = (Vec<[f32; 2]>, Vec<bool>);

/// The tiles a footprint's projection may reach: a rectangle of them, each
/// grown by `margin` pixels for rounding.
enum Reach {
    Nowhere,
    Everywhere,
    Within { columns: Range<usize>, rows: Range<usize>, margin: f64 },
}

/// A line `(a, n)` through point a with unit normal n.
type Edge = ([f64; 2], [f64; 2]);

/// One footprint's projection and outline on the image, with room reused
/// from one primitive to the next.
#[derive(Default)]
struct Outline {
    projected: Vec<[f32; 2]>,
    /// The projections in f64, which the monotone chain sorts.
    points: Vec<[f64; 2]>,
    hull: Vec<[f64; 2]>,
    cuts: Vec<Cut>,
}

impl Outline {
    /// Makes `cuts` those edges of the convex hull of `projected` that take
    /// tiles from the rectangle of `columns` × `rows`, their normals pointing
    /// out of it; none when the hull has no inside.
    ///
    /// An edge takes tiles only if the rectangle's corner tile farthest out
    /// lies beyond it: the distance of a tile's nearest pixel centre beyond an
    /// edge grows (or shrinks) along the rectangle's rows and columns, rounding
    /// included. An edge whose unscaled distance to that tile is not positive
    /// is let go before its normal is scaled: scaled, rounding could move it
    /// by far less than `margin`.
    fn cut(&mut self, columns: &Range<usize>, rows: &Range<usize>, margin: f64, in_order: bool) {
        self.cuts.clear();
        if !self.hull(in_order) {
            return;
        }
        let Outline { hull, cuts, .. } = self;
        let n = hull.len();
        let outmost = |outward: bool, tiles: &Range<usize>| if outward { tiles.end - 1 } else { tiles.start };
        for i in 0..n {
            let (a, b) = (hull[i], hull[if i + 1 == n { 0 } else { i + 1 }]);
            let (dx, dy) = (b[0] - a[0], b[1] - a[1]);
            let (x, y) = (outmost(dy > 0.0, columns), outmost(-dx > 0.0, rows));
            let nearest = |t: usize, side: u32, toward: f64| f64::from(t as u32 * side) + nearest_offset(side, toward);
            if (nearest(x, EYE_TILE_WIDTH, dy) - a[0]) * dy - (nearest(y, EYE_TILE_HEIGHT, -dx) - a[1]) * dx <= 0.0 {
                continue;
            }
            let cut = Cut::new(edge(a, b));
            if cut.column_term(x) + cut.row_term(y) > margin {
                cuts.push(cut);
            }
        }
    }

    /// Makes `hull` the convex hull of `projected`, counter-clockwise from its
    /// lowest point in x, then y, as Andrew's monotone chain leaves it. False
    /// when the hull has no inside. `in_order`: the points go round an outline.
    fn hull(&mut self, in_order: bool) -> bool {
        let Outline { projected, points, hull, .. } = self;
        points.clear();
        points.extend(projected.iter().map(|p| [f64::from(p[0]), f64::from(p[1])]));
        if !(in_order && convex_in_order(points, hull)) {
            monotone_chain(points, hull);
        }
        has_inside(hull)
    }
}

/// The line through `a` and `b`, with its normal to the right of a to b.
fn edge(a: [f64; 2], b: [f64; 2]) -> Edge {
    let (dx, dy) = (b[0] - a[0], b[1] - a[1]);
    let length = (dx * dx + dy * dy).sqrt();
    (a, [dy / length, -dx / length])
}

/// Twice the signed area of the triangle `o`, `a`, `b`: positive when it
/// turns counter-clockwise, as the hull's corners do.
fn cross(o: [f64; 2], a: [f64; 2], b: [f64; 2]) -> f64 {
    (a[0] - o[0]) * (b[1] - o[1]) - (a[1] - o[1]) * (b[0] - o[0])
}

/// Whether a counter-clockwise `hull` encloses an area.
fn has_inside(hull: &[[f64; 2]]) -> bool {
    let n = hull.len();
    let next = |i: usize| if i + 1 == n { 0 } else { i + 1 };
    let area: f64 = (0..n).map(|i| hull[i][0] * hull[next(i)][1] - hull[next(i)][0] * hull[i][1]).sum();
    n >= 3 && area >= 1e-6
}

/// Andrew's monotone chain: makes `hull` the convex hull of `points`,
/// sorting them.
fn monotone_chain(points: &mut [[f64; 2]], hull: &mut Vec<[f64; 2]>) {
    // By x, then y: an insertion sort, as there are few.
    for k in 1..points.len() {
        let p = points[k];
        let mut j = k;
        while j > 0 && lowest_first(points[j - 1], p).is_gt() {
            points[j] = points[j - 1];
            j -= 1;
        }
        points[j] = p;
    }
    hull.clear();
    // The lower hull left to right, then the upper one back.
    for backwards in [false, true] {
        let start = hull.len();
        for k in 0..points.len() {
            let p = points[if backwards { points.len() - 1 - k } else { k }];
            while hull.len() >= start + 2 && cross(hull[hull.len() - 2], hull[hull.len() - 1], p) <= 0.0 {
                hull.pop();
            }
            hull.push(p);
        }
        hull.pop();
    }
}

/// The order of the monotone chain's sort: by x, then y.
fn lowest_first(a: [f64; 2], b: [f64; 2]) -> std::cmp::Ordering {
    a[0].total_cmp(&b[0]).then(a[1].total_cmp(&b[1]))
}

/// Makes `hull` the monotone chain's hull of `points` without sorting them,
/// when they are the corners of a convex polygon in order (as a convex
/// polygon's, or a triangle's, project): then the hull is all of them, turned
/// counter-clockwise and started at the lowest. False, leaving `hull` to the
/// chain, unless every corner turns the same way, clearly beyond rounding,
/// and the outline goes round once.
fn convex_in_order(points: &[[f64; 2]], hull: &mut Vec<[f64; 2]>) -> bool {
    let n = points.len();
    if n < 3 {
        return false;
    }
    let scale = points.iter().flatten().fold(1.0f64, |m, x| m.max(x.abs()));
    let clear = CLEAR_TURN * scale * scale;
    let (mut left, mut right) = (true, true);
    // Turning one way at every corner, an outline that goes round more than
    // once (a star) turns back in x more than twice.
    let (mut reversals, mut first_dx, mut last_dx) = (0, 0.0, 0.0);
    let (mut before, mut corner) = (points[n - 2], points[n - 1]);
    for &after in points {
        let turn = cross(before, corner, after);
        (left, right) = (left && turn > clear, right && turn < -clear);
        let dx = after[0] - corner[0];
        if dx != 0.0 {
            reversals += usize::from(last_dx * dx < 0.0);
            (first_dx, last_dx) = (if first_dx == 0.0 { dx } else { first_dx }, dx);
        }
        (before, corner) = (corner, after);
    }
    reversals += usize::from(last_dx * first_dx < 0.0);
    if !(left || right) || reversals != 2 {
        return false;
    }
    let lowest = (0..n).min_by(|&i, &j| lowest_first(points[i], points[j])).unwrap_or(0);
    hull.clear();
    if left {
        hull.extend_from_slice(&points[lowest..]);
        hull.extend_from_slice(&points[..lowest]);
    } else {
        hull.extend(points[..=lowest].iter().rev());
        hull.extend(points[lowest + 1..].iter().rev());
    }
    true
}

/// How clearly, as a share of the square of the largest coordinate, a corner
/// must turn for [`convex_in_order`] to trust its turn: far beyond the rounding
/// of `cross`, so that the chain would find every turn as it does.
const CLEAR_TURN: f64 = 1e-9;

/// A hull edge that takes tiles, with the offsets from a tile's first pixel
/// to its pixel centres nearest the edge, across and down.
struct Cut {
    edge: Edge,
    nearest: [f64; 2],
}

impl Cut {
    fn new(edge: Edge) -> Cut {
        let n = edge.1;
        Cut { edge, nearest: [nearest_offset(EYE_TILE_WIDTH, n[0]), nearest_offset(EYE_TILE_HEIGHT, n[1])] }
    }

    /// How far beyond the edge, along its normal, tile column `x`'s pixel
    /// centres nearest it lie: the part of that distance across. A tile lies
    /// beyond the edge when this and its `row_term` add up to more than the margin.
    fn column_term(&self, x: usize) -> f64 {
        let (a, n) = self.edge;
        (f64::from(x as u32 * EYE_TILE_WIDTH) + self.nearest[0] - a[0]) * n[0]
    }

    /// The part down of the distance beyond the edge of tile row `y`'s pixel
    /// centres nearest it.
    fn row_term(&self, y: usize) -> f64 {
        let (a, n) = self.edge;
        (f64::from(y as u32 * EYE_TILE_HEIGHT) + self.nearest[1] - a[1]) * n[1]
    }
}

/// From a tile's first pixel to its pixel centre nearest the side that a
/// normal's component `toward` faces away from, `side` pixels a tile: the
/// first centre when the component is positive, else the last.
fn nearest_offset(side: u32, toward: f64) -> f64 {
    if toward > 0.0 { 0.5 } else { f64::from(side) - 0.5 }
}

/// `d`'s bits as a key that sorts as `f32::total_cmp` orders `d`.
fn sortable_bits(d: f32) -> u32 {
    let bits = d.to_bits();
    if bits >> 31 == 1 { !bits } else { bits | 1 << 31 }
}

fn corners(lo: Vec3, hi: Vec3) -> [Vec3; 8] {
    std::array::from_fn(|k| Vec3::new([lo.x, hi.x][k & 1], [lo.y, hi.y][(k >> 1) & 1], [lo.z, hi.z][(k >> 2) & 1]))
}

#[cfg(test)]
mod tests;
