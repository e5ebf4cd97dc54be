// The BVH's nodes as glint-encoding's gpu_bvh.rs stores them: an interior
// node's two child boxes quantised to a byte per coordinate on a grid of
// power-of-two cells, so that one 16-byte load brings both boxes a visit tests
// (docs/decisions/001-quantised-bvh-nodes.md says where it was measured). The
// grid is derived from the box the walk just tested, and loaded only for a
// node popped from the stack.
// import: bvh_records

// A node's grid in registers: origin and biased cell exponents per axis.
struct Grid {
    origin: vec3<f32>,
    exponents: vec3<u32>,
}

fn stored_grid(index: u32) -> Grid {
    let g = grid_at(index);
    return Grid(g.origin, vec3<u32>(g.exponents, g.exponents >> 8u, g.exponents >> 16u) & vec3<u32>(0xffu));
}

// The grid over box [lo, hi] as gpu_bvh.rs derives it: origin lo; per axis the
// smallest power-of-two cell c with 254·c ≥ hi − lo, from the extent's bits
// (for m·2^E, 1 ≤ m < 2: 2^(E−7) when m ≤ 254/128, else 2^(E−6)), at least 2^-100.
fn derived_grid(lo: vec3<f32>, hi: vec3<f32>) -> Grid {
    let bits = bitcast<vec3<u32>>(hi - lo) & vec3<u32>(0x7fffffffu);
    let e = (bits >> vec3<u32>(23u)) + select(vec3<u32>(0u), vec3<u32>(1u), (bits & vec3<u32>(0x7fffffu)) > vec3<u32>(0x7e0000u));
    return Grid(lo, clamp(e, vec3<u32>(34u), vec3<u32>(261u)) - vec3<u32>(7u));
}

// Corner bytes `shift` / 8 of `q` in world space: exact products, one rounding.
fn decode(grid: Grid, q: vec3<u32>, shift: vec3<u32>) -> vec3<f32> {
    let cell = bitcast<vec3<f32>>(grid.exponents << vec3<u32>(23u));
    return grid.origin + vec3<f32>((q >> shift) & vec3<u32>(0xffu)) * cell;
}

// A node's two child boxes in world space, each by its corners on the side a
// ray meets first (`near_byte` per axis, as in `traverse`) and last.
struct ChildCorners {
    left_near: vec3<f32>,
    left_far: vec3<f32>,
    right_near: vec3<f32>,
    right_far: vec3<f32>,
}

fn child_corners(grid: Grid, q: vec3<u32>, near_byte: vec3<u32>) -> ChildCorners {
    let far_byte = near_byte ^ vec3<u32>(8u);
    return ChildCorners(decode(grid, q, near_byte), decode(grid, q, far_byte), decode(grid, q, near_byte + 16u), decode(grid, q, far_byte + 16u));
}

// The grid of the child a walk descends into (the left one when `left`): the
// one over the box just tested.
fn entered_grid(c: ChildCorners, left: bool, near_byte: vec3<u32>) -> Grid {
    let near = select(c.right_near, c.left_near, left);
    let far = select(c.right_far, c.left_far, left);
    let negative = near_byte != vec3<u32>(0u);
    return derived_grid(select(near, far, negative), select(far, near, negative));
}
