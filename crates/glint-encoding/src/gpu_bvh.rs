//! The BVH as the kernels read it. Record `i` stands for node `i` of the
//! binary tree (children adjacent, as the builder lays them out):
//!
//! - an interior record holds both children's boxes, quantised to 8 bits per
//!   coordinate on a grid over the node's own box, and the index of its first
//!   child with a flag per child that says whether it is a leaf;
//! - a leaf record holds its range of the packed primitives.
//!
//! A node's grid is not stored with it: its origin is the low corner of the node's
//! box as its parent's record decodes it, its cells the smallest power of two
//! that spans the box in 254 steps (one to spare for rounding outwards). The
//! kernel derives the grid of the child it descends into from the box it has
//! just tested; only a node it returns to from the stack (and the root) needs
//! its grid loaded, from [`GpuBvh::grids`].
//!
//! Why: on a software rasteriser every load whose address differs
//! between SIMD lanes is done lane by lane and component by component, so a
//! node visit costs what it loads. Two f32 child boxes and two child indices
//! are 14 components; a record is 4. Boxes are rounded outwards, so a ray that
//! enters a child's true box always enters its quantised one and traversal finds
//! exactly the hits it found before.

use bytemuck::{Pod, Zeroable};
use glam::Vec3;
use glint_scene::bvh::{Bvh, Node};
use glint_scene::validate::Invalid;

/// In a reference to a BVH record: a leaf. In `GpuNode::children`: the first
/// child is a leaf. The kernels get it and its siblings through the prelude
/// (gpu_types.rs).
pub const LEAF: u32 = 1 << 31;
/// In `GpuNode::children`: the second child is a leaf.
pub const RIGHT_LEAF: u32 = 1 << 30;
/// The end of a traversal.
pub const NO_NODE: u32 = u32::MAX;

/// The bits of a child reference that index a record. [`LEAF`] marks a
/// reference to a leaf (on the kernel's stack and in [`GpuBvh::root`]); in an
/// interior record's `children` it marks the first child as a leaf and
/// [`RIGHT_LEAF`] the second.
const INDEX: u32 = RIGHT_LEAF - 1;
/// The most records a tree can have: every child index must fit [`INDEX`].
pub const MAX_NODES: usize = INDEX as usize + 1;
/// The finest cell: 2^-100 (biased exponent 27), far above the subnormals a GPU
/// may flush to zero, so host and kernel derive the same grids.
const MIN_EXPONENT: u32 = 27;

/// One record, 16 bytes, mirrored by `GpuNode` in shaders/types.wgsl.
/// Interior: byte `2c` (low corner) and `2c + 1` (high corner) of `quantized[a]`
/// are child `c`'s box on axis `a` in grid cells; `children` is the first
/// child's index, with [`LEAF`] and [`RIGHT_LEAF`]. Leaf: `quantized[0]` is the
/// first primitive and `quantized[1]` the count.
#[repr(C)]
#[derive(Debug, Clone, Copy, PartialEq, Pod, Zeroable)]
pub struct GpuNode {
    pub quantized: [u32; 3],
    pub children: u32,
}

/// A node's grid, 16 bytes, mirrored by `GpuGrid` in shaders/types.wgsl: the
/// origin and, in byte `a` of `exponents`, the biased exponent of the cell size
/// on axis `a`.
#[repr(C)]
#[derive(Debug, Clone, Copy, PartialEq, Pod, Zeroable)]
pub struct GpuGrid {
    pub origin: [f32; 3],
    pub exponents: u32,
}

/// The tree in the kernel's layout.
#[derive(Debug, Clone, PartialEq)]
pub struct GpuBvh {
    pub nodes: Vec<GpuNode>,
    /// The grid of every interior record (unused for leaves).
    pub grids: Vec<GpuGrid>,
    /// Where traversal starts: record 0, flagged [`LEAF`] when the whole tree is one leaf.
    pub root: u32,
}

