// Hard shadows: how much of a light reaches `point` (the hit's transmittance;
// its prim is the opaque occluder that stopped the ray, when t != MISS).
// Occluders beyond the light do not count; the ray leaves along the geometric
// normal so smooth-shaded surfaces do not shadow themselves at the terminator.
// import: bindings bvh dispatch primitive types

fn light_visibility(point: vec3<f32>, geometric: vec3<f32>, to_light: vec3<f32>, distance: f32) -> Hit {
    if (uniforms.flags & FLAG_SHADOWS) == 0u {
        return Hit(MISS, 0u, vec3<f32>(1.0), 0u);
    }
    count_ray(STAT_SHADOW);
    let eps = ray_epsilon(point);
    let ray = Ray(point + geometric * eps, to_light);
    // Only transmitters tint: a scene without them (HAS_SECONDARY_RAYS false)
    // compiles the opaque test alone.
    let tinted = HAS_SECONDARY_RAYS && (uniforms.flags & FLAG_TINTED_SHADOWS) != 0u;
    return traverse(ray, 0.0, distance - eps, true, tinted);
}
