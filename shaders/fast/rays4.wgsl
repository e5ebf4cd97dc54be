// Four rays side by side, for ray packets (packet.wgsl): vector k's
// coordinates in component k of each vec4, so that one vec4 operation does
// an operation of all four.
// import: types

struct Vec3x4 {
    x: vec4<f32>,
    y: vec4<f32>,
    z: vec4<f32>,
}

fn gather4(a: vec3<f32>, b: vec3<f32>, c: vec3<f32>, d: vec3<f32>) -> Vec3x4 {
    return Vec3x4(vec4<f32>(a.x, b.x, c.x, d.x), vec4<f32>(a.y, b.y, c.y, d.y), vec4<f32>(a.z, b.z, c.z, d.z));
}

fn vector_of(v: Vec3x4, k: u32) -> vec3<f32> {
    return vec3<f32>(v.x[k], v.y[k], v.z[k]);
}

// `dot(a, b)` for each of four vectors b, by the same `dot` one ray uses, so
// that each gets the same bits as alone.
fn dot4(a: vec3<f32>, b: Vec3x4) -> vec4<f32> {
    return vec4<f32>(dot(a, vector_of(b, 0u)), dot(a, vector_of(b, 1u)), dot(a, vector_of(b, 2u)), dot(a, vector_of(b, 3u)));
}

// Four rays, the eye rays of a 2×2 block of pixels (packet.wgsl).
struct Rays4 {
    origin: Vec3x4,
    dir: Vec3x4,
}

fn ray_of(rays: Rays4, k: u32) -> Ray {
    return Ray(vector_of(rays.origin, k), vector_of(rays.dir, k));
}