impl GpuGrid {
    /// The grid over box [lo, hi] (as decoded by the parent).
    fn over(lo: Vec3, hi: Vec3) -> Self {
        let e = (hi - lo).to_array().map(cell_exponent);
        Self { origin: lo.into(), exponents: e[0] | e[1] << 8 | e[2] << 16 }
    }

    fn cell(&self, axis: usize) -> f32 {
        f32::from_bits(((self.exponents >> (8 * axis)) & 0xff) << 23)
    }

    /// Grid coordinate `q` on `axis` in world space, as the kernel computes it:
    /// `q·cell` is exact (a byte times a power of two), so only the sum rounds,
    /// once, with or without a fused multiply-add.
    fn decode(&self, axis: usize, q: u32) -> f32 {
        self.origin[axis] + q as f32 * self.cell(axis)
    }

    /// The box of bytes `byte` (low corner) and `byte + 1` (high) of `quantized`.
    fn decode_box(&self, quantized: [u32; 3], byte: u32) -> (Vec3, Vec3) {
        let corner = |b: u32| Vec3::from_array(std::array::from_fn(|a| self.decode(a, (quantized[a] >> (8 * b)) & 0xff)));
        (corner(byte), corner(byte + 1))
    }

    /// The grid cells of [lo, hi] on `axis`: the largest coordinate that decodes
    /// to at most `lo` and the smallest that decodes to at least `hi`. Any box
    /// inside the grid's own box fits: 0 decodes to the origin and 255 past its end.
    fn quantize(&self, axis: usize, lo: f32, hi: f32) -> (u32, u32) {
        let cell = self.cell(axis);
        let origin = self.origin[axis];
        let mut q_lo = ((lo - origin) / cell).floor().clamp(0.0, 255.0) as u32;
        while q_lo > 0 && self.decode(axis, q_lo) > lo {
            q_lo -= 1;
        }
        let mut q_hi = ((hi - origin) / cell).ceil().clamp(0.0, 255.0) as u32;
        while q_hi < 255 && self.decode(axis, q_hi) < hi {
            q_hi += 1;
        }
        (q_lo, q_hi)
    }
}

/// The biased exponent of the smallest power of two `c` with 254·c ≥ `extent`,
/// from the bits alone, as `derived_grid` in bvh_nodes.wgsl does: for extent m·2^E
/// (1 ≤ m < 2) that is 2^(E−7) when m ≤ 254/128, else 2^(E−6).
fn cell_exponent(extent: f32) -> u32 {
    let bits = extent.to_bits() & 0x7fff_ffff;
    let e = (bits >> 23) + u32::from(bits & 0x7f_ffff > 0x7e_0000);
    e.clamp(MIN_EXPONENT + 7, 254 + 7) - 7
}

impl GpuBvh {
    /// `bvh` in the kernel's layout (see the module documentation), once it
    /// is known to fit it.
    pub fn encode(bvh: &Bvh) -> Result<GpuBvh, Invalid> {
        bvh.validate()?;
        if bvh.nodes.len() > MAX_NODES {
            return Err(Invalid::TooMany { what: "BVH nodes", count: bvh.nodes.len(), max: MAX_NODES });
        }
        let mut out = GpuBvh {
            nodes: vec![GpuNode::zeroed(); bvh.nodes.len()],
            grids: vec![GpuGrid::zeroed(); bvh.nodes.len()],
            root: 0,
        };
        let root = &bvh.nodes[0];
        if root.is_leaf() {
            // An inverted box (the empty scene's) holds nothing: count 0 never
            // reads the padding primitive.
            let empty = !Vec3::from(root.min).cmple(Vec3::from(root.max)).all();
            out.nodes[0] = leaf(root.left_or_first, if empty { 0 } else { root.count });
            out.root = LEAF;
        } else {
            place(bvh, 0, GpuGrid::over(root.min.into(), root.max.into()), &mut out);
        }
        Ok(out)
    }
}

