//! Bounding volume hierarchy over primitive bounds, built on the host and
//! flattened for the GPU.
//!
//! Layout: `nodes[0]` is the root; an interior node's children are adjacent at
//! `left_or_first` and `left_or_first + 1`; a leaf (`count > 0`) holds
//! `order[left_or_first .. left_or_first + count]`, indices into the primitives
//! the tree was built over.

use bytemuck::{Pod, Zeroable};
use glam::Vec3;

/// The deepest tree the builder makes; the WGSL traversal stack is sized by it.
pub const MAX_DEPTH: usize = 32;

/// One node, 32 bytes, mirrored by `Node` in shaders/types.wgsl.
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
}
