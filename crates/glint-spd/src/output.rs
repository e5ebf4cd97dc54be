//! What every generator calls: SPD's `lib_output_*` functions, one method
//! each. Each output format implements them in its own file, as SPD's
//! library switches on the format inside each function: `nff_out.rs`
//! (`-r 1`) and `rayshade_out.rs` (`-r 8`).

use crate::fmt_g;
use crate::vecmath::{self, Vec3, Vec4};

/// SPD's `EPSILON2`: edges shorter than this make a polygon vertex a duplicate.
const DEGENERATE_EDGE: f64 = 1.0e-6;

/// The scene text a generator writes, in one of SPD's output formats.
pub trait Output {
    /// SPD's `lscale` for a scene of `lights` lights: each generator gives
    /// its lights 1/√n, except for formats whose tracers scale the
    /// intensities themselves (NFF), which get 1.
    fn light_scale(&self, lights: u32) -> f64;
    /// `lib_output_background_color`.
    fn background(&mut self, color: Vec3);
    /// `lib_output_viewpoint`, with SPD's aspect ratio of 1.
    #[allow(clippy::too_many_arguments)]
    fn viewpoint(&mut self, from: Vec3, at: Vec3, up: Vec3, angle: f64, hither: f64, resx: i32, resy: i32);
    /// `lib_output_light`: a point light, its intensity in `[3]`.
    fn light(&mut self, center: Vec4);
    /// `lib_output_color`: the surface of the objects that follow.
    #[allow(clippy::too_many_arguments)]
    fn color(&mut self, color: Vec3, ka: f64, kd: f64, ks: f64, ks_spec: f64, ang: f64, kt: f64, ior: f64);
    /// `lib_output_sphere`.
    fn sphere(&mut self, center: Vec4);
    /// `lib_output_cylcone`: an open cone or cylinder between two ends.
    fn cylcone(&mut self, base: Vec4, apex: Vec4);
    /// `lib_output_polygon`, given the vertices [`kept_vertices`] leaves.
    fn polygon_kept(&mut self, vertices: &[Vec3]);
    /// `lib_output_polypatch`: a triangle with a normal per vertex (SPD
    /// splits every larger patch into triangles, so its files hold only these).
    fn polypatch(&mut self, vertices: &[Vec3; 3], normals: &[Vec3; 3]);

    /// `lib_output_polygon`: a vertex closer than 1e-6 to the next one
    /// (cyclically) is dropped, and what is left is printed only if it still
    /// has three vertices.
    fn polygon(&mut self, vertices: &[Vec3]) {
        let mut kept = vertices.to_vec();
        let mut i = 0;
        while i < kept.len() {
            let next = kept[(i + 1) % kept.len()];
            if vecmath::length(vecmath::sub(kept[i], next)) < DEGENERATE_EDGE {
                kept.remove(i);
            } else {
                i += 1;
            }
        }
        if kept.len() >= 3 {
            self.polygon_kept(&kept);
        }
    }
}

/// The Phong exponent SPD derives from the highlight's half angle `ang`
/// (degrees), in `lib_output_color`.
pub fn phong_pow(ang: f64) -> f64 {
    let ang_radians = std::f64::consts::PI * ang / 180.0;
    if ang_radians <= 0.0 {
        100000.0
    } else if ang_radians >= std::f64::consts::PI / 2.0 {
        1.0
    } else {
        0.5f64.ln() / ang_radians.cos().ln()
    }
}

/// Appends `values` to `text` as `%g %g …`.
pub fn push_numbers(text: &mut String, values: &[f64]) {
    for (i, v) in values.iter().enumerate() {
        if i > 0 {
            text.push(' ');
        }
        text.push_str(&fmt_g(*v));
    }
}
