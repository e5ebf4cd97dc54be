// Structs shared by the kernels. Each one the host uploads (Gpu…, the
// uniforms, the dispatch) has a Rust twin of the same name in
// crates/glint-encoding/src/gpu_types.rs (gpu_bvh.rs for the BVH, primitive_kinds.rs for GpuPrim); a naga test checks
// that sizes and member offsets agree. Rays are the kernels' own. The constants they use (PRIM_, VIEW_,
// FLAG_, MISS, LEAF …) come from the generated prelude (gpu_types::wgsl_prelude).

struct GpuCamera {
    eye: vec3<f32>,
    projection: u32,
    u: vec3<f32>,
    half_width: f32,
    v: vec3<f32>,
    half_height: f32,
    w: vec3<f32>,
    _pad: f32,
}

// Written once per scene change.
struct SceneUniforms {
    camera: GpuCamera,
    background: vec3<f32>,
    width: u32,
    ambient: vec3<f32>,
    height: u32,
    depth_cue_color: vec3<f32>,
    light_count: u32,
    depth_cue: vec4<f32>, // near, far, near_scale, far_scale
    max_depth: u32,
    cutoff: f32,
    flags: u32,
    // The BVH record traversal starts from.
    bvh_root: u32,
    // The infinite planes, prims[plane_first .. plane_first + plane_count],
    // which every ray tests besides the BVH.
    plane_first: u32,
    plane_count: u32,
    _pad0: u32,
    _pad1: u32,
}

// Written before each dispatch: the region it covers and the sample it adds.
struct DispatchParams {
    origin: vec2<u32>,
    // Exclusive: whole workgroups may reach past it.
    end: vec2<u32>,
    sample_index: u32,
    seed: u32,
    // Samples per pixel of this render (stratified); 1 traces the pixel centre,
    // 0 means an open-ended progressive render (jittered, unstratified).
    sample_count: u32,
    pixel_filter: u32,
    // What the kernel writes per pixel (a VIEW_ constant).
    view: u32,
    // The image pixel the accumulation buffer's first entry holds, and the
    // width of its rows: a tile accumulates in a buffer of its own size.
    tile_x: u32,
    tile_y: u32,
    tile_width: u32,
}

struct GpuLight {
    position: vec3<f32>, // travel direction for a directional light
    kind: u32,
    radiance: vec3<f32>,
    attenuation: u32,
    coefficients: vec4<f32>,
}

struct GpuMaterial {
    color: vec3<f32>,
    ka: f32,
    specular_color: vec3<f32>,
    kd: f32,
    reflect: vec3<f32>,
    ks: f32,
    transmit: vec3<f32>,
    shininess: f32,
    f0: vec3<f32>,
    ior: f32,
    // O_d of the checker's odd tiles (with MATERIAL_CHECKER).
    checker: vec3<f32>,
    checker_size: f32,
    flags: u32,
    _pad0: u32,
    _pad1: u32,
    _pad2: u32,
}

struct GpuPrim {
    a: vec4<f32>,
    b: vec4<f32>,
    c: vec4<f32>,
    kind_material: u32,
    object: u32,
    first: u32,
    count: u32,
}

// A BVH record (crates/glint-encoding/src/gpu_bvh.rs has the details). Interior:
// bytes 2c and 2c + 1 of quantized[a] are child c's box on axis a in cells of
// the node's grid, `children` the first child's index with LEAF set when it is a
// leaf and RIGHT_LEAF when the second is. Leaf: quantized.x is the first
// primitive, quantized.y the count.
struct GpuNode {
    quantized: vec3<u32>,
    children: u32,
}

// A node's grid: the origin and, in byte a of `exponents`, the biased exponent
// of the cell size on axis a.
struct GpuGrid {
    origin: vec3<f32>,
    exponents: u32,
}

struct Ray {
    origin: vec3<f32>,
    dir: vec3<f32>,
}

fn prim_kind(p: GpuPrim) -> u32 {
    return p.kind_material & 0xffu;
}

fn prim_material(p: GpuPrim) -> u32 {
    return p.kind_material >> 8u;
}
