use glam::{DVec3, Vec3};

/// How the camera maps pixels to rays.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Projection {
    /// Vertical field of view in degrees, measured from the top edge of the image
    /// to the bottom edge.
    Perspective { fov_y_degrees: f32 },
    /// Height of the view plane in world units; rays are parallel to the view direction.
    Orthographic { height: f32 },
}

#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Camera {
    pub eye: Vec3,
    pub look_at: Vec3,
    pub up: Vec3,
    pub projection: Projection,
}

/// The camera's orthonormal basis: `u` right, `v` up, `w` pointing backwards
/// (from the scene towards the eye), as in the classic lecture.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Basis {
    pub u: DVec3,
    pub v: DVec3,
    pub w: DVec3,
}

/// An `up` that works for a camera looking along `view`: of +y, −z and +x,
/// the one furthest from parallel to it (the first among equals). Looking
/// straight down, that is −z, so the image's top is towards −z.
pub fn suggested_up(view: Vec3) -> Vec3 {
    let view = view.normalize();
    [Vec3::Y, Vec3::NEG_Z, Vec3::X].into_iter().min_by(|a, b| a.dot(view).abs().total_cmp(&b.dot(view).abs())).expect("three candidates")
}

/// A ray in double precision, for host-side math and tests.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Ray {
    pub origin: DVec3,
    pub direction: DVec3,
}

/// A field of view of at most π "degrees" was probably written in radians.
pub(crate) fn radians_warning(key: &str, degrees: f32) -> Option<String> {
    (degrees > 0.0 && degrees <= std::f32::consts::PI).then(|| {
        format!("{key}: {degrees}° is a very narrow view; angles are in degrees ({degrees} radians is {:.1})", degrees.to_degrees())
    })
}

impl Camera {
    /// The basis, or `None` when `up` is parallel to the view direction or the
    /// eye sits on the look-at point.
    pub fn basis(&self) -> Option<Basis> {
        let w = (self.eye - self.look_at).as_dvec3();
        let up = self.up.as_dvec3();
        if w.length() == 0.0 || up.length() == 0.0 {
            return None;
        }
        let w = w.normalize();
        let u = up.cross(w);
        if u.length() < 1e-9 * up.length() {
            return None;
        }
        let u = u.normalize();
        Some(Basis { u, v: w.cross(u), w })
    }

    /// Half extents (right edge `r`, top edge `t`) of the view window: at distance 1
    /// for a perspective camera, in world units for an orthographic one; l = −r, b = −t.
    pub fn half_extents(&self, width: u32, height: u32) -> (f64, f64) {
        let aspect = f64::from(width) / f64::from(height);
        let t = match self.projection {
            Projection::Perspective { fov_y_degrees } => {
                (f64::from(fov_y_degrees).to_radians() / 2.0).tan()
            }
            Projection::Orthographic { height } => f64::from(height) / 2.0,
        };
        (t * aspect, t)
    }

    /// The ray through image position (`x`, `y`) in pixels, with (0, 0) the top-left
    /// corner of the image; the centre of pixel (i, j) is (i + 0.5, j + 0.5), so
    /// u_s = l + (r − l)(i + 0.5)/n_x.
    pub fn ray(&self, width: u32, height: u32, x: f64, y: f64) -> Option<Ray> {
        let b = self.basis()?;
        let (r, t) = self.half_extents(width, height);
        let us = -r + 2.0 * r * x / f64::from(width);
        let vs = t - 2.0 * t * y / f64::from(height);
        let eye = self.eye.as_dvec3();
        Some(match self.projection {
            Projection::Perspective { .. } => Ray {
                origin: eye,
                direction: (-b.w + us * b.u + vs * b.v).normalize(),
            },
            Projection::Orthographic { .. } => Ray {
                origin: eye + us * b.u + vs * b.v,
                direction: -b.w,
            },
        })
    }

    /// Where world point `p` lands on the image, in pixel coordinates (inverse of `ray`).
    /// `None` for points behind a perspective camera.
    pub fn project(&self, width: u32, height: u32, p: DVec3) -> Option<(f64, f64)> {
        let b = self.basis()?;
        let (r, t) = self.half_extents(width, height);
        let d = p - self.eye.as_dvec3();
        let (x, y, z) = (d.dot(b.u), d.dot(b.v), -d.dot(b.w));
        let (us, vs) = match self.projection {
            Projection::Perspective { .. } => {
                if z <= 0.0 {
                    return None;
                }
                (x / z, y / z)
            }
            Projection::Orthographic { .. } => (x, y),
        };
        Some((
            (us + r) / (2.0 * r) * f64::from(width),
            (t - vs) / (2.0 * t) * f64::from(height),
        ))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn camera(projection: Projection) -> Camera {
        Camera {
            eye: Vec3::new(1.0, 2.0, 5.0),
            look_at: Vec3::new(0.0, 0.5, 0.0),
            up: Vec3::Y,
            projection,
        }
    }

    #[test]
    fn basis_is_orthonormal_and_right_handed() {
        let b = camera(Projection::Perspective { fov_y_degrees: 40.0 }).basis().unwrap();
        for (a, c) in [(b.u, b.v), (b.v, b.w), (b.u, b.w)] {
            assert!(a.dot(c).abs() < 1e-12);
        }
        assert!((b.u.cross(b.v) - b.w).length() < 1e-12);
        assert!(b.v.y > 0.0, "v points up");
    }

    #[test]
    fn degenerate_up_has_no_basis() {
        let mut c = camera(Projection::Perspective { fov_y_degrees: 40.0 });
        c.up = c.eye - c.look_at;
        assert!(c.basis().is_none());
    }

    #[test]
    fn centre_ray_looks_at_target() {
        let c = camera(Projection::Perspective { fov_y_degrees: 40.0 });
        let ray = c.ray(64, 48, 32.0, 24.0).unwrap();
        let to_target = (c.look_at - c.eye).as_dvec3().normalize();
        assert!((ray.direction - to_target).length() < 1e-12);
    }

    #[test]
    fn top_edge_ray_makes_half_the_field_of_view() {
        let c = camera(Projection::Perspective { fov_y_degrees: 40.0 });
        let ray = c.ray(64, 48, 32.0, 0.0).unwrap();
        let to_target = (c.look_at - c.eye).as_dvec3().normalize();
        let angle = ray.direction.dot(to_target).acos().to_degrees();
        assert!((angle - 20.0).abs() < 1e-9, "{angle}");
    }

    #[test]
    fn project_inverts_ray_for_both_projections() {
        for projection in [
            Projection::Perspective { fov_y_degrees: 55.0 },
            Projection::Orthographic { height: 3.0 },
        ] {
            let c = camera(projection);
            let ray = c.ray(80, 60, 13.25, 47.5).unwrap();
            let p = ray.origin + 7.0 * ray.direction;
            let (x, y) = c.project(80, 60, p).unwrap();
            assert!((x - 13.25).abs() < 1e-9 && (y - 47.5).abs() < 1e-9, "{x} {y}");
        }
    }
}
