// Mirror reflection and Schlick's Fresnel approximation.

// r = d − 2(d·n)n
fn reflect_dir(d: vec3<f32>, n: vec3<f32>) -> vec3<f32> {
    return d - 2.0 * dot(d, n) * n;
}

// F = F0 + (1 − F0)(1 − cos θ)^5
fn schlick(f0: vec3<f32>, cos_theta: f32) -> vec3<f32> {
    let m = clamp(1.0 - cos_theta, 0.0, 1.0);
    let m2 = m * m;
    return f0 + (vec3<f32>(1.0) - f0) * (m2 * m2 * m);
}

// Schlick's F0 for an interface between indices n1 and n2.
fn dielectric_f0(n1: f32, n2: f32) -> f32 {
    let r = (n1 - n2) / (n1 + n2);
    return r * r;
}
