//! The primitives of the scene model, and the one place each is built and
//! checked from what a file says (pbrt's `Shape::Create`): every loader (TOML,
//! NFF, OBJ) calls these constructors, so the same input has the same outcome
//! in every format. The policy (docs/scene-format.md, "Errors and warnings"):
//!
//! * a **degenerate** shape (a sphere of radius 0, a triangle, polygon or
//!   rectangle with no area, a cone whose ends coincide or whose radii are
//!   both 0) has no surface to render: it is skipped, with a warning naming
//!   file and line;
//! * a **non-planar** polygon is kept, with a warning: it is intersected in the
//!   plane of its Newell normal, which is well defined, and files written by
//!   other tools (the SPD generators among them) contain slightly bent ones;
//! * a shape whose bounds **overflow** 32-bit floats cannot be placed in the
//!   BVH, nor a plane whose offset n·p overflows intersected: an error.
//!
//! Values out of their domain (a negative radius, NaN) are the loaders' to
//! report at the token that holds them; the constructors take them as checked.

use glam::{DVec3, Vec3};

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

/// What every tool calls a shape (`glint check`, the probe, the viewer), in
/// the order `glint check` counts them.
pub const SHAPE_NAMES: [&str; 6] = ["sphere", "triangle", "polygon", "cone", "cylinder", "infinite plane"];

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
    /// An infinite plane through `point` with unit `normal`, which points to
    /// its front side. It has no bounds: the kernels test it beside the BVH.
    Plane { point: Vec3, normal: Vec3 },
}

impl Shape {
    /// A sphere; `radius` must not be negative.
    pub fn sphere(center: Vec3, radius: f32) -> Result<Shape, ShapeProblem> {
        checked(Shape::Sphere { center, radius })
    }

    /// An open cone or cylinder; the radii must not be negative. A cone whose
    /// base radius is 0 is stored with its ends swapped (the same surface), so
    /// the base is always the wide end.
    pub fn cone(base: Vec3, base_radius: f32, apex: Vec3, apex_radius: f32) -> Result<Shape, ShapeProblem> {
        checked(if base_radius == 0.0 {
            Shape::Cone { base: apex, base_radius: apex_radius, apex: base, apex_radius: base_radius }
        } else {
            Shape::Cone { base, base_radius, apex, apex_radius }
        })
    }

    /// A triangle, smooth-shaded when it has (unit) vertex normals.
    pub fn triangle(vertices: [Vec3; 3], normals: Option<[Vec3; 3]>) -> Result<Shape, ShapeProblem> {
        checked(Shape::Triangle { vertices, normals })
    }

    /// A polygon of at least 3 vertices, with a warning when it is not planar.
    /// One of three vertices is a triangle: the same surface, which the
    /// kernels test without the polygon's vertex loop (NFF writes every
    /// triangle of a mesh as `p 3`).
    pub fn polygon(vertices: Vec<Vec3>) -> Result<(Shape, Option<String>), ShapeProblem> {
        let polygon = checked(Shape::Polygon { vertices })?;
        let Shape::Polygon { vertices } = &polygon else { unreachable!("checked keeps the shape") };
        if let [a, b, c] = vertices[..] {
            return Ok((Shape::Triangle { vertices: [a, b, c], normals: None }, None));
        }
        let normal = polygon_normal(vertices).expect("checked: it has area");
        let deviation = polygon_non_planarity(vertices, normal);
        let warning = (deviation > NON_PLANAR_TOLERANCE)
            .then(|| format!("polygon is not planar (its vertices leave the plane by {deviation:.2e} of its size); kept"));
        Ok((polygon, warning))
    }

    /// An infinite plane through `point`; `normal` must be a unit vector.
    pub fn plane(point: Vec3, normal: Vec3) -> Result<Shape, ShapeProblem> {
        checked(Shape::Plane { point, normal })
    }

    /// A rectangle centred on `center` in the plane of the unit `normal`, with
    /// sides `size[0]` along the plane's axis u and `size[1]` along v
    /// ([`plane_axes`]); the sizes must not be negative. It is stored as the
    /// polygon of its corners, counter-clockwise seen from where the normal
    /// points, so that side is its front.
    pub fn rectangle(center: Vec3, normal: Vec3, size: [f32; 2]) -> Result<Shape, ShapeProblem> {
        let [u, v] = plane_axes(normal.as_dvec3());
        let (a, b) = (u * f64::from(size[0] / 2.0), v * f64::from(size[1] / 2.0));
        // v is normal × u or its opposite: pick the sign that winds the corners
        // counter-clockwise about the normal.
        let b = if u.cross(v).dot(normal.as_dvec3()) > 0.0 { b } else { -b };
        let c = center.as_dvec3();
        let vertices: Vec<Vec3> = [c - a - b, c + a - b, c + a + b, c - a + b].iter().map(|p| p.as_vec3()).collect();
        // Corners beyond f32 are an overflow, not a lack of area.
        if !vertices.iter().all(|p| p.is_finite()) {
            return Err(ShapeProblem::Overflows);
        }
        if polygon_normal(&vertices).is_none() {
            return Err(ShapeProblem::Degenerate("degenerate rectangle (no area) skipped".into()));
        }
        checked(Shape::Polygon { vertices })
    }

