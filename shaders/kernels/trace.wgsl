// The trace kernel: one sample per pixel per dispatch, Whitted's ray tree walked
// with an explicit stack (WGSL has no recursion). Each pending ray carries the
// weight its colour contributes to the pixel.
// import: bindings bvh camera dispatch primitive reflect refract sample shade types

struct PendingRay {
    ray: Ray,
    weight: vec3<f32>,
    depth: u32,
}

fn trace_pixel(eye: Ray) -> vec3<f32> {
    var stack: array<PendingRay, RAY_STACK>;
    stack[0] = PendingRay(eye, vec3<f32>(1.0), 1u);
    var top = 1u;
    var color = vec3<f32>(0.0);
    while top > 0u {
        top--;
        let pending = stack[top];
        let ray = pending.ray;
        let hit = traverse(ray, 0.0, MISS, false, false);
        if pending.depth == 1u {
            count_ray(select(STAT_EYE_HIT, STAT_EYE_MISS, hit.t == MISS));
        }
        if hit.t == MISS {
            color += pending.weight * uniforms.background;
            continue;
        }
        let p = prims[hit.prim];
        let m = materials[prim_material(p)];
        let s = surface_at(p, ray, hit.t);
        let local = shade(s, m, -ray.dir);
        var weight = pending.weight;
        if (uniforms.flags & FLAG_DEPTH_CUE) != 0u {
            let so = depth_cue_scale(hit.t);
            color += weight * (so * local + (1.0 - so) * uniforms.depth_cue_color);
            weight *= so;
        } else {
            color += weight * local;
        }
        if pending.depth >= uniforms.max_depth {
            continue;
        }

        // Entering when the ray meets the front of the surface; the outside is air.
        let eta = select(1.0 / m.ior, m.ior, s.backface);
        var k_reflect = m.reflect;
        var k_refract = select(vec3<f32>(0.0), m.transmit, (uniforms.flags & FLAG_REFRACTIONS) != 0u);
        let refracted = refract_dir(ray.dir, s.shading, eta);
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
            stack[top] = PendingRay(r, w_reflect, pending.depth + 1u);
            top++;
        }
        let w_refract = weight * k_refract;
        if any(w_refract > vec3<f32>(uniforms.cutoff)) && any(w_refract > vec3<f32>(0.0)) {
            count_ray(STAT_REFRACT);
            let r = Ray(s.point - s.geometric * eps, refracted.xyz);
            stack[top] = PendingRay(r, w_refract, pending.depth + 1u);
            top++;
        }
    }
    return color;
}

@compute @workgroup_size(8, 8)
fn trace_main(
    @builtin(global_invocation_id) gid: vec3<u32>,
    @builtin(workgroup_id) wid: vec3<u32>,
    @builtin(num_workgroups) groups: vec3<u32>,
) {
    let pixel = band_pixel(gid);
    if in_band(pixel) {
        accumulate(pixel, trace_pixel(camera_ray(vec2<f32>(pixel) + sample_offset(pixel))));
    }
    flush_ray_counts(wid, groups);
}
