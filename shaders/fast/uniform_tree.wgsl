// The BVH's records and their grids from two uniform buffers, for a tree that
// fits them (Tuning::uniform_tree; docs/decisions/044-uniform-tree.md): the
// functions of lib/bvh_records.wgsl. The scene's arrays hold the tree too.
// import: types

@group(0) @binding(10) var<uniform> uniform_nodes: array<GpuNode, UNIFORM_TREE_RECORDS>;
@group(0) @binding(11) var<uniform> uniform_grids: array<GpuGrid, UNIFORM_TREE_RECORDS>;

fn node_at(i: u32) -> GpuNode {
    return uniform_nodes[i];
}

fn grid_at(i: u32) -> GpuGrid {
    return uniform_grids[i];
}