/// Writes `bvh`'s interior node `i` over `grid` and, depth first, its subtree.
fn place(bvh: &Bvh, i: usize, grid: GpuGrid, out: &mut GpuBvh) {
    out.grids[i] = grid;
    let first = bvh.nodes[i].left_or_first;
    let mut record = GpuNode { quantized: [0; 3], children: first };
    for (c, flag) in [LEAF, RIGHT_LEAF].into_iter().enumerate() {
        let index = first as usize + c;
        let child: &Node = &bvh.nodes[index];
        for a in 0..3 {
            let (q_lo, q_hi) = grid.quantize(a, child.min[a], child.max[a]);
            record.quantized[a] |= (q_lo | q_hi << 8) << (16 * c);
        }
        if child.is_leaf() {
            record.children |= flag;
            out.nodes[index] = leaf(child.left_or_first, child.count);
        } else {
            let (lo, hi) = grid.decode_box(record.quantized, 2 * c as u32);
            place(bvh, index, GpuGrid::over(lo, hi), out);
        }
    }
    out.nodes[i] = record;
}

fn leaf(first: u32, count: u32) -> GpuNode {
    GpuNode { quantized: [first, count, 0], children: 0 }
}

#[cfg(test)]
mod tests {
    use super::*;
    use glint_scene::bvh::MAX_DEPTH;
    use glint_scene::test_rng::Rng;

    /// A ray that missed both children, as NEEDS_POP in the kernel.
    const NEEDS_POP: u32 = u32::MAX - 1;

    fn sphere_bounds(spheres: &[(Vec3, f32)]) -> Vec<(Vec3, Vec3)> {
        spheres.iter().map(|&(c, r)| (c - r, c + r)).collect()
    }

    fn random_spheres(rng: &mut Rng, n: usize, spread: f32) -> Vec<(Vec3, f32)> {
        (0..n).map(|_| (rng.vec3(-spread, spread), rng.range(0.01, 3.0) * spread / 100.0)).collect()
    }

    fn contains(outer: (Vec3, Vec3), inner: (Vec3, Vec3)) -> bool {
        outer.0.cmple(inner.0).all() && outer.1.cmpge(inner.1).all()
    }

    /// What the kernel sees of interior record `i` over `grid`: both children's
    /// references (flagged as on the stack) and decoded boxes.
    fn children(gpu: &GpuBvh, i: u32, grid: &GpuGrid) -> [(u32, (Vec3, Vec3)); 2] {
        let n = gpu.nodes[i as usize];
        let first = n.children & INDEX;
        [(first, n.children & LEAF != 0), (first + 1, n.children & RIGHT_LEAF != 0)]
            .map(|(index, is_leaf)| if is_leaf { index | LEAF } else { index })
            .into_iter()
            .zip([0, 2].map(|byte| grid.decode_box(n.quantized, byte)))
            .collect::<Vec<_>>()
            .try_into()
            .unwrap()
    }

    fn leaf_range(gpu: &GpuBvh, reference: u32) -> std::ops::Range<u32> {
        let n = gpu.nodes[(reference & !LEAF) as usize];
        n.quantized[0]..n.quantized[0] + n.quantized[1]
    }

    /// Walks the tree as the kernel does, deriving each child's grid from its
    /// decoded box: that grid is the one stored for it, every primitive is in
    /// exactly one leaf, and every decoded box contains its primitives.
    fn check(bvh: &Bvh, bounds: &[(Vec3, Vec3)]) {
        let gpu = GpuBvh::encode(&bvh).unwrap();
        let mut seen = vec![0u32; bounds.len()];
        let mut stack = vec![(gpu.root, gpu.grids[0], None)];
        while let Some((reference, grid, decoded)) = stack.pop() {
            if reference & LEAF != 0 {
                for p in leaf_range(&gpu, reference) {
                    let prim = bvh.order[p as usize] as usize;
                    seen[prim] += 1;
                    if let Some(decoded) = decoded {
                        assert!(contains(decoded, bounds[prim]), "{decoded:?} misses {:?}", bounds[prim]);
                    }
                }
                continue;
            }
            assert_eq!(grid, gpu.grids[reference as usize], "derived and stored grids differ");
            for (child, (lo, hi)) in children(&gpu, reference, &grid) {
                stack.push((child, GpuGrid::over(lo, hi), Some((lo, hi))));
            }
        }
        assert!(seen.iter().all(|&s| s == 1), "a primitive is in no leaf or in several");
    }

