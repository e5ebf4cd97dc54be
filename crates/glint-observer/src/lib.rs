//! The rays seen from outside: a camera's frame, its view window and the ray
//! trees it probed, as 3-D segments and dots that a second camera, the
//! observer, draws. The viewer paints them with egui and `glint probe
//! --observer` into a PNG; both take the geometry and the inks from here.
//! It reads the probe's rays as glint-encoding lays them out, and knows no
//! GPU and no GUI.

use glam::{DVec2, DVec3, Vec3};
use glint_scene::camera_frame::CameraFrame;
use glint_scene::{Camera, LightKind, Projection, Scene};

use glint_encoding::gpu_types::{shadow_ray_light, ProbeRay, NO_RAY, PROBE_BLOCKED, RAY_EYE, RAY_REFLECT, RAY_REFRACT, RAY_SHADOW};

/// The window's pixel grid is drawn when a pixel looks at least this many
/// of the observer's pixels across.
pub const GRID_CELL_PIXELS: f64 = 4.0;

/// What a segment or dot shows, which decides how it is drawn.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Ink {
    AxisU,
    AxisV,
    AxisW,
    Window,
    Grid,
    /// The outline of a probed pixel on the window.
    Pixel,
    EyeRay,
    Reflect,
    Refract,
    ShadowLit,
    ShadowBlocked,
    Normal,
    Eye,
    Hit,
    Light,
}

impl Ink {
    /// The colour, 8-bit sRGB.
    pub fn rgb(self) -> [u8; 3] {
        match self {
            Ink::AxisU => [255, 80, 80],
            Ink::AxisV => [80, 230, 80],
            Ink::AxisW => [90, 140, 255],
            Ink::Window => [235, 235, 235],
            Ink::Grid => [150, 150, 150],
            Ink::Pixel => [255, 150, 0],
            Ink::EyeRay | Ink::Eye | Ink::Hit => [255, 255, 255],
            Ink::Reflect => [80, 200, 255],
            Ink::Refract => [120, 255, 120],
            Ink::ShadowLit | Ink::Light => [255, 220, 60],
            Ink::ShadowBlocked => [255, 60, 60],
            Ink::Normal => [255, 120, 230],
        }
    }

    /// How wide a line of this ink is drawn, in pixels: rays widest, the
    /// grid thinnest.
    pub fn line_width(self) -> f64 {
        match self {
            Ink::Grid => 1.0,
            Ink::Window | Ink::Pixel | Ink::Normal => 1.5,
            _ => 2.0,
        }
    }

    /// Shadow rays are dashed: they add no light of their own, they only ask.
    pub fn is_dashed(self) -> bool {
        matches!(self, Ink::ShadowLit | Ink::ShadowBlocked)
    }

    /// The ink of a ray of the tree.
    pub fn of_ray(ray: &ProbeRay) -> Ink {
        match ray.kind {
            RAY_EYE => Ink::EyeRay,
            RAY_REFLECT => Ink::Reflect,
            RAY_REFRACT => Ink::Refract,
            _ if ray.flags & PROBE_BLOCKED != 0 => Ink::ShadowBlocked,
            _ => Ink::ShadowLit,
        }
    }
}

/// Which ray a segment draws: ray `ray` of the `tree`-th probed pixel.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct RayId {
    pub tree: usize,
    pub ray: usize,
}

#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Segment {
    pub a: DVec3,
    pub b: DVec3,
    pub ink: Ink,
    pub ray: Option<RayId>,
}

#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Dot {
    pub at: DVec3,
    pub ink: Ink,
}

/// A probed pixel and its ray tree, in the order the probe recorded it.
pub struct ProbedPixel<'a> {
    pub pixel: (u32, u32),
    pub rays: &'a [ProbeRay],
}

/// What the overlay shows of the trees.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct OverlayOptions {
    /// Rays deeper than this are left out (the eye ray is depth 1; a shadow
    /// ray counts the depth of the ray that cast it).
    pub max_depth: u32,
    /// The window's pixel grid, when it is coarse enough to see.
    pub grid: bool,
}

/// Everything drawn over the observer's render, in world space.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct Overlay {
    pub segments: Vec<Segment>,
    pub dots: Vec<Dot>,
}

