// Whitted's ray tree for one eye ray, trace(R) = local(R) + k_m·trace(reflect)
// + k_t·trace(refract), walked with an explicit stack (WGSL has no recursion)
// down to the scene's maximum depth. Each pending ray carries the weight its
// colour contributes to the pixel. The tree is handed, ray by ray and term by
// term, to the kernel's `note_` functions: the trace kernel's do nothing, the
// probe kernel's record the tree for `glint probe` and the viewer's inspector.
//
// Every ray of the tree and every shadow ray goes through one call of
// `traverse`: a loop whose step is one query, the next ray of the tree or the
// shadow ray towards the next light of the surface being shaded. The driver
// inlines a call's whole walk and primitive tests, so a second call would be
// a second copy of them to compile (a cold start pays for every copy).
// import: bindings bvh checker dispatch primitive reflect refract scene_arrays shade shadow types

struct PendingRay {
    ray: Ray,
    weight: vec3<f32>,
    depth: u32,
    // RAY_EYE, RAY_REFLECT or RAY_REFRACT, and the id `note_ray` gave the ray it came from.
    kind: u32,
    parent: u32,
}

// The deepest level this invocation's tree reached (the ray-depth view).
var<private> deepest: u32;

fn trace_pixel(eye: Ray) -> vec3<f32> {
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
            push_secondary_rays(pending, t_hit, s, shaded_material(material, color_at_hit), id, local, &color, &stack, &top);
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

// Where the ray stack's entry `top` is kept. Without transmitters
// (HAS_REFRACTIONS false) a surface spawns its reflected ray alone, so the
// tree is a chain and the stack never holds more than one pending ray: at the
// constant slot 0 the driver keeps it in registers instead of compiling a
// store and a load at an index that differs between SIMD lanes.
fn stack_slot(top: u32) -> u32 {
    return select(0u, top, HAS_REFRACTIONS);
}

// Adds the shaded surface's local colour `local` (depth-cued) to `color` and
// pushes the reflected and refracted rays it spawns, down to the maximum depth.
fn push_secondary_rays(
    pending: PendingRay,
    t_hit: f32,
    s: Surface,
    m: GpuMaterial,
    id: u32,
    local: vec3<f32>,
    color: ptr<function, vec3<f32>>,
    stack: ptr<function, array<PendingRay, MAX_DEPTH>>,
    top: ptr<function, u32>,
) {
    let ray = pending.ray;
    var weight = pending.weight;
    if HAS_DEPTH_CUE && (uniforms.flags & FLAG_DEPTH_CUE) != 0u {
        let so = depth_cue_scale(t_hit);
        note_cue(so);
        *color += weight * (so * local + (1.0 - so) * uniforms.depth_cue_color);
        weight *= so;
    } else {
        *color += weight * local;
    }
    // A kernel for a scene whose materials neither reflect nor transmit
    // (HAS_SECONDARY_RAYS false) compiles without the rest.
    if !HAS_SECONDARY_RAYS || pending.depth >= uniforms.max_depth {
        return;
    }

    // Entering when the ray meets the front of the surface; the outside is air.
    let eta = select(1.0 / m.ior, m.ior, s.backface);
    var k_reflect = m.reflect;
    // Without transmitters (HAS_REFRACTIONS false) nothing below refracts,
    // and the driver's compiler drops the refraction with the constant.
    var k_refract = select(vec3<f32>(0.0), m.transmit, HAS_REFRACTIONS && (uniforms.flags & FLAG_REFRACTIONS) != 0u);
    let refracted = refract_dir(ray.dir, s.shading, eta);
    note_refraction(eta, any(k_refract > vec3<f32>(0.0)) && refracted.w == 0.0);
    if any(k_refract > vec3<f32>(0.0)) {
        if refracted.w == 0.0 {
            // Total internal reflection: the transmitted share is reflected.
            k_reflect += k_refract;
            k_refract = vec3<f32>(0.0);
        } else if (m.flags & MATERIAL_FRESNEL) != 0u {
            let cos_i = -dot(ray.dir, s.shading);
            let cos_t = -dot(refracted.xyz, s.shading);
            // Schlick with the cosine on the less dense side.
            let f = schlick(vec3<f32>(dielectric_f0(1.0, m.ior)), select(cos_i, cos_t, eta > 1.0)).x;
            k_reflect += k_refract * f;
            k_refract *= 1.0 - f;
        }
    }
    // With reflections off no reflected ray is traced at all, including the
    // share that total internal reflection or Fresnel moved into it.
    if (uniforms.flags & FLAG_REFLECTIONS) == 0u {
        k_reflect = vec3<f32>(0.0);
    }
    let eps = ray_epsilon(s.point);
    let w_reflect = weight * k_reflect;
    let w_refract = weight * k_refract;
    // Bit 0: the reflected ray, bit 1: the refracted one.
    var spawned = 0u;
    if any(w_reflect > vec3<f32>(uniforms.cutoff)) && any(w_reflect > vec3<f32>(0.0)) {
        count_ray(STAT_REFLECT);
        spawned |= 1u;
    }
    if any(w_refract > vec3<f32>(uniforms.cutoff)) && any(w_refract > vec3<f32>(0.0)) {
        count_ray(STAT_REFRACT);
        spawned |= 2u;
    }
    // One push for both, in a loop whose count the driver's compiler does not
    // know, so it keeps one copy of the store into the stack: a store at an
    // index that differs between SIMD lanes is much code.
    while spawned != 0u {
        let refracted_ray = firstTrailingBit(spawned) == 1u;
        spawned &= spawned - 1u;
        let r = Ray(
            s.point + select(eps, -eps, refracted_ray) * s.geometric,
            select(reflect_dir(ray.dir, s.shading), refracted.xyz, refracted_ray),
        );
        (*stack)[stack_slot(*top)] = PendingRay(r, select(w_reflect, w_refract, refracted_ray), pending.depth + 1u, select(RAY_REFLECT, RAY_REFRACT, refracted_ray), id);
        *top += 1u;
    }
}
