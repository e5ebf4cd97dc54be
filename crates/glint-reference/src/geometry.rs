//! The primitives in f64: intersection and normals, written from the equations
//! rather than ported from the WGSL, so that a mistake shared by both would have
//! to be made twice. Triangles and polygons are tested in the ray's frame
//! ([`RayFrame`]), which makes them watertight as the kernels are.

use glam::DVec3;
use glint_scene::Shape;

/// One primitive of the scene, converted to f64 once.
#[derive(Debug, Clone)]
pub(crate) enum Geom {
    Sphere {
        center: DVec3,
        radius: f64,
    },
    Triangle {
        v: [DVec3; 3],
        /// (v1 − v0) × (v2 − v0), not normalised.
        n: DVec3,
        normals: Option<[DVec3; 3]>,
    },
    Polygon {
        /// Unit normal (Newell).
        normal: DVec3,
        /// A point of the plane (the vertex average).
        origin: DVec3,
        vertices: Vec<DVec3>,
    },
    Cone {
        base: DVec3,
        /// Unit axis from base to apex.
        axis: DVec3,
        h: f64,
        r0: f64,
        /// Radius slope (r1 − r0)/h.
        k: f64,
    },
    Plane {
        /// Unit normal.
        normal: DVec3,
        point: DVec3,
    },
    /// A degenerate shape (zero radius, zero area, zero height): never hit.
    Empty,
}

fn d3(v: glam::Vec3) -> DVec3 {
    DVec3::new(f64::from(v.x), f64::from(v.y), f64::from(v.z))
}

impl Geom {
    pub(crate) fn new(shape: &Shape) -> Geom {
        match shape {
            Shape::Sphere { center, radius } => {
                let radius = f64::from(*radius).abs();
                if radius > 0.0 { Geom::Sphere { center: d3(*center), radius } } else { Geom::Empty }
            }
            Shape::Triangle { vertices, normals } => {
                let v = vertices.map(d3);
                let n = (v[1] - v[0]).cross(v[2] - v[0]);
                if n.length_squared() > 0.0 {
                    Geom::Triangle { v, n, normals: normals.map(|ns| ns.map(d3)) }
                } else {
                    Geom::Empty
                }
            }
            Shape::Polygon { vertices } => {
                if vertices.len() < 3 {
                    return Geom::Empty;
                }
                let v: Vec<DVec3> = vertices.iter().map(|p| d3(*p)).collect();
                // Newell's normal: twice the vector area, exact for planar polygons
                // of any shape.
                let mut area = DVec3::ZERO;
                for i in 0..v.len() {
                    area += v[i].cross(v[(i + 1) % v.len()]);
                }
                let size = v.iter().map(|p| p.length_squared()).fold(0.0, f64::max);
                if area.length() <= 1e-12 * size.max(1e-300) {
                    return Geom::Empty;
                }
                let normal = area.normalize();
                let origin = v.iter().copied().sum::<DVec3>() / v.len() as f64;
                Geom::Polygon { normal, origin, vertices: v }
            }
            Shape::Cone { base, base_radius, apex, apex_radius } => {
                let (base, apex) = (d3(*base), d3(*apex));
                let h = (apex - base).length();
                let (r0, r1) = (f64::from(*base_radius), f64::from(*apex_radius));
                if h == 0.0 || (r0 <= 0.0 && r1 <= 0.0) {
                    return Geom::Empty;
                }
                Geom::Cone { base, axis: (apex - base) / h, h, r0, k: (r1 - r0) / h }
            }
            Shape::Plane { point, normal } => Geom::Plane { normal: d3(*normal).normalize(), point: d3(*point) },
        }
    }

    /// The unit normal of a flat primitive (a polygon or a plane), whose
    /// checker counts tiles in the plane's own coordinates.
    pub(crate) fn flat_normal(&self) -> Option<DVec3> {
        match self {
            Geom::Polygon { normal, .. } | Geom::Plane { normal, .. } => Some(*normal),
            _ => None,
        }
    }