    #[test]
    fn quantised_boxes_contain_their_primitives_at_every_scale() {
        let mut rng = Rng(1);
        for spread in [1e-3, 1.0, 1e3, 1e6] {
            let spheres = random_spheres(&mut rng, 2000, spread);
            let bounds = sphere_bounds(&spheres);
            check(&Bvh::build(&bounds), &bounds);
        }
        // Far from the origin, where fine cells vanish in the coordinates' rounding.
        let offset = Vec3::splat(3.0e5);
        let spheres: Vec<_> = random_spheres(&mut rng, 500, 1.0).into_iter().map(|(c, r)| (c + offset, r)).collect();
        let bounds = sphere_bounds(&spheres);
        check(&Bvh::build(&bounds), &bounds);
    }

    #[test]
    fn flat_and_identical_boxes_are_kept() {
        // Axis-aligned triangles have no thickness; duplicates share one box.
        let mut bounds: Vec<(Vec3, Vec3)> =
            (0..100).map(|i| (Vec3::new(i as f32, 0.0, 2.0), Vec3::new(i as f32 + 0.5, 1.0, 2.0))).collect();
        bounds.extend(std::iter::repeat_n((Vec3::splat(7.0), Vec3::splat(7.0)), 50));
        check(&Bvh::build(&bounds), &bounds);
    }

    #[test]
    fn quantisation_is_tight() {
        // A cell is at most 1/127 of the parent's decoded extent and boxes grow by
        // under two cells per side; the decoded extent itself grows level by
        // level, so compare with the parent's decoded box.
        let mut rng = Rng(2);
        let bounds = sphere_bounds(&random_spheres(&mut rng, 1000, 10.0));
        let bvh = Bvh::build(&bounds);
        let gpu = GpuBvh::encode(&bvh).unwrap();
        let mut stack = vec![(0u32, gpu.grids[0])];
        while let Some((i, grid)) = stack.pop() {
            let first = bvh.nodes[i as usize].left_or_first as usize;
            let (origin, extent) = (Vec3::from(grid.origin), Vec3::from_array(std::array::from_fn(|a| 254.0 * grid.cell(a))));
            for (c, (child, (lo, hi))) in children(&gpu, i, &grid).into_iter().enumerate() {
                let exact = &bvh.nodes[first + c];
                let slack = extent * (2.0 / 254.0) + origin.abs() * 1e-6;
                assert!((Vec3::from(exact.min) - lo).cmple(slack).all() && (hi - Vec3::from(exact.max)).cmple(slack).all());
                if child & LEAF == 0 {
                    stack.push((child, GpuGrid::over(lo, hi)));
                }
            }
        }
    }

    #[test]
    fn cell_exponents_are_the_smallest_that_span_254_cells() {
        let mut rng = Rng(3);
        for _ in 0..10_000 {
            let extent = 10f32.powf(rng.range(-20.0, 20.0));
            let e = cell_exponent(extent);
            let cell = |e: u32| f32::from_bits(e << 23);
            assert!(254.0 * cell(e) >= extent, "{extent}: 2^{} too small", e as i32 - 127);
            assert!(254.0 * cell(e - 1) < extent, "{extent}: 2^{} not the smallest", e as i32 - 127);
        }
        assert_eq!(cell_exponent(0.0), MIN_EXPONENT);
        assert_eq!(cell_exponent(f32::MIN_POSITIVE / 4.0), MIN_EXPONENT);
    }

