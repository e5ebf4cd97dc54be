//! The primitives in f64: intersection and normals, written from the equations
//! rather than ported from the WGSL, so that a mistake shared by both would have
//! to be made twice.

use glam::{DVec2, DVec3};
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
        /// Orthonormal in-plane basis for the 2D inside test.
        e1: DVec3,
        e2: DVec3,
        /// Vertices in that basis, relative to `origin`.
        flat: Vec<DVec2>,
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
    /// A degenerate shape (zero radius, zero area, zero height): never hit.
    Empty,
}

fn d3(v: glam::Vec3) -> DVec3 {
    DVec3::new(f64::from(v.x), f64::from(v.y), f64::from(v.z))
}

/// Some unit vector perpendicular to unit `n`.
pub(crate) fn perpendicular(n: DVec3) -> DVec3 {
    let a = if n.x.abs() < 0.6 { DVec3::X } else if n.y.abs() < 0.6 { DVec3::Y } else { DVec3::Z };
    (a - n * a.dot(n)).normalize()
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
                let e1 = perpendicular(normal);
                let e2 = normal.cross(e1);
                let flat = v.iter().map(|p| DVec2::new((*p - origin).dot(e1), (*p - origin).dot(e2))).collect();
                Geom::Polygon { normal, origin, e1, e2, flat }
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
            Geom::Triangle { v, n, .. } => {
                let denom = n.dot(d);
                if denom == 0.0 {
                    return None;
                }
                let t = n.dot(v[0] - o) / denom;
                if !in_range(t) {
                    return None;
                }
                let w = barycentric(v, *n, o + t * d);
                (w.min_element() >= 0.0).then_some(t)
            }
            Geom::Polygon { normal, origin, e1, e2, flat } => {
                let denom = normal.dot(d);
                if denom == 0.0 {
                    return None;
                }
                let t = normal.dot(*origin - o) / denom;
                if !in_range(t) {
                    return None;
                }
                let p = o + t * d - *origin;
                even_odd(flat, DVec2::new(p.dot(*e1), p.dot(*e2))).then_some(t)
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
            Geom::Polygon { normal, .. } => (*normal, *normal),
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

/// Even-odd rule: count crossings of the half-line from `q` towards +x.
fn even_odd(poly: &[DVec2], q: DVec2) -> bool {
    let mut inside = false;
    let mut j = poly.len() - 1;
    for i in 0..poly.len() {
        let (a, b) = (poly[j], poly[i]);
        if (a.y > q.y) != (b.y > q.y) {
            let x = a.x + (q.y - a.y) * (b.x - a.x) / (b.y - a.y);
            if x > q.x {
                inside = !inside;
            }
        }
        j = i;
    }
    inside
}