    /// The nearest parameter t in (t_min, t_max) where o + t·d meets the surface.
    pub(crate) fn intersect(&self, o: DVec3, d: DVec3, t_min: f64, t_max: f64) -> Option<f64> {
        let in_range = |t: f64| t > t_min && t < t_max;
        match self {
            Geom::Sphere { center, radius } => {
                // a t² + 2 b t + c = 0
                let oc = o - *center;
                let a = d.length_squared();
                let b = oc.dot(d);
                let c = oc.length_squared() - radius * radius;
                let disc = b * b - a * c;
                if disc < 0.0 {
                    return None;
                }
                let q = -(b + b.signum() * disc.sqrt());
                let (t0, t1) = if q == 0.0 { (0.0, 0.0) } else { order(q / a, c / q) };
                [t0, t1].into_iter().find(|&t| in_range(t))
            }
            Geom::Triangle { v, .. } => {
                let frame = RayFrame::new(o, d);
                let [a, b, c] = v.map(|p| frame.point(p));
                let (u, v, w) = (edge(b, c), edge(c, a), edge(a, b));
                // Zero on an edge: every triangle sharing it is hit.
                if (u < 0.0 || v < 0.0 || w < 0.0) && (u > 0.0 || v > 0.0 || w > 0.0) {
                    return None;
                }
                let det = u + v + w;
                if det == 0.0 {
                    return None;
                }
                let t = (u * a.z + v * b.z + w * c.z) / det;
                in_range(t).then_some(t)
            }
            Geom::Polygon { normal, origin, vertices } => {
                let t = plane_hit(*normal, *origin, o, d).filter(|&t| in_range(t))?;
                let frame = RayFrame::new(o, d);
                let sheared: Vec<DVec3> = vertices.iter().map(|p| frame.point(*p)).collect();
                even_odd(&sheared).then_some(t)
            }
            Geom::Cone { base, axis, h, r0, k } => {
                // |q⊥|² = (r0 + k s)², q = o + t d − B, s = q·a.
                let oc = o - *base;
                let (os, ds) = (oc.dot(*axis), d.dot(*axis));
                let (op, dp) = (oc - os * *axis, d - ds * *axis);
                let (m, n) = (r0 + k * os, k * ds);
                let a = dp.length_squared() - n * n;
                let b = op.dot(dp) - m * n;
                let c = op.length_squared() - m * m;
                let accept = |t: f64| {
                    let s = os + t * ds;
                    in_range(t) && (0.0..=*h).contains(&s) && r0 + k * s >= 0.0
                };
                let roots: [f64; 2] = if a == 0.0 {
                    if b == 0.0 {
                        return None;
                    }
                    [-c / (2.0 * b), f64::NAN]
                } else {
                    let disc = b * b - a * c;
                    if disc < 0.0 {
                        return None;
                    }
                    let q = -(b + b.signum() * disc.sqrt());
                    if q == 0.0 {
                        [0.0, f64::NAN]
                    } else {
                        let (t0, t1) = order(q / a, c / q);
                        [t0, t1]
                    }
                };
                roots.into_iter().find(|&t| accept(t))
            }
            Geom::Plane { normal, point } => plane_hit(*normal, *point, o, d).filter(|&t| in_range(t)),
            Geom::Empty => None,
        }
    }

