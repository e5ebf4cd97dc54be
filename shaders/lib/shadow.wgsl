// Hard shadows: the ray from a surface point towards a light that decides S,
// the light let through (the traversal's any-hit query; its prim is the opaque
// occluder that stopped the ray, when t != MISS). Occluders beyond the light
// do not count; the ray leaves along the geometric normal so smooth-shaded
// surfaces do not shadow themselves at the terminator.
// import: bindings bvh dispatch primitive types

struct ShadowRay {
    ray: Ray,
    t_max: f32,
}

fn shadow_ray(point: vec3<f32>, geometric: vec3<f32>, to_light: vec3<f32>, distance: f32) -> ShadowRay {
    let eps = ray_epsilon(point);
    return ShadowRay(Ray(point + geometric * eps, to_light), distance - eps);
}

fn shadows_traced() -> bool {
    return (uniforms.flags & FLAG_SHADOWS) != 0u;
}

// Whether transmissive occluders tint the light instead of stopping it. Only
// transmitters tint: a scene without them (HAS_REFRACTIONS false) or whose
// shadows are opaque (HAS_TINTED_SHADOWS false) compiles the opaque test alone.
fn shadows_tinted() -> bool {
    return HAS_REFRACTIONS && HAS_TINTED_SHADOWS && (uniforms.flags & FLAG_TINTED_SHADOWS) != 0u;
}

// S for a light whose shadow ray is not traced (shadows off): all of it.
fn unshadowed() -> Hit {
    return Hit(MISS, 0u, vec3<f32>(1.0), 0u);
}

// S at the surface `s` from a light in direction `to_light` at `distance`: the
// any hit of the shadow ray towards it, or all of the light when shadows are off.
fn cast_shadow_ray(s: Surface, to_light: vec3<f32>, distance: f32) -> Hit {
    if !shadows_traced() {
        return unshadowed();
    }
    count_ray(STAT_SHADOW);
    let shadow = shadow_ray(s.point, s.geometric, to_light, distance);
    return traverse(shadow.ray, 0.0, shadow.t_max, true, shadows_tinted());
}
