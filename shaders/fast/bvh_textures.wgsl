// The BVH's records and their grids in textures, beside the scene's other
// arrays (fast/scene_textures.wgsl): the functions of lib/bvh_records.wgsl.
// import: fast/scene_textures types

@group(0) @binding(2) var node_texels: texture_2d<u32>;
// The grids of the BVH's interior records, for the nodes traversal returns to.
@group(0) @binding(8) var grid_texels: texture_2d<u32>;

fn node_at(i: u32) -> GpuNode {
    let t = textureLoad(node_texels, texel_of(i), 0);
    return GpuNode(t.xyz, t.w);
}

fn grid_at(i: u32) -> GpuGrid {
    let t = textureLoad(grid_texels, texel_of(i), 0);
    return GpuGrid(bitcast<vec3<f32>>(t.xyz), t.w);
}