    /// Outward geometric normal and shading normal (both unit) at point `p` on the surface.
    pub(crate) fn normals(&self, p: DVec3) -> (DVec3, DVec3) {
        match self {
            Geom::Sphere { center, radius } => {
                let n = ((p - *center) / *radius).normalize();
                (n, n)
            }
            Geom::Triangle { v, n, normals } => {
                let ng = n.normalize();
                let ns = match normals {
                    Some(vn) => {
                        let w = barycentric(v, *n, p);
                        let s = w.x * vn[0] + w.y * vn[1] + w.z * vn[2];
                        if s.length_squared() > 0.0 { s.normalize() } else { ng }
                    }
                    None => ng,
                };
                (ng, ns)
            }
            Geom::Polygon { normal, .. } | Geom::Plane { normal, .. } => (*normal, *normal),
            Geom::Cone { base, axis, k, .. } => {
                let q = p - *base;
                let radial = (q - q.dot(*axis) * *axis).normalize();
                let n = (radial - *k * *axis).normalize();
                (n, n)
            }
            Geom::Empty => (DVec3::Z, DVec3::Z),
        }
    }
}

/// Where o + t·d meets the plane through `point` with normal `n`:
/// t = n·(point − o) / n·d, none for a ray parallel to it.
fn plane_hit(n: DVec3, point: DVec3, o: DVec3, d: DVec3) -> Option<f64> {
    let denom = n.dot(d);
    (denom != 0.0).then(|| n.dot(point - o) / denom)
}

fn order(a: f64, b: f64) -> (f64, f64) {
    if a <= b { (a, b) } else { (b, a) }
}

/// Barycentric weights of `p` (in the triangle's plane) for v0, v1, v2 from the
/// signed areas of the sub-triangles opposite each vertex.
fn barycentric(v: &[DVec3; 3], n: DVec3, p: DVec3) -> DVec3 {
    let inv = 1.0 / n.length_squared();
    let w0 = (v[2] - v[1]).cross(p - v[1]).dot(n) * inv;
    let w1 = (v[0] - v[2]).cross(p - v[2]).dot(n) * inv;
    let w2 = (v[1] - v[0]).cross(p - v[0]).dot(n) * inv;
    DVec3::new(w0, w1, w2)
}

/// The ray's frame (Woop, Benthin & Wald 2013): points sheared so that the ray
/// runs along +z through the origin. Which side of an edge the ray passes is
/// then the sign of [`edge`] of two sheared vertices, which a neighbour sharing
/// the edge computes from the same numbers with the opposite sign: no ray
/// passes between two primitives.
struct RayFrame {
    origin: DVec3,
    /// Axes x, y, z of the frame; z is the direction's largest component.
    axes: [usize; 3],
    /// x − Sx·z, y − Sy·z cancel the ray's slope; Sz·z is the distance t.
    shear: DVec3,
}

impl RayFrame {
    fn new(origin: DVec3, d: DVec3) -> Self {
        let a = d.abs();
        let kz = if a.x > a.y && a.x > a.z { 0 } else if a.y > a.z { 1 } else { 2 };
        let (mut kx, mut ky) = ((kz + 1) % 3, (kz + 2) % 3);
        // Swapping for a ray down its axis keeps every winding's sign.
        if d[kz] < 0.0 {
            std::mem::swap(&mut kx, &mut ky);
        }
        Self { origin, axes: [kx, ky, kz], shear: DVec3::new(d[kx] / d[kz], d[ky] / d[kz], 1.0 / d[kz]) }
    }

    fn point(&self, p: DVec3) -> DVec3 {
        let q = p - self.origin;
        let [kx, ky, kz] = self.axes;
        DVec3::new(q[kx] - self.shear.x * q[kz], q[ky] - self.shear.y * q[kz], self.shear.z * q[kz])
    }
}

/// Twice the signed area of (origin, a, b) in the frame's xy plane; exactly −edge(b, a).
fn edge(a: DVec3, b: DVec3) -> f64 {
    a.x * b.y - a.y * b.x
}

