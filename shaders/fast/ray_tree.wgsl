// The ray tree of lib/ray_tree.wgsl, the same rays in the same order, walked
// as one loop whose step is one query: the next ray of the tree or the shadow
// ray towards the next light of the surface being shaded. Every ray goes
// through one call of `traverse`: lavapipe inlines a call's whole walk and
// primitive tests, so a second call would be a second copy of them to compile
// (docs/decisions/024-one-walk-in-the-trace-kernel.md). With EYE_HITS the eye
// ray's hit is not walked again: the primary kernel's eye tiles found it and
// left it in the accumulation buffer (docs/decisions/059-eye-hits-from-the-eye-tiles.md).
// import: bindings bvh camera checker dispatch notes primitive ray_stack sample scene_arrays secondary_rays shade shadow types

// The deepest level this invocation's tree reached (the ray-depth view).
var<private> deepest: u32;

fn trace_pixel(pixel: vec2<u32>) -> vec3<f32> {
    let eye = camera_ray(vec2<f32>(pixel) + sample_offset(pixel));
    // Rays at depth d < max_depth push at most two and the next is popped at
    // once, so at most one sibling per level waits: max_depth entries.
    var stack: array<PendingRay, MAX_DEPTH>;
    var top = 0u;
    var pending = PendingRay(eye, vec3<f32>(1.0), 1u, RAY_EYE, NO_RAY);
    var color = vec3<f32>(0.0);
    // The surface `pending` hit, while it is shaded: its distance, point,
    // material and colour there (see `shaded_material`), the id `note_ray`
    // gave the ray, the local colour so far and the light whose shadow ray is
    // traced next (light_count: none left).
    var t_hit: f32;
    var s: Surface;
    var material: u32;
    var color_at_hit: vec3<f32>;
    var id: u32;
    var local: vec3<f32>;
    var light: LitLight;
    // The query traced next: `pending`'s closest hit, or a shadow ray's any
    // hit before the light, along `query_ray` up to `query_end`.
    var shadow_query = false;
    var query_ray = eye;
    var query_end = MISS;
    loop {
        var hit: Hit;
        if shadow_query && !shadows_traced() {
            hit = unshadowed();
        } else if EYE_HITS && !shadow_query && pending.depth == 1u {
            let found = eye_hit_written(pixel);
            hit = Hit(found.t, found.prim, vec3<f32>(1.0), 0u);
        } else {
            hit = traverse(query_ray, 0.0, query_end, shadow_query, shadow_query && shadows_tinted());
        }
        var shading = true;
        var first_light = 0u;
        if shadow_query {
            local += light_term(light, s, shaded_material(material, color_at_hit), -pending.ray.dir, hit);
            first_light = light.index + 1u;
        } else {
            deepest = max(deepest, pending.depth);
            if pending.depth == 1u {
                count_ray(select(STAT_EYE_HIT, STAT_EYE_MISS, hit.t == MISS));
            }
            id = note_ray(pending.kind, pending.parent, pending.depth, pending.ray, pending.weight, hit.t);
            if hit.t == MISS {
                color += pending.weight * uniforms.background;
                shading = false;
            } else {
                let p = prim_at(hit.prim);
                t_hit = hit.t;
                s = surface_at(p, pending.ray, hit.t);
                let m = material_at(p, s.point);
                material = prim_material(p);
                color_at_hit = m.color;
                note_hit(s, hit.prim);
                s = lit_surface(s);
                local = ambient_term(m);
            }
        }
        if shading {
            light = next_lit_light(s, first_light);
        }
        if shading && light.index < uniforms.light_count {
            if shadows_traced() {
                count_ray(STAT_SHADOW);
            }
            let shadow = shadow_ray(s.point, s.geometric, light.sample.l, light.sample.distance);
            query_ray = shadow.ray;
            query_end = shadow.t_max;
            shadow_query = true;
            continue;
        }
        if shading {
            // The surface turned back: secondary rays leave as the lecture's do.
            push_secondary_rays(pending, t_hit, lit_surface(s), shaded_material(material, color_at_hit), id, local, &color, &stack, &top);
        }
        // Without secondary rays the tree is the eye ray alone, and the
        // kernel compiles without the stack (a sixth less to compile).
        if !HAS_SECONDARY_RAYS || top == 0u {
            break;
        }
        top--;
        pending = stack[stack_slot(top)];
        query_ray = pending.ray;
        query_end = MISS;
        shadow_query = false;
    }
    return color;
}

// The material being shaded, with its colour at the hit (a checker's tile).
// The loop carries its index and that colour, not the whole material: a
// variable the loop carries is kept in memory by a kernel compiled without
// optimisation, and read and written whole each time round.
fn shaded_material(index: u32, color: vec3<f32>) -> GpuMaterial {
    var m = materials[index];
    m.color = color;
    return m;
}
