//! The camera frame as the lecture draws it: the eye e, the basis u, v, w and
//! the view window (l, r, b, t at distance d) the pixels are laid on. `glint
//! probe` prints it and the observer view draws it, from this one definition.

use glam::DVec3;

use crate::{Camera, Projection};

#[derive(Debug, Clone, Copy, PartialEq)]
pub struct CameraFrame {
    pub e: DVec3,
    pub u: DVec3,
    pub v: DVec3,
    pub w: DVec3,
    pub l: f64,
    pub r: f64,
    pub b: f64,
    pub t: f64,
    /// The window's distance from e along −w: 1 for a perspective camera, 0
    /// for an orthographic one, whose rays start on the window itself.
    pub d: f64,
    pub projection: Projection,
    /// The pixels across and down the window, n_x and n_y.
    pub width: u32,
    pub height: u32,
}

impl CameraFrame {
    /// The frame of `camera` for a `width` x `height` image; `None` when the
    /// camera has no basis.
    pub fn new(camera: &Camera, width: u32, height: u32) -> Option<Self> {
        let basis = camera.basis()?;
        let (r, t) = camera.half_extents(width, height);
        let d = match camera.projection {
            Projection::Perspective { .. } => 1.0,
            Projection::Orthographic { .. } => 0.0,
        };
        let (u, v, w) = (basis.u, basis.v, basis.w);
        Some(Self { e: camera.eye.as_dvec3(), u, v, w, l: -r, r, b: -t, t, d, projection: camera.projection, width, height })
    }

    pub fn is_orthographic(&self) -> bool {
        matches!(self.projection, Projection::Orthographic { .. })
    }

    /// The screen point (u_s, v_s) of image position (`x`, `y`) in pixels from
    /// the top-left corner: u_s = l + (r − l)·x/n_x, v_s = t − (t − b)·y/n_y.
    pub fn screen_point(&self, x: f64, y: f64) -> (f64, f64) {
        let us = self.l + (self.r - self.l) * x / f64::from(self.width);
        let vs = self.t - (self.t - self.b) * y / f64::from(self.height);
        (us, vs)
    }

    /// Image position (`x`, `y`) on the view window, in the world.
    pub fn window_point(&self, x: f64, y: f64) -> DVec3 {
        let (us, vs) = self.screen_point(x, y);
        self.e - self.d * self.w + us * self.u + vs * self.v
    }

    /// The centre of pixel (`i`, `j`) on the view window.
    pub fn pixel_centre(&self, i: u32, j: u32) -> DVec3 {
        self.window_point(f64::from(i) + 0.5, f64::from(j) + 0.5)
    }

    /// The window's corners: top-left, top-right, bottom-right, bottom-left.
    pub fn corners(&self) -> [DVec3; 4] {
        let (w, h) = (f64::from(self.width), f64::from(self.height));
        [self.window_point(0.0, 0.0), self.window_point(w, 0.0), self.window_point(w, h), self.window_point(0.0, h)]
    }

    /// Where the eye ray through pixel (`i`, `j`)'s centre starts: at e for a
    /// perspective camera, on the window for an orthographic one.
    pub fn ray_origin(&self, i: u32, j: u32) -> DVec3 {
        if self.is_orthographic() { self.pixel_centre(i, j) } else { self.e }
    }
}

#[cfg(test)]
mod tests {
    use glam::Vec3;

    use super::*;

    fn camera(projection: Projection) -> Camera {
        Camera { eye: Vec3::new(1.0, 2.0, 5.0), look_at: Vec3::new(0.0, 0.5, 0.0), up: Vec3::Y, projection }
    }

    #[test]
    fn the_window_lies_at_distance_d_along_minus_w() {
        let frame = CameraFrame::new(&camera(Projection::Perspective { fov_y_degrees: 40.0 }), 64, 48).unwrap();
        let centre = frame.window_point(32.0, 24.0);
        assert!((centre - (frame.e - frame.w)).length() < 1e-12, "the window's centre is e − d·w");
        let [tl, tr, br, bl] = frame.corners();
        assert!(((tr - tl).length() - (frame.r - frame.l)).abs() < 1e-12);
        assert!(((tl - bl).length() - (frame.t - frame.b)).abs() < 1e-12);
        assert!((br - bl).normalize().dot(frame.u) > 1.0 - 1e-12, "the bottom edge runs along u");
        assert!(((frame.t / frame.d).atan().to_degrees() * 2.0 - 40.0).abs() < 1e-9, "t = d·tan(fov/2)");
    }

    #[test]
    fn pixel_centres_lie_on_the_cameras_own_rays() {
        for projection in [Projection::Perspective { fov_y_degrees: 40.0 }, Projection::Orthographic { height: 3.0 }] {
            let cam = camera(projection);
            let frame = CameraFrame::new(&cam, 64, 48).unwrap();
            for (i, j) in [(0, 0), (63, 47), (10, 30)] {
                let ray = cam.ray(64, 48, f64::from(i) + 0.5, f64::from(j) + 0.5).unwrap();
                let (origin, centre) = (frame.ray_origin(i, j), frame.pixel_centre(i, j));
                assert!((origin - ray.origin).length() < 1e-12, "{projection:?} ({i}, {j})");
                let along = centre - ray.origin;
                assert!((along - along.dot(ray.direction) * ray.direction).length() < 1e-12, "{projection:?} ({i}, {j})");
                let (x, y) = cam.project(64, 48, centre).unwrap();
                assert!((x - (f64::from(i) + 0.5)).abs() < 1e-9 && (y - (f64::from(j) + 0.5)).abs() < 1e-9);
            }
        }
    }
}
