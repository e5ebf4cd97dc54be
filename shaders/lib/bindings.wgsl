// Resources of the trace kernel, in bind group 0. The scene's arrays
// (bindings 1, 2, 5 and 8) are in scene_arrays.
// import: types

@group(0) @binding(0) var<uniform> uniforms: SceneUniforms;
// Uniform buffers: see MAX_LIGHTS and MAX_MATERIALS in gpu_types.rs.
@group(0) @binding(3) var<uniform> materials: array<GpuMaterial, MAX_MATERIALS>;
@group(0) @binding(4) var<uniform> lights: array<GpuLight, MAX_LIGHTS>;
// Running sum of samples per pixel: rgb and the sample count in w; a view of
// one number (depth, heat map) holds it in x alone (dispatch.wgsl).
@group(0) @binding(6) var<storage, read_write> accum: array<vec4<f32>>;
// Ray counts: STAT_COUNT counters per slot, one slot per workgroup (modulo the
// slot count), so counting needs no barrier and atomics rarely contend.
@group(0) @binding(7) var<storage, read_write> stats: array<atomic<u32>>;
// The region and sample of the current dispatch.
@group(0) @binding(9) var<uniform> dispatch: DispatchParams;
