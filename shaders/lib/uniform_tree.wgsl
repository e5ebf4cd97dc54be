// Where the kernels read the BVH's records and grids: from two uniform buffers
// when the scene's tree fits them (UNIFORM_TREE, Tuning::uniform_tree),
// else from the scene's arrays, which hold it either way. lavapipe loads a
// uniform per lane without the branch that each lane's load from a storage
// buffer takes.
// import: scene_arrays types

@group(0) @binding(10) var<uniform> uniform_nodes: array<GpuNode, UNIFORM_TREE_RECORDS>;
@group(0) @binding(11) var<uniform> uniform_grids: array<GpuGrid, UNIFORM_TREE_RECORDS>;

fn node_at(i: u32) -> GpuNode {
    if UNIFORM_TREE {
        return uniform_nodes[i];
    }
    return node_in_arrays(i);
}

fn grid_at(i: u32) -> GpuGrid {
    if UNIFORM_TREE {
        return uniform_grids[i];
    }
    return grid_in_arrays(i);
}
