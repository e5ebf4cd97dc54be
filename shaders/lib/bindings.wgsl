// Resources of the trace kernel, in bind group 0.
// import: types

@group(0) @binding(0) var<uniform> uniforms: SceneUniforms;
@group(0) @binding(1) var<storage, read> prims: array<GpuPrim>;
@group(0) @binding(2) var<storage, read> nodes: array<GpuNode>;
// Uniform buffers: see MAX_LIGHTS and MAX_MATERIALS in gpu_types.rs.
@group(0) @binding(3) var<uniform> materials: array<GpuMaterial, MAX_MATERIALS>;
@group(0) @binding(4) var<uniform> lights: array<GpuLight, MAX_LIGHTS>;
// Polygon vertices and triangle vertex normals (xyz).
@group(0) @binding(5) var<storage, read> points: array<vec4<f32>>;
// Running sum of samples per pixel: rgb and the sample count in w.
@group(0) @binding(6) var<storage, read_write> accum: array<vec4<f32>>;
// Ray counts: STAT_COUNT counters per slot, one slot per workgroup (modulo the
// slot count), so counting needs no barrier and atomics rarely contend.
@group(0) @binding(7) var<storage, read_write> stats: array<atomic<u32>>;
// The grids of the BVH's interior records, for the nodes traversal returns to.
@group(0) @binding(8) var<storage, read> grids: array<GpuGrid>;
// The region and sample of the current dispatch.
@group(0) @binding(9) var<uniform> dispatch: DispatchParams;
