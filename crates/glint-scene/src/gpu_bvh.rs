//! The BVH as the trace kernel reads it: one [`GpuNode`] per interior node of
//! the binary tree, holding both children's boxes, quantised to 8 bits per
//! coordinate on a grid over the node's own box, and references to them; a leaf
//! is a reference that names its primitives, so it costs no record and no load.
//!
//! Why quantise: on a software rasteriser (lavapipe) every load whose address
//! differs between SIMD lanes is done lane by lane, component by component, so
//! a node visit costs what it loads. Two f32 child boxes and two child indices
//! are 14 components; this layout needs 9 (grid origin and cell sizes 4, boxes 3,
//! children 2). Boxes are rounded outwards, so a ray that enters a child's true
//! box always enters its quantised one and traversal finds exactly the hits it
//! found before.

use bytemuck::{Pod, Zeroable};
use glam::Vec3;

use crate::bvh::{Bvh, Node};

/// A child reference with this bit set is a leaf: primitives
/// `first .. first + count` with `first` in bits 0–27 and `count − 1` in bits 28–30.
pub const LEAF: u32 = 1 << 31;
/// The reference of a missing child (an empty scene's root has none).
pub const NO_CHILD: u32 = u32::MAX;
/// The most primitives one leaf reference can name.
pub const MAX_LEAF_REF: usize = 8;
const FIRST_BITS: u32 = 28;

/// One interior node, 48 bytes, mirrored by `GpuNode` in shaders/types.wgsl.
///
/// Child `c`'s box on axis `a` is `origin[a] + q·cell[a]` for `q` from byte
/// `2c` (low corner) to byte `2c + 1` (high corner) of `quantized[a]`, where
/// `cell[a] = 2^(e − 127)` and `e` is byte `a` of `exponents`.
#[repr(C)]
#[derive(Debug, Clone, Copy, PartialEq, Pod, Zeroable)]
pub struct GpuNode {
    pub origin: [f32; 3],
    pub exponents: u32,
    pub quantized: [u32; 3],
    pub left: u32,
    pub right: u32,
    pub _pad: [u32; 3],
}

impl GpuNode {
    /// Child `c`'s box as the kernel decodes it.
    pub fn child_box(&self, c: usize) -> (Vec3, Vec3) {
        let corner = |byte: usize| {
            Vec3::from_array(std::array::from_fn(|a| {
                let q = (self.quantized[a] >> (8 * byte)) & 0xff;
                decode(self.origin[a], q, cell(self.exponents >> (8 * a)))
            }))
        };
        (corner(2 * c), corner(2 * c + 1))
    }

    pub fn children(&self) -> [u32; 2] {
        [self.left, self.right]
    }
}

/// The primitives a leaf reference names, as a range of the packed primitives.
pub fn leaf_range(reference: u32) -> std::ops::Range<u32> {
    let first = reference & ((1 << FIRST_BITS) - 1);
    let count = ((reference >> FIRST_BITS) & 0x7) + 1;
    first..first + count
}

fn leaf_ref(first: u32, count: u32) -> u32 {
    debug_assert!((1..=MAX_LEAF_REF as u32).contains(&count));
    assert!(first < 1 << FIRST_BITS, "too many primitives for a leaf reference: {first}");
    LEAF | (count - 1) << FIRST_BITS | first
}

/// The cell size of a biased exponent byte.
fn cell(exponent_byte: u32) -> f32 {
    f32::from_bits((exponent_byte & 0xff) << 23)
}

/// A grid coordinate back in world space, as the kernel computes it: `q·cell` is
/// exact (a byte times a power of two), so only the sum rounds, once, with or
/// without a fused multiply-add.
fn decode(origin: f32, q: u32, cell: f32) -> f32 {
    origin + q as f32 * cell
}

/// The biased exponent of the smallest power-of-two cell that spans `extent` in
/// 254 cells (one to spare for rounding outwards), within the normal floats.
fn exponent_for(extent: f32) -> u32 {
    if !(extent > 0.0) {
        return if extent == 0.0 { 1 } else { 254 };
    }
    let guess = ((extent / 254.0).log2().ceil() + 127.0).clamp(1.0, 254.0) as u32;
    let spans = |e: u32| extent <= 254.0 * cell(e);
    let mut e = guess;
    while e < 254 && !spans(e) {
        e += 1;
    }
    while e > 1 && spans(e - 1) {
        e -= 1;
    }
    e
}

