// The branches of Whitted's ray tree: the reflected and refracted rays a
// surface spawns, k_r·trace(reflect) + k_t·trace(refract), which wait on the
// ray tree's stack with the weight their colour contributes to the pixel.
// import: bindings notes primitive push_rays ray_stack reflect refract shade types

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
    // and the compiler drops the refraction with the constant.
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
    push_rays(pending, s, refracted.xyz, weight * k_reflect, weight * k_refract, id, stack, top);
}
