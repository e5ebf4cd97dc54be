//! SPD's `mount` database (`mount.c`): a fractal mountain grown by Carpenter's
//! midpoint subdivision of a square, 2·4^SIZE triangles, with a pyramid of four
//! glass spheres in front of it. One light.

use std::f64::consts::PI;

use crate::Output;
use crate::vecmath::{Vec3, Vec4};

/// SPD's seed hash shifts by `7 - SIZE` bits, a negative (undefined) shift in C
/// past size 7, so no original output exists beyond it (size 7: 2.7 MB).
pub const MAX_SIZE: u32 = 7;

/// Between 2 and 3; sets how fast the height variance falls with the square's size.
const FRACTAL_DIMENSION: f64 = 2.2;
/// Change it for another mountain.
const MOUNTAIN_NO: i64 = 21;
/// Lower left corner and width of the mountain's square.
const CORNER: f64 = -1.0;
const WIDTH: f64 = 2.0;
/// SPD's √2, rounded to 8 digits; the heights depend on it, so it stays.
#[expect(clippy::approx_constant, reason = "SPD's own rounding of the constant")]
const SQRT_2: f64 = 1.4142136;

pub fn generate(size: u32, out: &mut dyn Output) {
    out.background([0.078, 0.361, 0.753]);
    out.viewpoint([-1.6, 1.6, 1.7], [0.0, 0.0, 0.0], [0.0, 0.0, 1.0], 45.0, 0.01, 512, 512);
    out.light([-100.0, -100.0, 100.0, out.light_scale(1)]);

    out.color([1.0, 1.0, 1.0], 0.0, 0.1, 0.1, 0.4, 6.7, 0.9, 1.5);
    create_spheres([-0.8, 0.8, 1.0, 0.17], out);

    out.color([0.5, 0.45, 0.35], 0.0, 1.0, 0.0, 0.0, 0.0, 0.0, 0.0);
    let num_pts = 1 << size;
    let ratio = 2.0 / (2.0f64.ln() / (FRACTAL_DIMENSION - 1.0)).exp();
    let mountain = Mountain { size, fnum_pts: f64::from(num_pts), roughness: (ratio * ratio - 1.0).sqrt() };
    mountain.grow(num_pts, 0, 0, [0.0; 4], out);
}

/// Four spheres of radius `center[3]` touching one another: one on top, three
/// around `center` below it.
fn create_spheres(center: Vec4, out: &mut dyn Output) {
    // (1, 1, 0) normalized, as lib_normalize_vector divides it.
    let axis = [1.0 / 2.0f64.sqrt(), 1.0 / 2.0f64.sqrt(), 0.0];
    let pt = [0.0, 0.0, center[3] * (3.0f64 / 2.0).sqrt()];
    out.sphere([center[0] + pt[0], center[1] + pt[1], center[2] + pt[2], center[3]]);

    let new_pt = transform_vector(pt, &axis_rotate_matrix(axis, (-1.0f64 / 3.0).acos()));
    for i in 0..3 {
        let p = transform_vector(new_pt, &z_rotate_matrix(f64::from(i) * 2.0 * PI / 3.0));
        out.sphere([p[0] + center[0], p[1] + center[1], p[2] + center[2], center[3]]);
    }
}

type Matrix3 = [[f64; 3]; 3];

/// `lib_create_axis_rotate_matrix` (the 3×3 part `lib_transform_vector` uses).
fn axis_rotate_matrix(axis: Vec3, angle: f64) -> Matrix3 {
    let (cosine, sine) = (angle.cos(), angle.sin());
    let one_minus_cosine = 1.0 - cosine;
    let [x, y, z] = axis;
    [
        [x * x + (1.0 - x * x) * cosine, x * y * one_minus_cosine + z * sine, x * z * one_minus_cosine - y * sine],
        [x * y * one_minus_cosine - z * sine, y * y + (1.0 - y * y) * cosine, y * z * one_minus_cosine + x * sine],
        [x * z * one_minus_cosine + y * sine, y * z * one_minus_cosine - x * sine, z * z + (1.0 - z * z) * cosine],
    ]
}

/// `lib_create_rotate_matrix(Z_AXIS, angle)`.
fn z_rotate_matrix(angle: f64) -> Matrix3 {
    let (cosine, sine) = (angle.cos(), angle.sin());
    [[cosine, sine, 0.0], [-sine, cosine, 0.0], [0.0, 0.0, 1.0]]
}

/// `lib_transform_vector`: the row vector `v` times `m`.
fn transform_vector(v: Vec3, m: &Matrix3) -> Vec3 {
    let column = |j: usize| v[0] * m[0][j] + v[1] * m[1][j] + v[2] * m[2][j];
    [column(0), column(1), column(2)]
}

struct Mountain {
    size: u32,
    fnum_pts: f64,
    roughness: f64,
}

