//! Bounding volume hierarchy over primitive bounds, built on the host;
//! [`crate::gpu_bvh`] lays it out for the kernel.
//!
//! Layout: `nodes[0]` is the root; an interior node's children are adjacent at
//! `left_or_first` and `left_or_first + 1`; a leaf (`count > 0`) holds
//! `order[left_or_first .. left_or_first + count]`, indices into the primitives
//! the tree was built over.
//!
//! [`Bvh::build`] splits with a binned surface area heuristic (SAH), in parallel
//! above a size threshold, and bounds the depth by [`MAX_DEPTH`] so the GPU's
//! fixed traversal stack always suffices.

use bytemuck::{Pod, Zeroable};
use glam::{Vec3, Vec3A};

/// The deepest tree the builder makes; the kernels' traversal stack is sized by it.
pub const MAX_DEPTH: usize = 32;

/// The most primitives the builder puts in a leaf: small leaves keep the GPU's
/// per-leaf loop short and its lanes coherent.
const MAX_LEAF: usize = 4;

/// SAH cost of visiting an interior node (two box tests) relative to one
/// primitive intersection.
const C_TRAV: f32 = 1.0;
const C_ISECT: f32 = 1.0;

/// Dearer nodes tried in turn for a tree that must fit a budget of nodes: each
/// makes larger leaves and fewer nodes (the bunny's 4,219 nodes at 1.0 are
/// 3,617 at 1.25).
const BUDGET_C_TRAV: [f32; 3] = [1.25, 1.5, 2.0];
/// A tree over its budget by more than this factor is not rebuilt: the dearest
/// node above would not bring it within.
const BUDGET_SLACK: f32 = 1.5;

/// SAH bins per axis over the centroid bounds. On random scenes 32 bins lower the
/// SAH cost by under 1% and 8 raise it by 2%, for +10% and -5% build time.
const BINS: usize = 16;

/// Nodes with more primitives than this recurse with `rayon::join` and bin in
/// parallel; smaller ones build serially, where task overhead would dominate.
const PARALLEL_MIN: usize = 4096;

/// One node of the binary tree, with its exact box.
#[repr(C)]
#[derive(Debug, Clone, Copy, PartialEq, Pod, Zeroable)]
pub struct Node {
    pub min: [f32; 3],
    pub left_or_first: u32,
    pub max: [f32; 3],
    pub count: u32,
}

impl Node {
    pub fn is_leaf(&self) -> bool {
        self.count > 0
    }

    fn interior(bounds: Aabb, left: u32) -> Self {
        Self { min: bounds.min.into(), left_or_first: left, max: bounds.max.into(), count: 0 }
    }

    fn leaf(bounds: Aabb, first: u32, count: usize) -> Self {
        Self { min: bounds.min.into(), left_or_first: first, max: bounds.max.into(), count: count as u32 }
    }

    fn half_area(&self) -> f32 {
        Aabb { min: self.min.into(), max: self.max.into() }.half_area()
    }
}

#[derive(Debug, Clone, PartialEq)]
pub struct Bvh {
    pub nodes: Vec<Node>,
    /// Primitive indices in leaf order.
    pub order: Vec<u32>,
}

impl Bvh {
    /// A single leaf holding every primitive: traversal degenerates to the brute-force
    /// loop over all primitives, the reference the real tree is tested against.
    pub fn single_leaf(bounds: &[(Vec3, Vec3)]) -> Self {
        let (min, max) = bounds
            .iter()
            .fold((Vec3::INFINITY, Vec3::NEG_INFINITY), |(lo, hi), (a, b)| (lo.min(*a), hi.max(*b)));
        // An empty scene keeps an inverted box that no ray enters, so the leaf's
        // count of 1 (a leaf needs one) never reads the padding primitive.
        let count = bounds.len() as u32;
        Self {
            nodes: vec![Node { min: min.into(), left_or_first: 0, max: max.into(), count: count.max(1) }],
            order: (0..count).collect(),
        }
    }

    /// A binned-SAH tree over `bounds[i] = (min, max)` of primitive `i`.
    ///
    /// Leaves hold at most `MAX_LEAF` (4) primitives (splitting by index where the
    /// boxes cannot be told apart, e.g. identical centroids), and the depth never
    /// exceeds [`MAX_DEPTH`]: a SAH split is only taken while both children can
    /// still be finished by median splits within the remaining depth, otherwise
    /// the node is split at its object median. An empty list gives
    /// [`Bvh::single_leaf`]'s empty tree.
    pub fn build(bounds: &[(Vec3, Vec3)]) -> Self {
        Self::build_costing(bounds, C_TRAV)
    }