/// The largest grid coordinate whose decoded value is at most `lo`, and the
/// smallest whose decoded value is at least `hi`, clamped to a byte; `None`
/// when the grid cannot enclose [lo, hi].
fn quantize_axis(origin: f32, cell: f32, lo: f32, hi: f32) -> Option<(u32, u32)> {
    let mut q_lo = ((lo - origin) / cell).floor().clamp(0.0, 255.0) as u32;
    while q_lo > 0 && decode(origin, q_lo, cell) > lo {
        q_lo -= 1;
    }
    let mut q_hi = ((hi - origin) / cell).ceil().clamp(0.0, 255.0) as u32;
    while q_hi < 255 && decode(origin, q_hi, cell) < hi {
        q_hi += 1;
    }
    (decode(origin, q_lo, cell) <= lo && decode(origin, q_hi, cell) >= hi).then_some((q_lo, q_hi))
}

/// A node over two children given by their references and boxes (`None`: no child).
fn node(children: [(u32, Option<(Vec3, Vec3)>); 2]) -> GpuNode {
    let (lo, hi) = children
        .iter()
        .filter_map(|(_, b)| *b)
        .fold((Vec3::INFINITY, Vec3::NEG_INFINITY), |(lo, hi), (a, b)| (lo.min(a), hi.max(b)));
    let mut n = GpuNode { left: children[0].0, right: children[1].0, ..Zeroable::zeroed() };
    for a in 0..3 {
        let origin = if lo[a].is_finite() { lo[a] } else { 0.0 };
        // Far from the origin a fine grid's steps vanish in the coordinates'
        // rounding: coarser cells until every child is enclosed (non-finite
        // boxes never are, and keep the coarsest).
        let mut e = exponent_for(hi[a] - origin);
        let quantized = loop {
            let q = children.map(|(_, b)| b.map(|(clo, chi)| quantize_axis(origin, cell(e), clo[a], chi[a])));
            if e == 254 || q.iter().all(|c| !matches!(c, Some(None))) {
                break q;
            }
            e += 1;
        };
        n.origin[a] = origin;
        n.exponents |= e << (8 * a);
        for (c, q) in quantized.into_iter().enumerate() {
            let (q_lo, q_hi) = q.flatten().unwrap_or((0, 255));
            n.quantized[a] |= (q_lo | q_hi << 8) << (16 * c);
        }
    }
    n
}

fn bounds(node: &Node) -> Option<(Vec3, Vec3)> {
    let (lo, hi) = (Vec3::from(node.min), Vec3::from(node.max));
    // An inverted box (the empty scene's) holds nothing.
    lo.cmple(hi).all().then_some((lo, hi))
}

impl Bvh {
    /// The tree in the kernel's layout: `[0]` is the root. A leaf of more than
    /// [`MAX_LEAF_REF`] primitives (the brute-force tree's single leaf) becomes a
    /// balanced subtree of such leaves whose boxes are all the leaf's box, so a
    /// ray that enters it still tests every primitive.
    pub fn gpu_nodes(&self) -> Vec<GpuNode> {
        let mut out = vec![GpuNode::zeroed()];
        let root = &self.nodes[0];
        let record = match bounds(root) {
            _ if !root.is_leaf() => self.interior(root, &mut out),
            Some(b) => node([(self.leaf(root.left_or_first, root.count, root, &mut out), Some(b)), (NO_CHILD, None)]),
            None => node([(NO_CHILD, None), (NO_CHILD, None)]),
        };
        out[0] = record;
        out
    }

    /// The record of binary interior node `n`, its descendants appended to `out`.
    fn interior(&self, n: &Node, out: &mut Vec<GpuNode>) -> GpuNode {
        let left = n.left_or_first as usize;
        let children = [left, left + 1].map(|i| {
            let child = &self.nodes[i];
            (self.reference(child, out), bounds(child))
        });
        node(children)
    }

    fn reference(&self, child: &Node, out: &mut Vec<GpuNode>) -> u32 {
        if child.is_leaf() {
            return self.leaf(child.left_or_first, child.count, child, out);
        }
        let slot = out.len();
        out.push(GpuNode::zeroed());
        let record = self.interior(child, out);
        out[slot] = record;
        slot as u32
    }

