// The reflected and the refracted ray that `pending` spawns where it hits
// surface `s`, pushed on the ray stack, each if it `spawns`, the reflected one
// first, off the surface on its own side. A tuning may put
// fast/push_rays.wgsl in this file's place.
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
    if spawns(w_reflect) {
        count_ray(STAT_REFLECT);
        let r = Ray(s.point + eps * s.geometric, reflect_dir(pending.ray.dir, s.shading));
        (*stack)[stack_slot(*top)] = PendingRay(r, w_reflect, pending.depth + 1u, RAY_REFLECT, id);
        *top += 1u;
    }
    if spawns(w_refract) {
        count_ray(STAT_REFRACT);
        let r = Ray(s.point - eps * s.geometric, refracted);
        (*stack)[stack_slot(*top)] = PendingRay(r, w_refract, pending.depth + 1u, RAY_REFRACT, id);
        *top += 1u;
    }
}