    /// [`Bvh::build`]'s tree, or, when it has more than `max_nodes` nodes but
    /// at most `BUDGET_SLACK` times as many, the first tree within `max_nodes`
    /// of those built with a node costing `BUDGET_C_TRAV` primitive tests (for
    /// a tree the kernels read faster when it fits a uniform buffer).
    pub fn build_within(bounds: &[(Vec3, Vec3)], max_nodes: usize) -> Self {
        let tree = Self::build(bounds);
        if tree.nodes.len() <= max_nodes || tree.nodes.len() as f32 > BUDGET_SLACK * max_nodes as f32 {
            return tree;
        }
        BUDGET_C_TRAV.iter().map(|&c_trav| Self::build_costing(bounds, c_trav)).find(|t| t.nodes.len() <= max_nodes).unwrap_or(tree)
    }

    /// The binned-SAH tree with an interior node costing `c_trav` primitive tests.
    fn build_costing(bounds: &[(Vec3, Vec3)], c_trav: f32) -> Self {
        use rayon::prelude::*;
        if bounds.is_empty() {
            return Self::single_leaf(bounds);
        }
        // Up to 2n - 1 nodes, indexed by u32.
        assert!(bounds.len() <= (u32::MAX / 2) as usize, "too many primitives for a BVH: {}", bounds.len());
        let mut items: Vec<Item> =
            bounds.par_iter().enumerate().map(|(i, &(min, max))| Item { min, max, index: i as u32 }).collect();
        let extent = Extent::of(&items);
        let tree = Subtree::build(&mut items, 0, 0, &extent, c_trav);
        let mut nodes = vec![Node::zeroed(); tree.len()];
        let (root, rest) = nodes.split_first_mut().expect("a tree has a root");
        tree.place(root, rest, 1);
        Self { nodes, order: items.par_iter().map(|item| item.index).collect() }
    }

    /// Edges on the longest root-to-leaf path (0 for a lone leaf). The GPU
    /// traversal pushes at most one node per interior level, so this is the most
    /// stack entries it needs; the builder keeps it within [`MAX_DEPTH`].
    pub fn depth(&self) -> usize {
        let mut deepest = 0;
        let mut stack = vec![(0usize, 0usize)];
        while let Some((index, depth)) = stack.pop() {
            let node = &self.nodes[index];
            if node.is_leaf() {
                deepest = deepest.max(depth);
            } else {
                let left = node.left_or_first as usize;
                stack.extend([(left, depth + 1), (left + 1, depth + 1)]);
            }
        }
        deepest
    }

    /// The tree's SAH cost: the expected cost of a ray through the root box, each
    /// node weighted by the chance (area ratio) that the ray enters it. Interior
    /// nodes cost `C_TRAV`, leaves `C_ISECT` per primitive. Zero when the root has
    /// no area (empty or fully degenerate scene), where the ratios are undefined.
    pub fn sah_cost(&self) -> f32 {
        let root = self.nodes[0].half_area();
        if root <= 0.0 {
            return 0.0;
        }
        let total: f64 = self
            .nodes
            .iter()
            .map(|n| f64::from(n.half_area() * if n.is_leaf() { C_ISECT * n.count as f32 } else { C_TRAV }))
            .sum();
        (total / f64::from(root)) as f32
    }
}

/// A box in SIMD registers, for the builder's arithmetic.
#[derive(Debug, Clone, Copy, PartialEq)]
struct Aabb {
    min: Vec3A,
    max: Vec3A,
}

impl Aabb {
    const EMPTY: Self = Self { min: Vec3A::INFINITY, max: Vec3A::NEG_INFINITY };

    fn grow(&mut self, other: &Self) {
        self.min = self.min.min(other.min);
        self.max = self.max.max(other.max);
    }

    fn grow_point(&mut self, p: Vec3A) {
        self.min = self.min.min(p);
        self.max = self.max.max(p);
    }

    fn center(&self) -> Vec3A {
        (self.min + self.max) * 0.5
    }

    /// Half the surface area, proportional to the chance a random ray hits the
    /// box; zero for empty or inverted boxes.
    fn half_area(&self) -> f32 {
        let d = (self.max - self.min).max(Vec3A::ZERO);
        d.x * d.y + d.y * d.z + d.z * d.x
    }
}