    /// A reference to primitives `first .. first + count` of leaf `leaf`.
    fn leaf(&self, first: u32, count: u32, leaf: &Node, out: &mut Vec<GpuNode>) -> u32 {
        if count as usize <= MAX_LEAF_REF {
            return leaf_ref(first, count);
        }
        let half = count / 2;
        let slot = out.len();
        out.push(GpuNode::zeroed());
        let left = self.leaf(first, half, leaf, out);
        let right = self.leaf(first + half, count - half, leaf, out);
        out[slot] = node([(left, bounds(leaf)), (right, bounds(leaf))]);
        slot as u32
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::bvh::MAX_DEPTH;
    use crate::test_rng::Rng;

    fn sphere_bounds(spheres: &[(Vec3, f32)]) -> Vec<(Vec3, Vec3)> {
        spheres.iter().map(|&(c, r)| (c - r, c + r)).collect()
    }

    fn random_spheres(rng: &mut Rng, n: usize, spread: f32) -> Vec<(Vec3, f32)> {
        (0..n).map(|_| (rng.vec3(-spread, spread), rng.range(0.01, 3.0) * spread / 100.0)).collect()
    }

    fn contains(outer: (Vec3, Vec3), inner: (Vec3, Vec3)) -> bool {
        outer.0.cmple(inner.0).all() && outer.1.cmpge(inner.1).all()
    }

    /// Walks the GPU tree: every primitive is named by exactly one leaf
    /// reference, and every decoded child box contains its primitives.
    fn check(bvh: &Bvh, bounds: &[(Vec3, Vec3)]) {
        let nodes = bvh.gpu_nodes();
        let mut seen = vec![0u32; bounds.len()];
        let mut reached = vec![false; nodes.len()];
        let mut stack = vec![0u32];
        while let Some(i) = stack.pop() {
            assert!(!std::mem::replace(&mut reached[i as usize], true), "node {i} reached twice");
            let n = &nodes[i as usize];
            for (c, child) in n.children().into_iter().enumerate() {
                if child == NO_CHILD {
                    continue;
                }
                let decoded = n.child_box(c);
                if child & LEAF == 0 {
                    stack.push(child);
                    continue;
                }
                for p in leaf_range(child) {
                    let prim = bvh.order[p as usize] as usize;
                    seen[prim] += 1;
                    assert!(contains(decoded, bounds[prim]), "node {i} child {c} {decoded:?} misses {:?}", bounds[prim]);
                }
            }
        }
        assert!(seen.iter().all(|&s| s == 1), "a primitive is named by no leaf or by several");
        assert!(reached.iter().all(|&r| r), "unreachable nodes");
    }

    #[test]
    fn quantised_boxes_contain_their_primitives_at_every_scale() {
        let mut rng = Rng(1);
        for spread in [1e-3, 1.0, 1e3, 1e6] {
            let spheres = random_spheres(&mut rng, 2000, spread);
            let bounds = sphere_bounds(&spheres);
            check(&Bvh::build(&bounds), &bounds);
        }
        // Far from the origin, where the grid's cells are coarse against the
        // coordinates' own precision.
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
        // A cell is at most 1/127 of the parent's extent; boxes grow by under two
        // cells per side.
        let mut rng = Rng(2);
        let bounds = sphere_bounds(&random_spheres(&mut rng, 1000, 10.0));
        let bvh = Bvh::build(&bounds);
        let nodes = bvh.gpu_nodes();
        let mut stack = vec![(0u32, bvh.nodes[0])];
        while let Some((g, n)) = stack.pop() {
            let parent = (Vec3::from(n.min), Vec3::from(n.max));
            let slack = (parent.1 - parent.0) * (2.0 / 127.0);
            let left = n.left_or_first as usize;
            for (c, child) in [bvh.nodes[left], bvh.nodes[left + 1]].into_iter().enumerate() {
                let (lo, hi) = nodes[g as usize].child_box(c);
                assert!((Vec3::from(child.min) - lo).cmple(slack).all() && (hi - Vec3::from(child.max)).cmple(slack).all());
                let reference = nodes[g as usize].children()[c];
                if reference & LEAF == 0 {
                    stack.push((reference, child));
                }
            }
        }
    }

    #[test]
    fn a_big_leaf_becomes_a_subtree_of_small_ones() {
        let bounds: Vec<(Vec3, Vec3)> = (0..1000).map(|i| (Vec3::splat(i as f32), Vec3::splat(i as f32 + 1.0))).collect();
        let bvh = Bvh::single_leaf(&bounds);
        check(&bvh, &bounds);
        assert!(bvh.gpu_nodes().len() > 1000 / MAX_LEAF_REF);
    }

    #[test]
    fn an_empty_scene_has_no_children() {
        let nodes = Bvh::build(&[]).gpu_nodes();
        assert_eq!(nodes.len(), 1);
        assert_eq!(nodes[0].children(), [NO_CHILD, NO_CHILD]);
    }

    #[test]
    fn non_finite_bounds_do_not_panic() {
        let bounds = vec![
            (Vec3::splat(f32::NEG_INFINITY), Vec3::splat(f32::INFINITY)),
            (Vec3::splat(f32::NAN), Vec3::splat(f32::NAN)),
            (Vec3::ZERO, Vec3::ONE),
        ];
        Bvh::build(&bounds).gpu_nodes();
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

    /// Entry distance into the box (clamped to 0), as `box_entry` in bvh.wgsl.
    fn box_entry((lo, hi): (Vec3, Vec3), origin: Vec3, inv_dir: Vec3, t_max: f32) -> Option<f32> {
        let t0 = (lo - origin) * inv_dir;
        let t1 = (hi - origin) * inv_dir;
        let near = t0.min(t1).max_element();
        let far = t0.max(t1).min_element();
        (near <= far && far >= 0.0 && near <= t_max).then_some(near.max(0.0))
    }

    /// Closest hit as `traverse` in bvh.wgsl finds it, with the same fixed
    /// stack: down through interior nodes nearest child first, the far one
    /// pushed with its entry distance, then a leaf's primitives; pops skip
    /// entries behind the current hit; equal distances go to the lower
    /// primitive. Returns (t, input primitive index) and the most stack entries used.
    fn closest_hit(bvh: &Bvh, spheres: &[(Vec3, f32)], origin: Vec3, dir: Vec3) -> (Option<(f32, u32)>, usize) {
        let nodes = bvh.gpu_nodes();
        let inv_dir = dir.recip();
        let mut best: Option<(f32, u32)> = None;
        let t_max = |best: &Option<(f32, u32)>| best.map_or(f32::INFINITY, |b| b.0);
        let mut stack = [(0u32, 0f32); MAX_DEPTH];
        let (mut top, mut most) = (0, 0);
        let mut index = 0u32;
        loop {
            while index != NO_CHILD && index & LEAF == 0 {
                let n = &nodes[index as usize];
                let entry = |c: usize| {
                    let child = n.children()[c];
                    (child != NO_CHILD).then(|| box_entry(n.child_box(c), origin, inv_dir, t_max(&best))).flatten()
                };
                let (t_left, t_right) = (entry(0), entry(1));
                let near_first = t_left.unwrap_or(f32::INFINITY) <= t_right.unwrap_or(f32::INFINITY);
                let (near, far) = if near_first { (n.left, n.right) } else { (n.right, n.left) };
                if t_left.is_some() || t_right.is_some() {
                    if let (Some(a), Some(b)) = (t_left, t_right) {
                        stack[top] = (far, a.max(b));
                        top += 1;
                        most = most.max(top);
                    }
                    index = near;
                } else {
                    index = pop(&stack, &mut top, t_max(&best));
                }
            }
            if index == NO_CHILD {
                return (best, most);
            }
            for p in leaf_range(index) {
                let p = bvh.order[p as usize];
                let (center, radius) = spheres[p as usize];
                let Some(t) = hit_sphere(origin, dir, center, radius) else { continue };
                if best.is_none_or(|(best_t, best_p)| t < best_t || (t == best_t && p < best_p)) {
                    best = Some((t, p));
                }
            }
            index = pop(&stack, &mut top, t_max(&best));
        }
    }

    fn pop(stack: &[(u32, f32)], top: &mut usize, t_max: f32) -> u32 {
        while *top > 0 {
            *top -= 1;
            if stack[*top].1 <= t_max {
                return stack[*top].0;
            }
        }
        NO_CHILD
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
