// The scene's arrays in storage buffers, what optimised kernels read fastest.
// A kernel imports `scene_arrays`, which is this file or scene_textures.wgsl
// (SceneArrays in crates/glint-gpu/src/shaders.rs): both declare the same
// functions over the same bindings, of the kind the renderer's layout says.
// import: types

@group(0) @binding(1) var<storage, read> prims: array<GpuPrim>;
@group(0) @binding(2) var<storage, read> nodes: array<GpuNode>;
// Polygon vertices and triangle vertex normals (xyz).
@group(0) @binding(5) var<storage, read> points: array<vec4<f32>>;
// The grids of the BVH's interior records, for the nodes traversal returns to.
@group(0) @binding(8) var<storage, read> grids: array<GpuGrid>;

fn prim_at(i: u32) -> GpuPrim {
    return prims[i];
}

fn node_in_arrays(i: u32) -> GpuNode {
    return nodes[i];
}

fn grid_in_arrays(i: u32) -> GpuGrid {
    return grids[i];
}

fn point_at(i: u32) -> vec4<f32> {
    return points[i];
}
