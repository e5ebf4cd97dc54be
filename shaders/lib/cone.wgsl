// Ray intersection with an open cone or cylinder (no end caps): radius r0 at the
// base B, r1 at the apex A. With axis a = (A − B)/h and slope k = (r1 − r0)/h, a
// point P lies on the surface when |q − (q·a)a| = r0 + k(q·a), q = P − B, and
// 0 ≤ q·a ≤ h.
// import: types

fn cone_intersect(p: GpuPrim, ray: Ray, t_min_in: f32, t_max_in: f32) -> f32 {
    let base = p.a.xyz;
    let r0 = p.a.w;
    let axis_full = p.b.xyz - base;
    let h = length(axis_full);
    let axis = axis_full / h;
    let k = (p.b.w - r0) / h;
    // Solve from the point of the ray nearest the cone's middle: from a distant
    // origin the quadratic's discriminant cancels badly in f32.
    let shift = dot(base + 0.5 * axis_full - ray.origin, ray.dir);
    let t_min = t_min_in - shift;
    let t_max = t_max_in - shift;
    let oc = ray.origin + shift * ray.dir - base;
    let oc_a = dot(oc, axis);
    let d_a = dot(ray.dir, axis);
    let oc_perp = oc - oc_a * axis;
    let d_perp = ray.dir - d_a * axis;
    let m = r0 + k * oc_a;
    let n = k * d_a;
    let qa = dot(d_perp, d_perp) - n * n;
    let qb = dot(oc_perp, d_perp) - m * n;
    let qc = dot(oc_perp, oc_perp) - m * m;
    if abs(qa) < 1e-12 {
        // Ray parallel to a generating line: one root at most.
        if abs(qb) < 1e-12 {
            return MISS;
        }
        let t = -qc / (2.0 * qb);
        return select(MISS, t + shift, cone_accepts(oc_a, d_a, h, r0, k, t, t_min, t_max));
    }
    let disc = qb * qb - qa * qc;
    if disc < 0.0 {
        return MISS;
    }
    let s = sqrt(disc);
    let ta = (-qb - s) / qa;
    let tb = (-qb + s) / qa;
    let t0 = min(ta, tb);
    let t1 = max(ta, tb);
    if cone_accepts(oc_a, d_a, h, r0, k, t0, t_min, t_max) {
        return t0 + shift;
    }
    if cone_accepts(oc_a, d_a, h, r0, k, t1, t_min, t_max) {
        return t1 + shift;
    }
    return MISS;
}

// The root is in range, between the end planes, and on the cone's own nappe.
fn cone_accepts(oc_a: f32, d_a: f32, h: f32, r0: f32, k: f32, t: f32, t_min: f32, t_max: f32) -> bool {
    let s = oc_a + t * d_a;
    return t > t_min && t < t_max && s >= 0.0 && s <= h && r0 + k * s >= 0.0;
}

fn cone_normal(p: GpuPrim, point: vec3<f32>) -> vec3<f32> {
    let base = p.a.xyz;
    let axis_full = p.b.xyz - base;
    let h = length(axis_full);
    let axis = axis_full / h;
    let k = (p.b.w - p.a.w) / h;
    let q = point - base;
    let radial = normalize(q - dot(q, axis) * axis);
    return normalize(radial - k * axis);
}
