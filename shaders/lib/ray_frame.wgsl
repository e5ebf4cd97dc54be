// The ray's own frame for watertight edge tests (Woop, Benthin & Wald,
// "Watertight Ray/Triangle Intersection", JCGT 2013). Vertices are sheared so
// that the ray runs along +z through the origin; which side of an edge the ray
// passes becomes the sign of a 2D cross product of two sheared vertices. Two
// primitives sharing an edge compute that product from the same numbers, once
// with each sign, so no ray slips between them.
// import: types

struct RayFrame {
    origin: vec3<f32>,
    // The frame's axes as rows: x = q[kx] − Sx·q[kz], y = q[ky] − Sy·q[kz] and
    // z = Sz·q[kz] for q relative to the origin, with kz the axis along which
    // the direction is largest and Sx, Sy, Sz the shear that cancels the ray's
    // slope. As dot products they need no indexing by a per-ray axis; the
    // products with 0 and 1 are exact (docs/decisions/004).
    x: vec3<f32>,
    y: vec3<f32>,
    z: vec3<f32>,
}

fn ray_frame(ray: Ray) -> RayFrame {
    // Selects rather than branches: the same straight-line code for every ray.
    let a = abs(ray.dir);
    let kz = select(select(2u, 1u, a.y > a.z), 0u, (a.x > a.y) & (a.x > a.z));
    // Swapping x and y for a ray down the axis keeps every winding's sign.
    let swap = ray.dir[kz] < 0.0;
    let kx = select((kz + 1u) % 3u, (kz + 2u) % 3u, swap);
    let ky = select((kz + 2u) % 3u, (kz + 1u) % 3u, swap);
    let axes = vec3<u32>(0u, 1u, 2u);
    let ex = select(vec3<f32>(0.0), vec3<f32>(1.0), axes == vec3<u32>(kx));
    let ey = select(vec3<f32>(0.0), vec3<f32>(1.0), axes == vec3<u32>(ky));
    let ez = select(vec3<f32>(0.0), vec3<f32>(1.0), axes == vec3<u32>(kz));
    let dz = ray.dir[kz];
    return RayFrame(ray.origin, ex - (ray.dir[kx] / dz) * ez, ey - (ray.dir[ky] / dz) * ez, (1.0 / dz) * ez);
}

// `p` in the frame: x and y across the ray, z the distance along it. The sums
// are written out, so that every test that moves `p` into the frame gets the
// same numbers whatever a compiler does with `dot` (fast/ray_frame4.wgsl
// writes them in this order too).
fn to_frame(f: RayFrame, p: vec3<f32>) -> vec3<f32> {
    let q = p - f.origin;
    return vec3<f32>(q.x * f.x.x + q.y * f.x.y + q.z * f.x.z, q.x * f.y.x + q.y * f.y.y + q.z * f.y.z, q.x * f.z.x + q.y * f.z.y + q.z * f.z.z);
}

// Only x and y of `to_frame`, computed the same way: what an inside test needs.
fn to_frame_xy(f: RayFrame, p: vec3<f32>) -> vec2<f32> {
    return to_frame(f, p).xy;
}

// Twice the signed area of (origin, a, b) in the frame's xy plane: positive
// when the ray passes to the left of a→b.
fn edge(a: vec3<f32>, b: vec3<f32>) -> f32 {
    return a.x * b.y - a.y * b.x;
}

// The sign of edge(a, b) (1, −1 or 0 when the ray meets the edge), exactly
// −edge_sign(b, a). It compares the two products instead of subtracting them:
// a compiler may fuse a·b − c·d into one multiply-add, which rounds the two
// orders differently and would let a ray through a shared edge.
fn edge_sign(a: vec2<f32>, b: vec2<f32>) -> f32 {
    let left = a.x * b.y;
    let right = a.y * b.x;
    return select(select(-1.0, 1.0, left > right), 0.0, left == right);
}