impl Mountain {
    /// The square of `width` grid cells at (`ll_x`, `ll_y`) with corner heights
    /// `z` (lower left, lower right, upper right, upper left): two triangles for
    /// one cell, else four quarter squares whose new corners are the edge and
    /// centre midpoints, raised by a random amount that shrinks with the width.
    fn grow(&self, width: u32, ll_x: u32, ll_y: u32, z: [f64; 4], out: &mut dyn Output) {
        let [ll_fz, lr_fz, ur_fz, ul_fz] = z;
        if width == 1 {
            let l_fx = CORNER + f64::from(ll_x) * WIDTH / self.fnum_pts;
            let r_fx = CORNER + f64::from(ll_x + 1) * WIDTH / self.fnum_pts;
            let l_fy = CORNER + f64::from(ll_y) * WIDTH / self.fnum_pts;
            let u_fy = CORNER + f64::from(ll_y + 1) * WIDTH / self.fnum_pts;
            let corners = [[l_fx, l_fy, ll_fz], [r_fx, l_fy, lr_fz], [r_fx, u_fy, ur_fz], [l_fx, u_fy, ul_fz]];
            out.polygon(&[corners[0], corners[1], corners[2]]);
            out.polygon(&[corners[2], corners[3], corners[0]]);
            return;
        }
        let half = width >> 1;
        let hside_length = f64::from(half) * WIDTH / self.fnum_pts;
        let rise_height = hside_length * self.roughness;
        let bump = |x: u32, y: u32| gauss_rand(MOUNTAIN_NO + hash_rand(x, y, self.size));

        let lower_fz = (ll_fz + lr_fz) / 2.0 + rise_height * bump(ll_x + half, ll_y);
        let right_fz = (lr_fz + ur_fz) / 2.0 + rise_height * bump(ll_x + width, ll_y + half);
        let upper_fz = (ur_fz + ul_fz) / 2.0 + rise_height * bump(ll_x + half, ll_y + width);
        let left_fz = (ul_fz + ll_fz) / 2.0 + rise_height * bump(ll_x, ll_y + half);
        let middle_fz = (ll_fz + lr_fz + ur_fz + ul_fz) / 4.0 + SQRT_2 * rise_height * bump(ll_x + half, ll_y + half);

        self.grow(half, ll_x, ll_y, [ll_fz, lower_fz, middle_fz, left_fz], out);
        self.grow(half, ll_x + half, ll_y, [lower_fz, lr_fz, right_fz, middle_fz], out);
        self.grow(half, ll_x + half, ll_y + half, [middle_fz, right_fz, ur_fz, upper_fz], out);
        self.grow(half, ll_x, ll_y + half, [left_fz, middle_fz, upper_fz, ul_fz], out);
    }
}

/// The seed of a grid point: SPD's original hash, kept although it repeats
/// (it makes the mountain of the November 1987 IEEE CG&A article).
fn hash_rand(a: u32, b: u32, size: u32) -> i64 {
    let (a, b) = (u64::from(a), u64::from(b));
    (((a << (23 - size)) + (b << (15 - size)) + (a << (7 - size))) & 0xffff) as i64
}

/// `lib_gauss_rand`: a normal deviate from a seed, by the polar method on a
/// linear congruential generator (Numerical Recipes' GASDEV).
fn gauss_rand(seed: i64) -> f64 {
    const M1: i64 = 134456;
    const IA1: i64 = 8121;
    const IC1: i64 = 28411;
    let mut ix2 = seed;
    loop {
        let ix1 = (IC1 + ix2 * IA1) % M1;
        ix2 = (IC1 + ix1 * IA1) % M1;
        // SPD's `ix * 2.0 * RM1` expands to `ix * 2.0 * 1.0 / M1`.
        let v1 = ix1 as f64 * 2.0 * 1.0 / M1 as f64 - 1.0;
        let v2 = ix2 as f64 * 2.0 * 1.0 / M1 as f64 - 1.0;
        let r = v1 * v1 + v2 * v2;
        if r < 1.0 {
            return v1 * (-2.0 * r.ln() / r).sqrt();
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::nff_out::count;

    fn text(size: u32) -> String {
        crate::nff_out::generated(generate, size)
    }

    #[test]
    fn primitive_counts() {
        for size in 1..=3 {
            let text = text(size);
            // 4^SIZE grid cells of two triangles each; the four spheres.
            assert_eq!(count(&text, "p"), 2 * 4usize.pow(size), "size {size}");
            assert_eq!(count(&text, "s"), 4);
            assert_eq!(count(&text, "l"), 1);
            for other in ["c", "pp"] {
                assert_eq!(count(&text, other), 0);
            }
        }
    }

    #[test]
    fn deterministic() {
        assert_eq!(text(3), text(3));
    }

    #[test]
    fn seeds_and_deviates() {
        // Worked by hand from the C: seed 21 gives ix1 = 64496, ix2 = 94307, inside the unit circle.
        let (v1, v2) = (64496.0 * 2.0 / 134456.0 - 1.0, 94307.0 * 2.0 / 134456.0 - 1.0);
        let r: f64 = v1 * v1 + v2 * v2;
        assert_eq!(gauss_rand(21), v1 * (-2.0 * r.ln() / r).sqrt());
        // (1 << 22) + (1 << 6), masked to 16 bits.
        assert_eq!(hash_rand(1, 0, 1), 64);
    }
}