impl Overlay {
    /// The frame (the window's grid and edges, the eye, unit axes u, v, w),
    /// the lights, and each probed pixel's outline and tree: every ray up to
    /// its end, a dot at each hit with its normal; in that order, back to
    /// front, as they are drawn. `bounds` are the scene's
    /// objects' bounds, where a ray that hits nothing is cut off.
    pub fn new(scene: &Scene, frame: &CameraFrame, bounds: (Vec3, Vec3), probed: &[ProbedPixel<'_>], options: OverlayOptions) -> Self {
        let mut overlay = Overlay::default();
        let segment = |a, b, ink| Segment { a, b, ink, ray: None };
        let (w, h) = (f64::from(frame.width), f64::from(frame.height));
        if options.grid {
            for x in 1..frame.width {
                let x = f64::from(x);
                overlay.segments.push(segment(frame.window_point(x, 0.0), frame.window_point(x, h), Ink::Grid));
            }
            for y in 1..frame.height {
                let y = f64::from(y);
                overlay.segments.push(segment(frame.window_point(0.0, y), frame.window_point(w, y), Ink::Grid));
            }
        }
        overlay.outline(frame.corners(), Ink::Window);
        overlay.dots.push(Dot { at: frame.e, ink: Ink::Eye });
        for (axis, ink) in [(frame.u, Ink::AxisU), (frame.v, Ink::AxisV), (frame.w, Ink::AxisW)] {
            overlay.segments.push(segment(frame.e, frame.e + axis, ink));
        }
        for light in scene.lights.iter().filter(|l| l.enabled) {
            if let LightKind::Point { position } = light.kind {
                overlay.dots.push(Dot { at: position.as_dvec3(), ink: Ink::Light });
            }
        }
        let reach = Reach::new(bounds);
        for (tree, probed) in probed.iter().enumerate() {
            let (x, y) = (f64::from(probed.pixel.0), f64::from(probed.pixel.1));
            let corners = [(x, y), (x + 1.0, y), (x + 1.0, y + 1.0), (x, y + 1.0)].map(|(x, y)| frame.window_point(x, y));
            overlay.outline(corners, Ink::Pixel);
            for (id, ray) in probed.rays.iter().enumerate() {
                if depth(probed.rays, ray) > options.max_depth {
                    continue;
                }
                let (a, b) = (Vec3::from(ray.origin).as_dvec3(), ray_end(scene, &reach, ray));
                overlay.segments.push(Segment { a, b, ink: Ink::of_ray(ray), ray: Some(RayId { tree, ray: id }) });
                if ray.kind != RAY_SHADOW && ray.object != NO_RAY {
                    let normal = Vec3::from(ray.shading).as_dvec3();
                    overlay.segments.push(segment(b, b + normal * reach.normal_length, Ink::Normal));
                    overlay.dots.push(Dot { at: b, ink: Ink::Hit });
                }
            }
        }
        overlay
    }

    fn outline(&mut self, corners: [DVec3; 4], ink: Ink) {
        for k in 0..4 {
            self.segments.push(Segment { a: corners[k], b: corners[(k + 1) % 4], ink, ray: None });
        }
    }
}

/// A ray's depth in the tree; a shadow ray's is that of the ray that cast it.
fn depth(rays: &[ProbeRay], ray: &ProbeRay) -> u32 {
    match rays.get(ray.parent as usize) {
        Some(parent) if ray.kind == RAY_SHADOW => parent.depth,
        _ => ray.depth,
    }
}

/// The box around the scene's objects (empty, lo > hi, when none is bounded).
pub fn object_bounds(scene: &Scene) -> (Vec3, Vec3) {
    glint_encoding::gpu_types::primitive_bounds(scene).into_iter().fold((Vec3::INFINITY, Vec3::NEG_INFINITY), |(lo, hi), (a, b)| (lo.min(a), hi.max(b)))
}

/// Where rays that find nothing are cut off, and how long normals are drawn.
struct Reach {
    lo: DVec3,
    hi: DVec3,
    size: f64,
    normal_length: f64,
}

impl Reach {
    fn new(bounds: (Vec3, Vec3)) -> Self {
        let (lo, hi) = (bounds.0.as_dvec3(), bounds.1.as_dvec3());
        let size = if lo.cmple(hi).all() { ((hi - lo).length() / 2.0).max(1e-3) } else { 1.0 };
        let margin = DVec3::splat(size * 0.1);
        Self { lo: lo - margin, hi: hi + margin, size, normal_length: size * 0.08 }
    }

