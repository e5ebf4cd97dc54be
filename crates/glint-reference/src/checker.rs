//! Whitted's checkerboard, from its definition in docs/scene-format.md: a
//! material's O_d is its `color` on even tiles and the checker's colour on odd
//! ones. Tiles have side `size` and a corner at the world origin; on a polygon
//! or plane they are counted in the plane's coordinates (P·u, P·v), with the
//! axes of `glint_scene::plane_axes`, and elsewhere in x, y and z.

use glam::DVec3;
use glint_scene::{plane_axes, Material};

use crate::geometry::Geom;

/// Whether `p` on `geom` lies on an odd tile of the material's checker
/// (never, without one).
pub(crate) fn odd_tile(m: &Material, geom: &Geom, p: DVec3) -> bool {
    let Some(checker) = m.checker else { return false };
    let q = match geom.flat_normal() {
        Some(n) => {
            let [u, v] = plane_axes(n);
            DVec3::new(p.dot(u), p.dot(v), 0.0)
        }
        None => p,
    };
    let tiles = (q / f64::from(checker.size)).floor();
    (tiles.x + tiles.y + tiles.z).rem_euclid(2.0) == 1.0
}

/// O_d, the diffuse colour, at a hit on an odd tile or not.
pub(crate) fn diffuse_colour(m: &Material, odd_tile: bool) -> DVec3 {
    let c = match m.checker {
        Some(checker) if odd_tile => checker.color,
        _ => m.color,
    };
    c.as_dvec3()
}

#[cfg(test)]
mod tests {
    use super::*;
    use glam::Vec3;
    use glint_scene::{Checker, Shape};

    #[test]
    fn tiles_alternate_in_the_plane_of_a_floor_and_in_space_elsewhere() {
        let m = Material { checker: Some(Checker { color: Vec3::Y, size: 2.0 }), ..Material::default() };
        let floor = Geom::new(&Shape::Plane { point: Vec3::ZERO, normal: Vec3::Y });
        let ball = Geom::new(&Shape::Sphere { center: Vec3::ZERO, radius: 10.0 });
        // Either side of y = 0 on the floor is the same tile; in space it is not.
        for y in [1e-9, -1e-9] {
            assert!(!odd_tile(&m, &floor, DVec3::new(0.5, y, 0.5)));
            assert!(odd_tile(&m, &floor, DVec3::new(2.5, y, 0.5)));
            assert!(odd_tile(&m, &floor, DVec3::new(-0.5, y, 0.5)));
            assert!(!odd_tile(&m, &floor, DVec3::new(-0.5, y, -0.5)));
        }
        assert!(!odd_tile(&m, &ball, DVec3::new(0.5, 1e-9, 0.5)));
        assert!(odd_tile(&m, &ball, DVec3::new(0.5, -1e-9, 0.5)));
        assert_eq!(diffuse_colour(&m, true), DVec3::Y);
        assert_eq!(diffuse_colour(&m, false), DVec3::splat(f64::from(0.8f32)));
        assert!(!odd_tile(&Material::default(), &floor, DVec3::new(2.5, 0.0, 0.5)), "no checker, no odd tiles");
    }
}
