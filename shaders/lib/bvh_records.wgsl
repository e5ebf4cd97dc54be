// The BVH's records and their grids, in storage buffers. A tuning may put
// fast/bvh_textures.wgsl or fast/uniform_tree.wgsl in this file's place.
// A seam: the walk reads records through `node_at` and `grid_at`, not by
// indexing, only so that those files can keep them elsewhere.
// import: types

@group(0) @binding(2) var<storage, read> nodes: array<GpuNode>;
// The grids of the BVH's interior records, for the nodes traversal returns to.
@group(0) @binding(8) var<storage, read> grids: array<GpuGrid>;

fn node_at(i: u32) -> GpuNode {
    return nodes[i];
}

fn grid_at(i: u32) -> GpuGrid {
    return grids[i];
}