    #[test]
    fn a_lone_leaf_is_the_root() {
        let bounds = vec![(Vec3::ZERO, Vec3::ONE); 3];
        let gpu = GpuBvh::encode(&Bvh::build(&bounds)).unwrap();
        assert_eq!(gpu.root, LEAF);
        assert_eq!(leaf_range(&gpu, gpu.root), 0..3);
        // The brute-force tree: one leaf however many primitives.
        let many = vec![(Vec3::ZERO, Vec3::ONE); 1000];
        let gpu = GpuBvh::encode(&Bvh::single_leaf(&many)).unwrap();
        assert_eq!(leaf_range(&gpu, gpu.root), 0..1000);
    }

    #[test]
    fn an_empty_scene_has_an_empty_leaf() {
        let gpu = GpuBvh::encode(&Bvh::build(&[])).unwrap();
        assert_eq!(gpu.root, LEAF);
        assert_eq!(leaf_range(&gpu, gpu.root), 0..0);
    }

    #[test]
    fn non_finite_bounds_do_not_panic() {
        let bounds = vec![
            (Vec3::splat(f32::NEG_INFINITY), Vec3::splat(f32::INFINITY)),
            (Vec3::splat(f32::NAN), Vec3::splat(f32::NAN)),
            (Vec3::ZERO, Vec3::ONE),
            (Vec3::ZERO, Vec3::ONE),
            (Vec3::ZERO, Vec3::ONE),
        ];
        GpuBvh::encode(&Bvh::build(&bounds)).unwrap();
    }

    /// Nearest positive root of |o + t·d − c|² = r² for unit `d`.
    fn hit_sphere(origin: Vec3, dir: Vec3, center: Vec3, radius: f32) -> Option<f32> {
        let oc = origin - center;
        let b = oc.dot(dir);
        let disc = b * b - (oc.length_squared() - radius * radius);
        if disc < 0.0 {
            return None;
        }
        let s = disc.sqrt();
        [-b - s, -b + s].into_iter().find(|&t| t > 1e-4)
    }

    /// Entry distance into the box (clamped to 0), as `slab_entry` in bvh.wgsl.
    fn box_entry((lo, hi): (Vec3, Vec3), origin: Vec3, inv_dir: Vec3, t_max: f32) -> Option<f32> {
        let t0 = (lo - origin) * inv_dir;
        let t1 = (hi - origin) * inv_dir;
        let near = t0.min(t1).max_element();
        let far = t0.max(t1).min_element();
        (near <= far && far >= 0.0 && near <= t_max).then_some(near.max(0.0))
    }

