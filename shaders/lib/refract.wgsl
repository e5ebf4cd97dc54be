// Refraction by Snell's law. `n` faces the incoming ray; eta = n1/n2. Returns
// the refracted unit direction in xyz and w = 1, or w = 0 on total internal
// reflection.

fn refract_dir(d: vec3<f32>, n: vec3<f32>, eta: f32) -> vec4<f32> {
    let cos_i = -dot(d, n);
    let sin2_t = eta * eta * (1.0 - cos_i * cos_i);
    if sin2_t > 1.0 {
        return vec4<f32>(0.0);
    }
    let cos_t = sqrt(1.0 - sin2_t);
    return vec4<f32>(normalize(eta * d + (eta * cos_i - cos_t) * n), 1.0);
}