/// A primitive as the builder moves it: partitioning these in place keeps each
/// node's primitives contiguous and cache-friendly, with no per-node allocation.
/// Stored unaligned (28 bytes rather than 48) to cut the memory traffic of the
/// top levels; loaded into an [`Aabb`] for arithmetic.
#[derive(Debug, Clone, Copy)]
struct Item {
    min: Vec3,
    max: Vec3,
    index: u32,
}

impl Item {
    fn bounds(&self) -> Aabb {
        Aabb { min: self.min.into(), max: self.max.into() }
    }
}

/// What the builder knows of a node's items before splitting it: their bounds
/// (the node's box) and their centroids' bounds (the binning range).
#[derive(Debug, Clone, Copy)]
struct Extent {
    bounds: Aabb,
    centroids: Aabb,
}

impl Extent {
    const EMPTY: Self = Self { bounds: Aabb::EMPTY, centroids: Aabb::EMPTY };

    fn add(&mut self, bounds: &Aabb, centroid: Vec3A) {
        self.bounds.grow(bounds);
        self.centroids.grow_point(centroid);
    }

    fn merge(mut self, other: Self) -> Self {
        self.bounds.grow(&other.bounds);
        self.centroids.grow(&other.centroids);
        self
    }

    fn of(items: &[Item]) -> Self {
        use rayon::prelude::*;
        let serial = |items: &[Item]| {
            items.iter().fold(Self::EMPTY, |mut e, item| {
                let bounds = item.bounds();
                e.add(&bounds, bounds.center());
                e
            })
        };
        if items.len() <= PARALLEL_MIN {
            return serial(items);
        }
        items.par_chunks(PARALLEL_MIN).map(serial).reduce(|| Self::EMPTY, Self::merge)
    }
}

/// Per-axis bins: bounds and primitive count. A serial build reuses one set for
/// all its nodes, and each node resets only the bins it uses.
#[derive(Debug)]
struct Bins {
    bounds: [[Aabb; BINS]; 3],
    counts: [[u32; BINS]; 3],
}

impl Bins {
    fn new() -> Self {
        Self { bounds: [[Aabb::EMPTY; BINS]; 3], counts: [[0; BINS]; 3] }
    }

    fn merge(mut self, other: Self) -> Self {
        for axis in 0..3 {
            for bin in 0..BINS {
                self.bounds[axis][bin].grow(&other.bounds[axis][bin]);
                self.counts[axis][bin] += other.counts[axis][bin];
            }
        }
        self
    }
}

/// Maps centroids to bins per axis. An axis without centroid extent gets scale 0
/// (everything in bin 0) and is left out of the sweep.
struct Binning {
    origin: Vec3A,
    scale: Vec3A,
    /// Bins in use: as many as primitives in small nodes, whose sweeps would
    /// otherwise cost more than the binning.
    count: usize,
    axes: [bool; 3],
}

impl Binning {
    fn new(centroids: &Aabb, n: usize) -> Self {
        let count = n.min(BINS);
        let extent = centroids.max - centroids.min;
        let scale = count as f32 / extent;
        let usable = extent.cmpgt(Vec3A::ZERO) & scale.is_finite_mask();
        let scale = Vec3A::select(usable, scale, Vec3A::ZERO);
        Self { origin: centroids.min, scale, count, axes: usable.into() }
    }

    /// Bins of a centroid on the three axes, in one go. Rounds in the float unit
    /// (adding 2^23 to a value in [0, 2^22] leaves its integer in the mantissa), as
    /// saturating float-to-int casts cost more than the rest of the binning; the
    /// integer clamp catches NaN, whose min/max differ between SIMD backends.
    /// Binning and partitioning both go through here, so they always agree.
    fn bins_of(&self, c: Vec3A) -> [usize; 3] {
        const ROUND: f32 = 8_388_608.0;
        let last = self.count - 1;
        let x = ((c - self.origin) * self.scale - 0.5).min(Vec3A::splat(last as f32)).max(Vec3A::ZERO) + ROUND;
        x.to_array().map(|x| ((x.to_bits() & 0x7f_ffff) as usize).min(last))
    }

    /// Fills the first `count` bins of each axis of `bins` from `items`.
    fn bin(&self, items: &[Item], bins: &mut Bins) {
        use rayon::prelude::*;
        if items.len() > PARALLEL_MIN {
            *bins = items
                .par_chunks(PARALLEL_MIN)
                .map(|chunk| {
                    let mut bins = Bins::new();
                    self.bin(chunk, &mut bins);
                    bins
                })
                .reduce(Bins::new, Bins::merge);
            return;
        }
        for axis in 0..3 {
            bins.bounds[axis][..self.count].fill(Aabb::EMPTY);
            bins.counts[axis][..self.count].fill(0);
        }
        for item in items {
            let bounds = item.bounds();
            for (axis, bin) in self.bins_of(bounds.center()).into_iter().enumerate() {
                bins.bounds[axis][bin].grow(&bounds);
                bins.counts[axis][bin] += 1;
            }
        }
    }