    /// Closest hit as `traverse` in bvh.wgsl finds it, with the same fixed
    /// stack: down through interior records nearest child first, the far one
    /// pushed with its entry distance, the near one's grid derived from its box,
    /// until a leaf or a miss of both children; then the leaf's primitives and a
    /// pop, which skips entries behind the current hit and loads the grid of the
    /// node it returns to; equal distances go to the lower primitive. Returns
    /// (t, input primitive index) and the most stack entries used.
    fn closest_hit(bvh: &Bvh, spheres: &[(Vec3, f32)], origin: Vec3, dir: Vec3) -> (Option<(f32, u32)>, usize) {
        let gpu = GpuBvh::encode(&bvh).unwrap();
        let inv_dir = dir.recip();
        let mut best: Option<(f32, u32)> = None;
        let t_max = |best: &Option<(f32, u32)>| best.map_or(f32::INFINITY, |b| b.0);
        let mut stack = [(0u32, 0f32); MAX_DEPTH];
        let (mut top, mut most) = (0, 0);
        let mut index = gpu.root;
        let mut grid = gpu.grids[0];
        loop {
            while index & LEAF == 0 {
                let [(left, left_box), (right, right_box)] = children(&gpu, index, &grid);
                let (t_left, t_right) = (
                    box_entry(left_box, origin, inv_dir, t_max(&best)),
                    box_entry(right_box, origin, inv_dir, t_max(&best)),
                );
                let near_first = t_left.unwrap_or(f32::INFINITY) <= t_right.unwrap_or(f32::INFINITY);
                let ((near, near_box), far) = if near_first { ((left, left_box), right) } else { ((right, right_box), left) };
                if t_left.is_none() && t_right.is_none() {
                    index = NEEDS_POP;
                    break;
                }
                if let (Some(a), Some(b)) = (t_left, t_right) {
                    stack[top] = (far, a.max(b));
                    top += 1;
                    most = most.max(top);
                }
                index = near;
                grid = GpuGrid::over(near_box.0, near_box.1);
            }
            if index == NO_NODE {
                return (best, most);
            }
            let leaf = if index == NEEDS_POP { 0..0 } else { leaf_range(&gpu, index) };
            for p in leaf {
                let p = bvh.order[p as usize];
                let (center, radius) = spheres[p as usize];
                let Some(t) = hit_sphere(origin, dir, center, radius) else { continue };
                if best.is_none_or(|(best_t, best_p)| t < best_t || (t == best_t && p < best_p)) {
                    best = Some((t, p));
                }
            }
            index = pop(&gpu, &stack, &mut top, &mut grid, t_max(&best));
        }
    }

    fn pop(gpu: &GpuBvh, stack: &[(u32, f32)], top: &mut usize, grid: &mut GpuGrid, t_max: f32) -> u32 {
        while *top > 0 {
            *top -= 1;
            let (reference, t) = stack[*top];
            if t <= t_max {
                if reference & LEAF == 0 {
                    *grid = gpu.grids[reference as usize];
                }
                return reference;
            }
        }
        NO_NODE
    }

    fn brute_force(spheres: &[(Vec3, f32)], origin: Vec3, dir: Vec3) -> Option<(f32, u32)> {
        spheres
            .iter()
            .enumerate()
            .filter_map(|(i, &(c, r))| hit_sphere(origin, dir, c, r).map(|t| (t, i as u32)))
            .min_by(|a, b| a.0.total_cmp(&b.0))
    }

    #[test]
    fn closest_hit_matches_brute_force() {
        let mut rng = Rng(42);
        let spheres: Vec<(Vec3, f32)> = (0..3000).map(|_| (rng.vec3(0.0, 100.0), rng.range(0.2, 3.0))).collect();
        let bvh = Bvh::build(&sphere_bounds(&spheres));
        let mut hits = 0;
        for _ in 0..4000 {
            let origin = rng.vec3(-20.0, 120.0);
            let dir = rng.unit();
            let expected = brute_force(&spheres, origin, dir);
            assert_eq!(closest_hit(&bvh, &spheres, origin, dir).0, expected, "ray {origin} {dir}");
            hits += expected.is_some() as usize;
        }
        assert!(hits > 1000, "only {hits} rays hit: the test would prove little");
    }

    #[test]
    fn deepest_tree_fits_the_gpu_stack() {
        // SAH peels the biggest sphere off such a series one at a time; only the
        // depth limit keeps the chain short.
        let spheres: Vec<(Vec3, f32)> = (0..1000).map(|i| (Vec3::X * 1.08f32.powi(i), 0.5)).collect();
        let bvh = Bvh::build(&sphere_bounds(&spheres));
        assert_eq!(bvh.depth(), MAX_DEPTH);
        // A ray down the axis enters every box, so it reaches the nearest (deepest)
        // leaf with a far sibling pushed at every level: a full stack.
        let origin = Vec3::new(-1.0, 0.01, 0.02);
        let (hit, most) = closest_hit(&bvh, &spheres, origin, Vec3::X);
        assert_eq!(most, MAX_DEPTH);
        assert_eq!(hit, brute_force(&spheres, origin, Vec3::X));
        assert_eq!(hit.map(|(_, p)| p), Some(0));
    }
}
