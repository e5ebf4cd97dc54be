// The ray frames of ray_frame.wgsl for the four rays of a packet.
// import: fast/rays4 ray_frame

// The frames of four rays, ray k's in component k of each member: what a
// packet (packet.wgsl) tests its primitives in.
struct RayFrame4 {
    origin: Vec3x4,
    x: Vec3x4,
    y: Vec3x4,
    z: Vec3x4,
}

fn ray_frame4(rays: Rays4) -> RayFrame4 {
    let f0 = ray_frame(ray_of(rays, 0u));
    let f1 = ray_frame(ray_of(rays, 1u));
    let f2 = ray_frame(ray_of(rays, 2u));
    let f3 = ray_frame(ray_of(rays, 3u));
    return RayFrame4(rays.origin, gather4(f0.x, f1.x, f2.x, f3.x), gather4(f0.y, f1.y, f2.y, f3.y), gather4(f0.z, f1.z, f2.z, f3.z));
}

// `to_frame` for four rays at once.
fn to_frame4(f: RayFrame4, p: vec3<f32>) -> Vec3x4 {
    let qx = p.x - f.origin.x;
    let qy = p.y - f.origin.y;
    let qz = p.z - f.origin.z;
    return Vec3x4(qx * f.x.x + qy * f.x.y + qz * f.x.z, qx * f.y.x + qy * f.y.y + qz * f.y.z, qx * f.z.x + qy * f.z.y + qz * f.z.z);
}

// `edge` and `edge_sign` for four rays at once.
fn edge4(a: Vec3x4, b: Vec3x4) -> vec4<f32> {
    return a.x * b.y - a.y * b.x;
}

fn edge_sign4(a: Vec3x4, b: Vec3x4) -> vec4<f32> {
    let left = a.x * b.y;
    let right = a.y * b.x;
    return select(select(vec4<f32>(-1.0), vec4<f32>(1.0), left > right), vec4<f32>(0.0), left == right);
}
