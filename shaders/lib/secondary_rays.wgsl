// The branches of Whitted's ray tree: the reflected and refracted rays a
// surface spawns, k_r·trace(reflect) + k_t·trace(refract), which wait on the
// ray tree's stack with the weight their colour contributes to the pixel.
// import: bindings dispatch notes primitive reflect refract shade types

struct PendingRay {
    ray: Ray,
    weight: vec3<f32>,
    depth: u32,
    // RAY_EYE, RAY_REFLECT or RAY_REFRACT, and the id `note_ray` gave the ray it came from.
    kind: u32,
    parent: u32,
}

// Where the ray stack's entry `top` is kept. Without transmitters
// (HAS_REFRACTIONS false) a surface spawns its reflected ray alone, so the
// tree is a chain and the stack never holds more than one pending ray: at the
// constant slot 0 it can live in registers (docs/decisions/009-ray-stack-of-the-scenes-depth.md).
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
    // One push for both, in a loop whose count the compiler does not know, so
    // it keeps one copy of the store into the stack (docs/decisions/024-one-walk-in-the-trace-kernel.md).
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