    /// What every tool calls the shape: a cone of equal radii is a cylinder.
    pub fn name(&self) -> &'static str {
        let [sphere, triangle, polygon, cone, cylinder, plane] = SHAPE_NAMES;
        match self {
            Shape::Sphere { .. } => sphere,
            Shape::Triangle { .. } => triangle,
            Shape::Polygon { .. } => polygon,
            Shape::Cone { base_radius, apex_radius, .. } if base_radius == apex_radius => cylinder,
            Shape::Cone { .. } => cone,
            Shape::Plane { .. } => plane,
        }
    }

    /// Whether the shape has bounds, so a place in the BVH: all but an infinite plane.
    pub fn is_bounded(&self) -> bool {
        !matches!(self, Shape::Plane { .. })
    }

    /// Axis-aligned bounds (min, max); `None` for an infinite plane.
    pub fn bounds(&self) -> Option<(Vec3, Vec3)> {
        Some(match self {
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
            Shape::Plane { .. } => return None,
        })
    }

    /// The same shape with every length and position multiplied by `s`: what a
    /// test of scale invariance needs of each kind.
    pub fn scaled(&self, s: f32) -> Shape {
        match self {
            Shape::Sphere { center, radius } => Shape::Sphere { center: center * s, radius: radius * s },
            Shape::Triangle { vertices, normals } => Shape::Triangle { vertices: vertices.map(|v| v * s), normals: *normals },
            Shape::Polygon { vertices } => Shape::Polygon { vertices: vertices.iter().map(|v| v * s).collect() },
            Shape::Cone { base, base_radius, apex, apex_radius } => {
                Shape::Cone { base: base * s, base_radius: base_radius * s, apex: apex * s, apex_radius: apex_radius * s }
            }
            Shape::Plane { point, normal } => Shape::Plane { point: point * s, normal: *normal },
        }
    }

    /// Why the policy (above) keeps the shape out of a scene, if it does: what
    /// each constructor checks, and what no loaded shape has.
    pub fn problem(&self) -> Option<ShapeProblem> {
        let degenerate = match self {
            Shape::Sphere { radius, .. } => (*radius == 0.0).then(|| "sphere of radius 0 skipped".to_string()),
            Shape::Triangle { vertices, .. } => polygon_normal(vertices).is_none().then(|| "degenerate triangle (no area) skipped".to_string()),
            Shape::Polygon { vertices } => {
                let n = vertices.len();
                polygon_normal(vertices).is_none().then(|| format!("degenerate polygon ({n} vertices, no area) skipped"))
            }
            // Ends closer than f32 can measure leave the axis without a direction.
            Shape::Cone { base, base_radius, apex, apex_radius } => ((*apex - *base).length() == 0.0 || (*base_radius == 0.0 && *apex_radius == 0.0))
                .then(|| "degenerate cone (base equals apex, or both radii 0) skipped".to_string()),
            Shape::Plane { .. } => None,
        };
        match degenerate {
            Some(warning) => Some(ShapeProblem::Degenerate(warning)),
            None => (!self.is_finite()).then_some(ShapeProblem::Overflows),
        }
    }

    /// Whether 32-bit floats hold the shape: its bounds, or for a plane its
    /// offset n·p, which the kernels intersect with.
    pub fn is_finite(&self) -> bool {
        match self {
            Shape::Plane { point, normal } => normal.dot(*point).is_finite(),
            _ => self.bounds().is_some_and(|(lo, hi)| lo.is_finite() && hi.is_finite()),
        }
    }
}

/// `shape` if the policy keeps it: what every constructor ends with.
fn checked(shape: Shape) -> Result<Shape, ShapeProblem> {
    match shape.problem() {
        None => Ok(shape),
        Some(problem) => Err(problem),
    }
}

