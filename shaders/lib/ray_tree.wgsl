// Whitted's ray tree for one eye ray,
//   trace(R) = local(R) + k_r·trace(reflect(R)) + k_t·trace(refract(R)),
// down to the scene's maximum depth. WGSL has no recursion, so the rays still
// to trace wait on an explicit stack, each with the weight its colour
// contributes to the pixel, and `trace_step` is one call of trace(R). The tree
// is handed, ray by ray and term by term, to the `note_` functions of
// lib/notes.wgsl, which do nothing; the probe kernel composes its own in their
// place, which record the tree for `glint probe` and the viewer's inspector.
// import: bindings bvh camera checker dispatch notes primitive ray_stack sample scene_arrays secondary_rays shade shadow types

// The deepest level this invocation's tree reached (the ray-depth view).
var<private> deepest: u32;

// The colour of `pixel`'s sample: the tree of its eye ray.
fn trace_pixel(pixel: vec2<u32>) -> vec3<f32> {
    let eye = camera_ray(vec2<f32>(pixel) + sample_offset(pixel));
    // A ray at depth d < max_depth pushes at most two and the next is popped
    // at once, so at most one sibling per level waits: max_depth entries.
    var stack: array<PendingRay, MAX_DEPTH>;
    stack[0] = PendingRay(eye, vec3<f32>(1.0), 1u, RAY_EYE, NO_RAY);
    var top = 1u;
    var color = vec3<f32>(0.0);
    while top > 0u {
        top--;
        color += trace_step(stack[stack_slot(top)], &stack, &top);
    }
    return color;
}

// trace(R) for one ray of the tree: its closest hit, the local colour there,
// and the reflected and refracted rays it spawns pushed on the stack. Returns
// the colour it adds to the pixel.
fn trace_step(pending: PendingRay, stack: ptr<function, array<PendingRay, MAX_DEPTH>>, top: ptr<function, u32>) -> vec3<f32> {
    let hit = traverse(pending.ray, 0.0, MISS, false, false);
    deepest = max(deepest, pending.depth);
    if pending.depth == 1u {
        count_ray(select(STAT_EYE_HIT, STAT_EYE_MISS, hit.t == MISS));
    }
    let id = note_ray(pending.kind, pending.parent, pending.depth, pending.ray, pending.weight, hit.t);
    if hit.t == MISS {
        return pending.weight * uniforms.background;
    }
    let p = prim_at(hit.prim);
    let s = surface_at(p, pending.ray, hit.t);
    let m = material_at(p, s.point);
    note_hit(s, hit.prim);
    let local = local_color(s, m, -pending.ray.dir);
    var color = vec3<f32>(0.0);
    push_secondary_rays(pending, hit.t, s, m, id, local, &color, stack, top);
    return color;
}

// local(R) at `s` seen from `v`: the ambient term, and the term of each light
// facing the surface, through its own shadow ray.
fn local_color(surface: Surface, m: GpuMaterial, v: vec3<f32>) -> vec3<f32> {
    let s = lit_surface(surface);
    var color = ambient_term(m);
    var light = next_lit_light(s, 0u);
    while light.index < uniforms.light_count {
        color += light_term(light, s, m, v, cast_shadow_ray(s, light.sample.l, light.sample.distance));
        light = next_lit_light(s, light.index + 1u);
    }
    return color;
}