    /// The cheapest split between non-empty children over all axes, if any.
    fn best_split(&self, bins: &Bins) -> Option<SahSplit> {
        let mut best: Option<SahSplit> = None;
        for axis in (0..3).filter(|&a| self.axes[a]) {
            let (bounds, counts) = (&bins.bounds[axis][..self.count], &bins.counts[axis][..self.count]);
            // Left sweep: area and count of bins ..=i.
            let mut left_area = [0.0; BINS];
            let mut left_count = [0; BINS];
            let mut acc = Aabb::EMPTY;
            let mut count = 0;
            for i in 0..self.count - 1 {
                acc.grow(&bounds[i]);
                count += counts[i];
                left_area[i] = acc.half_area();
                left_count[i] = count;
            }
            // Right sweep, evaluating each boundary with both sides known.
            let mut acc = Aabb::EMPTY;
            let mut right = 0;
            for last in (0..self.count - 1).rev() {
                acc.grow(&bounds[last + 1]);
                right += counts[last + 1];
                let left = left_count[last];
                if left == 0 || right == 0 {
                    continue;
                }
                let cost = left_area[last] * left as f32 + acc.half_area() * right as f32;
                let imbalance = left.abs_diff(right);
                if best.is_none_or(|b| cost < b.cost || (cost == b.cost && imbalance < b.imbalance)) {
                    best = Some(SahSplit { axis, last, left: left as usize, cost, imbalance });
                }
            }
        }
        best
    }
}

/// A split between bins `..=last` and `last + 1..` on `axis`.
#[derive(Debug, Clone, Copy)]
struct SahSplit {
    axis: usize,
    last: usize,
    left: usize,
    /// Σ area·count over both children (the part of the SAH the split decides).
    cost: f32,
    /// |left − right|: among equal costs (e.g. zero-area boxes) the most balanced
    /// split wins, so degenerate input does not degrade into a chain.
    imbalance: u32,
}

/// How many primitives median splits fit into `levels` more levels of leaves of
/// at most `MAX_LEAF`.
fn capacity(levels: usize) -> u64 {
    (MAX_LEAF as u64) << levels
}

/// Moves the items whose centroid matches `left` to the front and returns how
/// many there are, with both sides' extents gathered on the way (saving the
/// children a pass).
fn partition(items: &mut [Item], left: impl Fn(Vec3A) -> bool) -> (usize, Extent, Extent) {
    let mut sides = (Extent::EMPTY, Extent::EMPTY);
    // Each item joins its side's extent when classified; the one item the two
    // scans may both classify joins twice, which a union ignores.
    let mut classify = |item: &Item| {
        let bounds = item.bounds();
        let centroid = bounds.center();
        let goes_left = left(centroid);
        if goes_left { &mut sides.0 } else { &mut sides.1 }.add(&bounds, centroid);
        goes_left
    };
    let (mut i, mut j) = (0, items.len());
    loop {
        while i < j && classify(&items[i]) {
            i += 1;
        }
        while i < j && !classify(&items[j - 1]) {
            j -= 1;
        }
        if i == j {
            break;
        }
        items.swap(i, j - 1);
        i += 1;
        j -= 1;
    }
    (i, sides.0, sides.1)
}

/// The split of a node at `depth` over `items` with extent `extent` (reordering
/// the items): where it splits and the children's extents, or `None` for a leaf.
///
/// Invariant: `items.len() <= capacity(MAX_DEPTH - depth)`, which holds at the root
/// and which every split passes on to both children.
fn split_node(items: &mut [Item], depth: usize, extent: &Extent, bins: &mut Bins, c_trav: f32) -> Option<(usize, Extent, Extent)> {
    let n = items.len();
    let remaining = MAX_DEPTH - depth;
    debug_assert!(n as u64 <= capacity(remaining));
    if n == 1 || remaining == 0 {
        return None;
    }
    let binning = Binning::new(&extent.centroids, n);
    binning.bin(items, bins);
    let sah = binning.best_split(bins);
    let area = extent.bounds.half_area();
    let worth_it = sah.is_some_and(|s| c_trav * area + C_ISECT * s.cost < C_ISECT * n as f32 * area);
    if n <= MAX_LEAF && !worth_it {
        return None;
    }
    match sah {
        Some(s) if s.left.max(n - s.left) as u64 <= capacity(remaining - 1) => {
            let split = partition(items, |centroid| binning.bins_of(centroid)[s.axis] <= s.last);
            debug_assert_eq!(split.0, s.left);
            Some(split)
        }
        // No SAH split, or one that would leave a child too deep: the object median
        // along the widest centroid axis halves the count, which always fits.
        _ => {
            let axis = (extent.centroids.max - extent.centroids.min).max_position();
            let mid = n / 2;
            let key = |item: &Item| item.min[axis] + item.max[axis];
            items.select_nth_unstable_by(mid, |a, b| key(a).total_cmp(&key(b)));
            Some((mid, Extent::of(&items[..mid]), Extent::of(&items[mid..])))
        }
    }
}