/// The axes (u, v) of a plane with unit normal `n`: the sides of a
/// rectangle, and the coordinates a checker tiles planes and polygons by.
/// u is the first world axis (in the order x, y, z) other than the normal's
/// largest component, projected into the plane; v is the remaining world axis,
/// made perpendicular to n and u. So a floor (normal ±y) has u = x and v = z,
/// a wall facing ±z has x and y, a wall facing ±x has y and z, whichever way
/// the normal points. In f64, for the CPU reference as well.
pub fn plane_axes(n: DVec3) -> [DVec3; 2] {
    let m = n.abs();
    let (i, j) = if m.x >= m.y && m.x >= m.z {
        (1, 2)
    } else if m.y >= m.z {
        (0, 2)
    } else {
        (0, 1)
    };
    let u = (DVec3::AXES[i] - n * n[i]).normalize();
    let v = (DVec3::AXES[j] - n * n[j] - u * u[j]).normalize();
    [u, v]
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
        let (lo, hi) = s.bounds().unwrap();
        assert!((lo - Vec3::new(-1.0, 0.0, -1.0)).length() < 1e-6);
        assert!((hi - Vec3::new(1.0, 2.0, 1.0)).length() < 1e-6);
    }

    #[test]
    fn a_scaled_shape_has_scaled_bounds() {
        let shapes = [
            Shape::sphere(Vec3::new(1.0, 2.0, 3.0), 0.5),
            Shape::triangle([Vec3::ZERO, Vec3::X, Vec3::Y], Some([Vec3::Z; 3])),
            Shape::polygon(vec![Vec3::ZERO, Vec3::X, Vec3::new(1.0, 1.0, 0.0), Vec3::Y]).map(|(shape, _)| shape),
            Shape::cone(Vec3::ZERO, 1.0, Vec3::Y, 0.5),
        ];
        for shape in shapes.map(Result::unwrap) {
            let ((lo, hi), (scaled_lo, scaled_hi)) = (shape.bounds().unwrap(), shape.scaled(4.0).bounds().unwrap());
            assert!((scaled_lo - lo * 4.0).length() < 1e-5 && (scaled_hi - hi * 4.0).length() < 1e-5, "{shape:?}");
        }
        let plane = Shape::Plane { point: Vec3::Y, normal: Vec3::Y };
        assert_eq!(plane.scaled(4.0), Shape::Plane { point: Vec3::Y * 4.0, normal: Vec3::Y });
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
    fn a_three_vertex_polygon_is_a_triangle() {
        let vertices = [Vec3::ZERO, Vec3::X, Vec3::Y];
        let (shape, warning) = Shape::polygon(vertices.to_vec()).unwrap();
        assert_eq!(shape, Shape::Triangle { vertices, normals: None });
        assert_eq!(warning, None);
        let (quad, _) = Shape::polygon(vec![Vec3::ZERO, Vec3::X, Vec3::ONE.with_z(0.0), Vec3::Y]).unwrap();
        assert!(matches!(quad, Shape::Polygon { .. }));
    }

    #[test]
    fn collinear_polygon_has_no_normal() {
        let line = [Vec3::ZERO, Vec3::X, Vec3::X * 2.0];
        assert!(polygon_normal(&line).is_none());
    }

    #[test]
    fn plane_axes_follow_the_world_axes_whichever_way_the_normal_points() {
        for (normal, axes) in [(DVec3::Y, [DVec3::X, DVec3::Z]), (DVec3::Z, [DVec3::X, DVec3::Y]), (DVec3::X, [DVec3::Y, DVec3::Z])] {
            assert_eq!(plane_axes(normal), axes);
            assert_eq!(plane_axes(-normal), axes);
        }
        let n = DVec3::new(0.3, -0.8, 0.5).normalize();
        let [u, v] = plane_axes(n);
        for (a, b) in [(u, n), (v, n), (u, v)] {
            assert!(a.dot(b).abs() < 1e-15 && (a.length() - 1.0).abs() < 1e-15);
        }
        assert!(u.cross(DVec3::X).dot(n).abs() < 1e-15, "u is x projected into the plane of a mostly-y normal");
    }

    #[test]
    fn a_rectangle_is_the_polygon_of_its_corners_facing_its_normal() {
        for normal in [Vec3::Y, -Vec3::Y] {
            let Ok(Shape::Polygon { vertices }) = Shape::rectangle(Vec3::new(1.0, 2.0, 3.0), normal, [4.0, 6.0]) else { panic!() };
            let (lo, hi) = points_bounds(&vertices);
            assert_eq!((lo, hi), (Vec3::new(-1.0, 2.0, 0.0), Vec3::new(3.0, 2.0, 6.0)), "4 along x, 6 along z");
            assert_eq!(polygon_normal(&vertices), Some(normal), "counter-clockwise seen from the normal's side");
        }
        let tilted = Vec3::new(0.0, 0.6, 0.8);
        let Ok(Shape::Polygon { vertices }) = Shape::rectangle(Vec3::ZERO, tilted, [2.0, 2.0]) else { panic!() };
        assert!((polygon_normal(&vertices).unwrap() - tilted).length() < 1e-6);
        assert!(polygon_non_planarity(&vertices, tilted) < 1e-7);
    }

    #[test]
    fn degenerate_and_overflowing_planes_follow_the_shape_policy() {
        let skipped = ShapeProblem::Degenerate("degenerate rectangle (no area) skipped".into());
        assert_eq!(Shape::rectangle(Vec3::ZERO, Vec3::Z, [0.0, 1.0]), Err(skipped.clone()));
        assert_eq!(Shape::rectangle(Vec3::splat(1e6), Vec3::Z, [1e-30, 1e-30]), Err(skipped));
        assert_eq!(Shape::rectangle(Vec3::new(3e38, 0.0, 0.0), Vec3::Z, [3e38, 1.0]), Err(ShapeProblem::Overflows));
        let diagonal = Vec3::new(1.0, 1.0, 0.0).normalize();
        assert_eq!(Shape::plane(Vec3::new(3e38, 3e38, 0.0), diagonal), Err(ShapeProblem::Overflows));
        let floor = Shape::plane(Vec3::new(3e38, 0.0, 0.0), Vec3::Y).unwrap();
        assert!(floor.is_finite() && floor.bounds().is_none(), "an infinite plane has no bounds");
    }
}
