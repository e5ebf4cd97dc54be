// Whitted's ray tree for one eye ray, trace(R) = local(R) + k_m·trace(reflect)
// + k_t·trace(refract), walked with an explicit stack (WGSL has no recursion)
// down to the scene's maximum depth. Each pending ray carries the weight its
// colour contributes to the pixel. The tree is handed, ray by ray and term by
// term, to the kernel's `note_` functions: the trace kernel's do nothing, the
// probe kernel's record the tree for `glint probe` and the viewer's inspector.
// import: bindings bvh checker dispatch primitive reflect refract shade types

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
    var stack: array<PendingRay, RAY_STACK>;
    var top = 0u;
    var pending = PendingRay(eye, vec3<f32>(1.0), 1u, RAY_EYE, NO_RAY);
    var color = vec3<f32>(0.0);
    loop {
        let ray = pending.ray;
        let hit = traverse(ray, 0.0, MISS, false, false);
        deepest = max(deepest, pending.depth);
        if pending.depth == 1u {
            count_ray(select(STAT_EYE_HIT, STAT_EYE_MISS, hit.t == MISS));
        }
        let id = note_ray(pending.kind, pending.parent, pending.depth, ray, pending.weight, hit.t);
        if hit.t == MISS {
            color += pending.weight * uniforms.background;
            continue;
        }
        let p = prims[hit.prim];
        let s = surface_at(p, ray, hit.t);
        let m = material_at(p, s.point);
        note_hit(s, hit.prim);
        let local = shade(s, m, -ray.dir);
        var weight = pending.weight;
        if (uniforms.flags & FLAG_DEPTH_CUE) != 0u {
            let so = depth_cue_scale(hit.t);
            note_cue(so);
            color += weight * (so * local + (1.0 - so) * uniforms.depth_cue_color);
            weight *= so;
        } else {
            color += weight * local;
        }
        // A kernel for a scene whose materials neither reflect nor transmit
        // (HAS_SECONDARY_RAYS false) compiles without the rest.
        if !HAS_SECONDARY_RAYS || pending.depth >= uniforms.max_depth {
            continue;
        }

        // Entering when the ray meets the front of the surface; the outside is air.
        let eta = select(1.0 / m.ior, m.ior, s.backface);
        var k_reflect = m.reflect;
        var k_refract = select(vec3<f32>(0.0), m.transmit, (uniforms.flags & FLAG_REFRACTIONS) != 0u);
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
        if any(w_reflect > vec3<f32>(uniforms.cutoff)) && any(w_reflect > vec3<f32>(0.0)) {
            count_ray(STAT_REFLECT);
            let r = Ray(s.point + s.geometric * eps, reflect_dir(ray.dir, s.shading));
            stack[top] = PendingRay(r, w_reflect, pending.depth + 1u, RAY_REFLECT, id);
            top++;
        }
        let w_refract = weight * k_refract;
        if any(w_refract > vec3<f32>(uniforms.cutoff)) && any(w_refract > vec3<f32>(0.0)) {
            count_ray(STAT_REFRACT);
            let r = Ray(s.point - s.geometric * eps, refracted.xyz);
            stack[top] = PendingRay(r, w_refract, pending.depth + 1u, RAY_REFRACT, id);
            top++;
        }
        continuing {
            // Without secondary rays the tree is the eye ray alone, and the
            // kernel compiles without the stack (a sixth less to compile).
            let done = !HAS_SECONDARY_RAYS || top == 0u;
            if !done {
                top--;
                pending = stack[top];
            }
            break if done;
        }
    }
    return color;
}