/// Even-odd rule in the ray's frame: the ray (the origin) is inside when an odd
/// number of edges cross the +x half-line from it. A vertex on that line counts
/// as above it and an edge through the origin as to its right, one tie rule for
/// every polygon, so a ray on a shared edge is inside exactly one of them.
fn even_odd(vertices: &[DVec3]) -> bool {
    let mut inside = false;
    let mut prev = vertices[vertices.len() - 1];
    for &cur in vertices {
        let rising = cur.y >= 0.0;
        if (prev.y >= 0.0) != rising {
            let e = edge(prev, cur);
            if e == 0.0 || (e > 0.0) == rising {
                inside = !inside;
            }
        }
        prev = cur;
    }
    inside
}

#[cfg(test)]
mod tests {
    use super::*;
    use glam::Vec3;

    /// Seven faces around a shared centre on a shallow cone, all seen from
    /// their front by the eyes used below.
    fn fan(as_polygons: bool) -> (Vec<DVec3>, Vec<Geom>) {
        let centre = Vec3::new(0.1, -0.2, 0.7);
        let ring: Vec<Vec3> = (0..7)
            .map(|k| {
                let a = k as f32 * std::f32::consts::TAU / 7.0 + 0.3;
                Vec3::new(a.cos(), a.sin(), 0.2 * (k % 3) as f32)
            })
            .collect();
        let faces = (0..7)
            .map(|k| {
                let vertices = [centre, ring[k], ring[(k + 1) % 7]];
                let shape = if as_polygons {
                    Shape::Polygon { vertices: vertices.to_vec() }
                } else {
                    Shape::Triangle { vertices, normals: None }
                };
                Geom::new(&shape)
            })
            .collect();
        let mut points = vec![centre.as_dvec3()];
        points.extend(ring.iter().map(|v| v.as_dvec3()));
        (points, faces)
    }

    #[test]
    fn rays_through_shared_edges_and_vertices_hit_and_polygons_count_once() {
        for as_polygons in [false, true] {
            let (points, faces) = fan(as_polygons);
            let centre = points[0];
            let mut targets = vec![centre];
            for (k, spoke) in points[1..].iter().enumerate() {
                targets.extend((1..40).map(|i| centre + (*spoke - centre) * (f64::from(i) / 40.0 + k as f64 * 1e-3)));
            }
            for (i, target) in targets.iter().enumerate() {
                for eye in [DVec3::new(0.3, 0.2, 6.0), DVec3::new(-1.1, 0.7, 4.0), DVec3::new(0.9, -1.3, 5.0)] {
                    let d = (*target - eye).normalize();
                    let hits = faces.iter().filter(|f| f.intersect(eye, d, 0.0, f64::INFINITY).is_some()).count();
                    assert!(hits >= 1, "polygons {as_polygons}, target {i}: the ray slipped through");
                    if as_polygons && i > 0 {
                        assert_eq!(hits, 1, "target {i}: a ray on a shared edge is inside exactly one polygon");
                    }
                }
            }
        }
    }

    #[test]
    fn planes_are_hit_from_both_sides_and_missed_by_parallel_rays() {
        let floor = Geom::new(&Shape::Plane { point: Vec3::new(5.0, -1.0, 2.0), normal: Vec3::Y });
        let hit = |o: DVec3, d: DVec3, t_max: f64| floor.intersect(o, d, 0.0, t_max);
        assert_eq!(hit(DVec3::new(0.0, 1.0, 0.0), DVec3::NEG_Y, f64::INFINITY), Some(2.0));
        assert_eq!(hit(DVec3::new(3.0, -4.0, 0.0), DVec3::Y, f64::INFINITY), Some(3.0), "from below");
        assert_eq!(hit(DVec3::new(0.0, 1.0, 0.0), DVec3::X, f64::INFINITY), None, "parallel");
        assert_eq!(hit(DVec3::new(0.0, 1.0, 0.0), DVec3::Y, f64::INFINITY), None, "behind the ray");
        assert_eq!(hit(DVec3::new(0.0, 1.0, 0.0), DVec3::NEG_Y, 1.5), None, "beyond t_max");
        assert_eq!(floor.normals(DVec3::ZERO), (DVec3::Y, DVec3::Y));
    }
}
