// The pushes of lib/push_rays.wgsl, the same rays in the same order, as one
// push in a loop that lavapipe compiles once (docs/decisions/057-loops-over-bit-masks.md):
// it steps through a bit mask of the rays spawned, a count the compiler does
// not know, so it keeps one copy of the store into the stack.
// import: dispatch primitive ray_stack reflect types

fn push_rays(
    pending: PendingRay,
    s: Surface,
    refracted: vec3<f32>,
    w_reflect: vec3<f32>,
    w_refract: vec3<f32>,
    id: u32,
    stack: ptr<function, array<PendingRay, MAX_DEPTH>>,
    top: ptr<function, u32>,
) {
    let eps = ray_epsilon(s.point);
    // Bit 0: the reflected ray, bit 1: the refracted one.
    var spawned = 0u;
    if spawns(w_reflect) {
        count_ray(STAT_REFLECT);
        spawned |= 1u;
    }
    if spawns(w_refract) {
        count_ray(STAT_REFRACT);
        spawned |= 2u;
    }
    while spawned != 0u {
        let refracted_ray = firstTrailingBit(spawned) == 1u;
        spawned &= spawned - 1u;
        let r = Ray(
            s.point + select(eps, -eps, refracted_ray) * s.geometric,
            select(reflect_dir(pending.ray.dir, s.shading), refracted, refracted_ray),
        );
        (*stack)[stack_slot(*top)] = PendingRay(r, select(w_reflect, w_refract, refracted_ray), pending.depth + 1u, select(RAY_REFLECT, RAY_REFRACT, refracted_ray), id);
        *top += 1u;
    }
}
