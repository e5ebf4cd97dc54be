// Whitted's checkerboard, on any material: O_d at a hit alternates between the
// material's colour (even tiles) and its checker colour (odd tiles), in tiles
// of side checker_size with a corner at the world origin. Planes and polygons
// count tiles in their own 2D coordinates (P·u, P·v, the axes packed in b and
// c): counted in 3D, a floor at y = 0 would flicker between the layers of
// y = 0 and y = −size as its hit points round above or below it. Other shapes
// use the solid checker of x, y and z.
// import: bindings types

// The material at `point` on primitive `p`, its colour the checker's there.
fn material_at(p: GpuPrim, point: vec3<f32>) -> GpuMaterial {
    var m = materials[prim_material(p)];
    if !HAS_CHECKER || (m.flags & MATERIAL_CHECKER) == 0u {
        return m;
    }
    var q = point;
    let kind = prim_kind(p);
    if kind == PRIM_PLANE || kind == PRIM_POLYGON {
        q = vec3<f32>(dot(point, p.b.xyz), dot(point, p.c.xyz), 0.0);
    }
    // The tile indices are whole numbers, so their sum is odd exactly when
    // half of it has a fractional part (0.5).
    let tiles = floor(q / m.checker_size);
    if fract(0.5 * (tiles.x + tiles.y + tiles.z)) != 0.0 {
        m.color = m.checker;
    }
    return m;
}
