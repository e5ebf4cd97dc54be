// The `diffuse` debug view (primary kernel): direct diffuse light alone.
// import: bindings bvh primitive shadow types

// Direct diffuse light only,
//   Σ_lights k_d·O_d·I_l·max(0, N·L)·V/d²
// with inverse-square falloff whatever the scene's attenuation (d = 1 for a
// directional light), V = 1 only when nothing at all blocks the light (every
// occluder opaque), and no ambient, specular, reflection or refraction.
fn diffuse_only(s: Surface, m: GpuMaterial) -> vec3<f32> {
    var color = vec3<f32>(0.0);
    for (var i = 0u; i < uniforms.light_count; i++) {
        let light = lights[i];
        var l = -light.position;
        var distance = MISS;
        var falloff = 1.0;
        if light.kind != LIGHT_DIRECTIONAL {
            let to_light = light.position - s.point;
            distance = length(to_light);
            l = to_light / distance;
            falloff = 1.0 / (distance * distance);
        }
        let n_dot_l = dot(s.shading, l);
        if n_dot_l <= 0.0 || dot(s.geometric, l) <= 0.0 {
            continue;
        }
        let shadow = shadow_ray(s.point, s.geometric, l, distance);
        let blocked = traverse(shadow.ray, 0.0, shadow.t_max, true, false).t != MISS;
        if !blocked {
            color += m.kd * m.color * light.radiance * n_dot_l * falloff;
        }
    }
    return color;
}
