//! The primitives of the scene model, and the one place each is built and
//! checked from what a file says (pbrt's `Shape::Create`): every loader (TOML,
//! NFF, OBJ) calls these constructors, so the same input has the same outcome
//! in every format. The policy (docs/scene-format.md, "Errors and warnings"):
//!
//! * a **degenerate** shape (a sphere of radius 0, a triangle or polygon with
//!   no area, a cone whose ends coincide or whose radii are both 0) has no
//!   surface to render: it is skipped, with a warning naming file and line;
//! * a **non-planar** polygon is kept, with a warning: it is intersected in the
//!   plane of its Newell normal, which is well defined, and files written by
//!   other tools (the SPD generators among them) contain slightly bent ones;
//! * a shape whose bounds **overflow** 32-bit floats cannot be placed in the
//!   BVH: an error.
//!
//! Values out of their domain (a negative radius, NaN) are the loaders' to
//! report at the token that holds them; the constructors take them as checked.

use glam::Vec3;

/// Why what a file describes does not become a shape.
#[derive(Debug, Clone, PartialEq)]
pub enum ShapeProblem {
    /// No surface to render: the loader skips the shape and warns with this text.
    Degenerate(String),
    /// The shape's bounds overflow 32-bit floats: the loader reports an error.
    Overflows,
}

/// A polygon whose vertices stray further than this from its plane, relative to
/// its size, is reported as non-planar (and kept).
pub const NON_PLANAR_TOLERANCE: f32 = 1e-4;

/// One geometric primitive.
#[derive(Debug, Clone, PartialEq)]
pub enum Shape {
    Sphere { center: Vec3, radius: f32 },
    /// Optional per-vertex normals make the triangle smooth-shaded.
    Triangle { vertices: [Vec3; 3], normals: Option<[Vec3; 3]> },
    /// A planar polygon, convex or concave (even-odd rule).
    Polygon { vertices: Vec<Vec3> },
    /// An open cone or cylinder without end caps: radius `base_radius` at `base`,
    /// `apex_radius` at `apex`.
    Cone { base: Vec3, base_radius: f32, apex: Vec3, apex_radius: f32 },
}

impl Shape {
    /// A sphere; `radius` must not be negative.
    pub fn sphere(center: Vec3, radius: f32) -> Result<Shape, ShapeProblem> {
        if radius == 0.0 {
            return Err(ShapeProblem::Degenerate("sphere of radius 0 skipped".into()));
        }
        finite(Shape::Sphere { center, radius })
    }

    /// An open cone or cylinder; the radii must not be negative. A cone whose
    /// base radius is 0 is stored with its ends swapped (the same surface), so
    /// the base is always the wide end.
    pub fn cone(base: Vec3, base_radius: f32, apex: Vec3, apex_radius: f32) -> Result<Shape, ShapeProblem> {
        // Ends closer than f32 can measure leave the axis without a direction.
        if (apex - base).length() == 0.0 || (base_radius == 0.0 && apex_radius == 0.0) {
            return Err(ShapeProblem::Degenerate("degenerate cone (base equals apex, or both radii 0) skipped".into()));
        }
        finite(if base_radius == 0.0 {
            Shape::Cone { base: apex, base_radius: apex_radius, apex: base, apex_radius: base_radius }
        } else {
            Shape::Cone { base, base_radius, apex, apex_radius }
        })
    }

    /// A triangle, smooth-shaded when it has (unit) vertex normals.
    pub fn triangle(vertices: [Vec3; 3], normals: Option<[Vec3; 3]>) -> Result<Shape, ShapeProblem> {
        if polygon_normal(&vertices).is_none() {
            return Err(ShapeProblem::Degenerate("degenerate triangle (no area) skipped".into()));
        }
        finite(Shape::Triangle { vertices, normals })
    }

    /// A polygon of at least 3 vertices, with a warning when it is not planar.
    pub fn polygon(vertices: Vec<Vec3>) -> Result<(Shape, Option<String>), ShapeProblem> {
        let Some(normal) = polygon_normal(&vertices) else {
            let n = vertices.len();
            return Err(ShapeProblem::Degenerate(format!("degenerate polygon ({n} vertices, no area) skipped")));
        };
        let deviation = polygon_non_planarity(&vertices, normal);
        let warning = (deviation > NON_PLANAR_TOLERANCE)
            .then(|| format!("polygon is not planar (its vertices leave the plane by {deviation:.2e} of its size); kept"));
        Ok((finite(Shape::Polygon { vertices })?, warning))
    }

