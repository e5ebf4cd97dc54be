// The BVH's records and grids in uniform buffers, which the kernels of a scene
// whose tree fits (UNIFORM_TREE, Specialization::uniform_tree) read instead of
// the storage buffers: lavapipe loads a uniform per lane without the branch
// that each lane's load from a storage buffer takes.
// import: types

@group(0) @binding(10) var<uniform> uniform_nodes: array<GpuNode, UNIFORM_TREE_RECORDS>;
@group(0) @binding(11) var<uniform> uniform_grids: array<GpuGrid, UNIFORM_TREE_RECORDS>;
