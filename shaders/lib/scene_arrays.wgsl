// The scene's primitives and polygon points, in storage buffers. A tuning may
// put fast/scene_textures.wgsl in this file's place: the same functions over
// the same bindings (SceneArrays in crates/glint-gpu/src/tuning.rs).
// A seam: `prim_at` and `point_at` stand for indexing, only so that the
// stand-in can read textures instead.
// import: types

@group(0) @binding(1) var<storage, read> prims: array<GpuPrim>;
// Polygon vertices and triangle vertex normals (xyz).
@group(0) @binding(5) var<storage, read> points: array<vec4<f32>>;

fn prim_at(i: u32) -> GpuPrim {
    return prims[i];
}

fn point_at(i: u32) -> vec4<f32> {
    return points[i];
}