    /// Axis-aligned bounds (min, max).
    pub fn bounds(&self) -> (Vec3, Vec3) {
        match self {
            Shape::Sphere { center, radius } => (center - *radius, center + *radius),
            Shape::Triangle { vertices, .. } => points_bounds(vertices),
            Shape::Polygon { vertices } => points_bounds(vertices),
            Shape::Cone { base, base_radius, apex, apex_radius } => {
                // Each end is a disc; bound it by its extent perpendicular to the axis.
                let axis = (*apex - *base).normalize_or_zero();
                let disc = (Vec3::ONE - axis * axis).max(Vec3::ZERO).powf(0.5);
                let (b, a) = (disc * *base_radius, disc * *apex_radius);
                ((base - b).min(apex - a), (base + b).max(apex + a))
            }
        }
    }
}

/// `shape` if its bounding box is finite.
fn finite(shape: Shape) -> Result<Shape, ShapeProblem> {
    let (lo, hi) = shape.bounds();
    if lo.is_finite() && hi.is_finite() {
        Ok(shape)
    } else {
        Err(ShapeProblem::Overflows)
    }
}

fn points_bounds(points: &[Vec3]) -> (Vec3, Vec3) {
    points.iter().fold((Vec3::INFINITY, Vec3::NEG_INFINITY), |(lo, hi), p| (lo.min(*p), hi.max(*p)))
}

/// The polygon's unit normal by Newell's method (robust for concave and
/// nearly collinear vertices), or `None` when the polygon has no area.
pub fn polygon_normal(vertices: &[Vec3]) -> Option<Vec3> {
    let mut n = glam::DVec3::ZERO;
    for (i, a) in vertices.iter().enumerate() {
        let b = vertices[(i + 1) % vertices.len()];
        let (a, b) = (a.as_dvec3(), b.as_dvec3());
        n += glam::DVec3::new((a.y - b.y) * (a.z + b.z), (a.z - b.z) * (a.x + b.x), (a.x - b.x) * (a.y + b.y));
    }
    let len = n.length();
    let scale = vertices.iter().map(|v| v.as_dvec3().length_squared()).fold(0.0, f64::max);
    (len > 1e-12 * scale.max(1e-30)).then(|| (n / len).as_vec3())
}

/// Largest distance of any vertex from the polygon's plane, relative to its size.
pub fn polygon_non_planarity(vertices: &[Vec3], normal: Vec3) -> f32 {
    let d = normal.dot(vertices[0]);
    let (lo, hi) = points_bounds(vertices);
    let size = (hi - lo).length().max(f32::MIN_POSITIVE);
    vertices.iter().map(|v| (normal.dot(*v) - d).abs()).fold(0.0, f32::max) / size
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn cylinder_bounds_are_tight_along_axis() {
        let s = Shape::Cone { base: Vec3::ZERO, base_radius: 1.0, apex: Vec3::Y * 2.0, apex_radius: 1.0 };
        let (lo, hi) = s.bounds();
        assert!((lo - Vec3::new(-1.0, 0.0, -1.0)).length() < 1e-6);
        assert!((hi - Vec3::new(1.0, 2.0, 1.0)).length() < 1e-6);
    }

    #[test]
    fn concave_polygon_normal() {
        // An L shape in the z = 3 plane, counter-clockwise seen from +z.
        let l = [(0., 0.), (2., 0.), (2., 1.), (1., 1.), (1., 2.), (0., 2.)]
            .map(|(x, y)| Vec3::new(x, y, 3.0));
        let n = polygon_normal(&l).unwrap();
        assert!((n - Vec3::Z).length() < 1e-6);
        assert!(polygon_non_planarity(&l, n) < 1e-6);
    }

    #[test]
    fn collinear_polygon_has_no_normal() {
        let line = [Vec3::ZERO, Vec3::X, Vec3::X * 2.0];
        assert!(polygon_normal(&line).is_none());
    }
}