    /// How far along `dir` from `origin` the scene's bounds end (twice its
    /// size when the ray never meets them).
    fn along(&self, origin: DVec3, dir: DVec3) -> f64 {
        let (a, b) = ((self.lo - origin) / dir, (self.hi - origin) / dir);
        let exit = a.max(b).min_element();
        if exit.is_finite() && exit > 0.0 { exit } else { self.size * 2.0 }
    }
}

/// Where `ray`'s segment ends: at its hit, at the blocker or light of a shadow
/// ray, and where it leaves the scene's bounds when it found nothing.
fn ray_end(scene: &Scene, reach: &Reach, ray: &ProbeRay) -> DVec3 {
    let (origin, dir) = (Vec3::from(ray.origin).as_dvec3(), Vec3::from(ray.dir).as_dvec3());
    if ray.kind == RAY_SHADOW {
        if ray.flags & PROBE_BLOCKED != 0 {
            return origin + dir * f64::from(ray.t);
        }
        let light = shadow_ray_light(scene, ray).map(|i| scene.lights[i].kind);
        let directional = matches!(light, Some(LightKind::Directional { .. }));
        return origin + dir * if directional { reach.along(origin, dir) } else { f64::from(ray.distance) };
    }
    if ray.object == NO_RAY { origin + dir * reach.along(origin, dir) } else { Vec3::from(ray.point).as_dvec3() }
}

/// The observer: a camera that sees the overlay, and the image it draws into.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Observer {
    pub camera: Camera,
    pub width: u32,
    pub height: u32,
}

impl Observer {
    /// Where world point `p` lands, in pixels from the image's top-left
    /// corner; `None` in front of the near plane.
    pub fn project(&self, p: DVec3) -> Option<DVec2> {
        if self.depth(p).is_some_and(|d| d < self.near()) {
            return None;
        }
        self.project_unclipped(p)
    }

    /// Segment `a`–`b` in pixels, the part in front of the near plane; `None`
    /// when all of it is behind.
    pub fn project_segment(&self, a: DVec3, b: DVec3) -> Option<(DVec2, DVec2)> {
        let (mut a, mut b) = (a, b);
        if let (Some(da), Some(db)) = (self.depth(a), self.depth(b)) {
            let near = self.near();
            if da < near && db < near {
                return None;
            }
            if da < near {
                a = b + (a - b) * ((db - near) / (db - da));
            } else if db < near {
                b = a + (b - a) * ((da - near) / (da - db));
            }
        }
        Some((self.project_unclipped(a)?, self.project_unclipped(b)?))
    }

    /// How big a pixel of `frame`'s window looks, in the observer's pixels
    /// (the smaller side); 0 when the window is not wholly in view.
    pub fn cell_size(&self, frame: &CameraFrame) -> f64 {
        let corners: Option<Vec<DVec2>> = frame.corners().iter().map(|&c| self.project(c)).collect();
        let Some(c) = corners else { return 0.0 };
        let across = c[0].distance(c[1]).min(c[3].distance(c[2])) / f64::from(frame.width);
        let down = c[0].distance(c[3]).min(c[1].distance(c[2])) / f64::from(frame.height);
        across.min(down)
    }

    /// Depth in front of a perspective camera; `None` for an orthographic
    /// one, which sees everything along its rays.
    fn depth(&self, p: DVec3) -> Option<f64> {
        let basis = self.camera.basis()?;
        match self.camera.projection {
            Projection::Perspective { .. } => Some((p - self.camera.eye.as_dvec3()).dot(-basis.w)),
            Projection::Orthographic { .. } => None,
        }
    }

    /// The near plane: close to the eye but not at it, where nothing projects.
    fn near(&self) -> f64 {
        f64::from((self.camera.eye - self.camera.look_at).length()) * 1e-3
    }

    fn project_unclipped(&self, p: DVec3) -> Option<DVec2> {
        self.camera.project(self.width, self.height, p).map(|(x, y)| DVec2::new(x, y))
    }
}

/// The part of segment `a`–`b` inside the box from `lo` to `hi`, so a segment
/// reaching far off the picture costs only what it covers when drawn.
pub fn clip_to_box(a: DVec2, b: DVec2, lo: DVec2, hi: DVec2) -> Option<(DVec2, DVec2)> {
    let d = b - a;
    let (mut t0, mut t1) = (0.0_f64, 1.0_f64);
    for axis in 0..2 {
        if d[axis] == 0.0 {
            if a[axis] < lo[axis] || a[axis] > hi[axis] {
                return None;
            }
            continue;
        }
        let (ta, tb) = ((lo[axis] - a[axis]) / d[axis], (hi[axis] - a[axis]) / d[axis]);
        t0 = t0.max(ta.min(tb));
        t1 = t1.min(ta.max(tb));
    }
    (t0 <= t1).then(|| (a + d * t0, a + d * t1))
}

#[cfg(test)]
mod tests;