/// Builds serially into `nodes`, children appended depth-first after their parent.
/// Leaves index the global item array, which `items` starts at `first`.
fn build_serial(
    items: &mut [Item],
    first: u32,
    depth: usize,
    extent: &Extent,
    bins: &mut Bins,
    nodes: &mut Vec<Node>,
    slot: usize,
    c_trav: f32,
) {
    let Some((mid, left_extent, right_extent)) = split_node(items, depth, extent, bins, c_trav) else {
        nodes[slot] = Node::leaf(extent.bounds, first, items.len());
        return;
    };
    let child = nodes.len();
    nodes[slot] = Node::interior(extent.bounds, child as u32);
    nodes.extend([Node::zeroed(); 2]);
    let (left, right) = items.split_at_mut(mid);
    build_serial(left, first, depth + 1, &left_extent, bins, nodes, child, c_trav);
    build_serial(right, first + mid as u32, depth + 1, &right_extent, bins, nodes, child + 1, c_trav);
}

/// The result of the parallel build before flattening: the top levels as boxed
/// splits, below them serially built chunks whose interior links are local
/// (root at 0).
enum Subtree {
    Chunk(Vec<Node>),
    Split { bounds: Aabb, left: Box<Subtree>, right: Box<Subtree>, len: usize },
}

impl Subtree {
    fn build(items: &mut [Item], first: u32, depth: usize, extent: &Extent, c_trav: f32) -> Self {
        if items.len() <= PARALLEL_MIN {
            let mut nodes = Vec::with_capacity(2 * items.len() - 1);
            nodes.push(Node::zeroed());
            build_serial(items, first, depth, extent, &mut Bins::new(), &mut nodes, 0, c_trav);
            return Self::Chunk(nodes);
        }
        let (mid, left_extent, right_extent) =
            split_node(items, depth, extent, &mut Bins::new(), c_trav).expect("nodes above MAX_LEAF always split");
        let (left, right) = items.split_at_mut(mid);
        let (left, right) = rayon::join(
            || Self::build(left, first, depth + 1, &left_extent, c_trav),
            || Self::build(right, first + mid as u32, depth + 1, &right_extent, c_trav),
        );
        let len = 1 + left.len() + right.len();
        Self::Split { bounds: extent.bounds, left: Box::new(left), right: Box::new(right), len }
    }

    fn len(&self) -> usize {
        match self {
            Self::Chunk(nodes) => nodes.len(),
            Self::Split { len, .. } => *len,
        }
    }

    /// Writes the subtree's root to `root` and its other nodes to `rest`, which
    /// starts at global node index `base`: a split's children first (adjacent),
    /// then the left and the right subtree's remaining nodes.
    fn place(self, root: &mut Node, rest: &mut [Node], base: u32) {
        match self {
            Self::Chunk(nodes) => {
                // Local index k >= 1 lands at base + k - 1.
                let relink = |mut node: Node| {
                    if !node.is_leaf() {
                        node.left_or_first += base - 1;
                    }
                    node
                };
                *root = relink(nodes[0]);
                for (dst, &src) in rest.iter_mut().zip(&nodes[1..]) {
                    *dst = relink(src);
                }
            }
            Self::Split { bounds, left, right, .. } => {
                *root = Node::interior(bounds, base);
                let (children, rest) = rest.split_at_mut(2);
                let (left_root, right_root) = children.split_at_mut(1);
                let left_rest_len = left.len() - 1;
                let (left_rest, right_rest) = rest.split_at_mut(left_rest_len);
                let right_base = base + 2 + left_rest_len as u32;
                rayon::join(
                    || left.place(&mut left_root[0], left_rest, base + 2),
                    || right.place(&mut right_root[0], right_rest, right_base),
                );
            }
        }
    }
}

#[cfg(test)]
mod tests;
