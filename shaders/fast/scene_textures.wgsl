// The scene's primitives and polygon points in textures of
// SCENE_TEXTURE_WIDTH texels of 16 bytes a row, for kernels compiled without
// optimisation (docs/decisions/034-scene-textures.md): the functions of
// lib/scene_arrays.wgsl, from the same bytes.
// import: types

@group(0) @binding(1) var prim_texels: texture_2d<u32>;
// Polygon vertices and triangle vertex normals (xyz).
@group(0) @binding(5) var point_texels: texture_2d<u32>;

// Where texel `index` of a scene texture is: row-major, SCENE_TEXTURE_WIDTH a row.
fn texel_of(index: u32) -> vec2<u32> {
    return vec2<u32>(index % SCENE_TEXTURE_WIDTH, index / SCENE_TEXTURE_WIDTH);
}

// Primitive i. Its PRIM_TEXELS texels, side by side in one row, are its
// vertices a, b and c, then its four words, as GpuPrim lays them out; the
// driver drops the fetches of the members a caller does not use.
fn prim_at(i: u32) -> GpuPrim {
    let first = texel_of(i * PRIM_TEXELS);
    let words = textureLoad(prim_texels, first + vec2<u32>(3u, 0u), 0);
    return GpuPrim(
        bitcast<vec4<f32>>(textureLoad(prim_texels, first, 0)),
        bitcast<vec4<f32>>(textureLoad(prim_texels, first + vec2<u32>(1u, 0u), 0)),
        bitcast<vec4<f32>>(textureLoad(prim_texels, first + vec2<u32>(2u, 0u), 0)),
        words.x,
        words.y,
        words.z,
        words.w,
    );
}

fn point_at(i: u32) -> vec4<f32> {
    return bitcast<vec4<f32>>(textureLoad(point_texels, texel_of(i), 0));
}
