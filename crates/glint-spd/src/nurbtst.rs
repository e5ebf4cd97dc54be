//! SPD's `nurbtst` database (`nurbtst.c`): one bicubic NURBS patch, 6 × 5
//! control points on open uniform knots, tessellated into 1500 smooth
//! triangles and turned to face the camera. One light.
//!
//! The basis functions are computed in `f32`, as SPD's libpr3 does.

use crate::Output;
use crate::vecmath::{self, Axis, Matrix, Vec3};
use std::f64::consts::PI;

/// `nurbtst` reads `-s` into a C `int` and then ignores it: every size is the
/// same scene, so every size the C program accepts is allowed.
pub const MAX_SIZE: u32 = i32::MAX as u32;

const ORDER: usize = 4;
/// Tessellation steps per control point (`lib_set_polygonalization(5, 5)`).
const RESOLUTION: usize = 5;
/// The open uniform knot vectors `lib_output_nurb` builds when given none, as
/// `nurbtst` asks (its own non-uniform vectors are unused).
const U_KNOTS: [f32; 10] = [0.0, 0.0, 0.0, 0.0, 1.0, 2.0, 3.0, 3.0, 3.0, 3.0];
const V_KNOTS: [f32; 9] = [0.0, 0.0, 0.0, 0.0, 1.0, 2.0, 2.0, 2.0, 2.0];

/// The control net, 6 rows along u of 5 points along v. `nurbtst.c` gives some
/// of them weights other than 1, but `lib_output_polygon_nurb` clears the
/// rational flag, so the patch is evaluated as a plain B-spline.
#[rustfmt::skip]
const CONTROL: [[Vec3; 5]; 6] = [
    [[0.0, 0.0, 0.0], [1.0, 0.0, 3.0], [2.0, 0.0, -3.0], [3.0, 0.0, 3.0], [4.0, 0.0, 0.0]],
    [[0.0, 1.0, 0.0], [1.0, 1.0, 0.0], [2.0, 1.0, 0.0], [3.0, 1.0, 0.0], [4.0, 1.0, 0.0]],
    [[0.0, 2.0, 0.0], [1.0, 2.0, 0.0], [2.0, 2.0, 5.0], [3.0, 2.0, 0.0], [4.0, 2.0, 0.0]],
    [[0.0, 3.0, 0.0], [1.0, 3.0, 0.0], [2.0, 3.0, 5.0], [3.0, 3.0, 0.0], [4.0, 3.0, 0.0]],
    [[0.0, 4.0, 0.0], [1.0, 4.0, 0.0], [2.0, 4.0, 0.0], [3.0, 4.0, 0.0], [4.0, 4.0, 0.0]],
    [[0.0, 5.0, 0.0], [1.0, 5.0, -3.0], [2.0, 5.0, 3.0], [3.0, 5.0, -3.0], [4.0, 5.0, 0.0]],
];

pub fn generate(_size: u32, out: &mut dyn Output) {
    out.background([0.0; 3]);
    out.viewpoint([0.0, 5.0, -10.0], [0.0, 0.0, 0.0], [0.0, 1.0, 0.0], 30.0, 0.001, 256, 256);
    out.light([0.0, 50.0, -10.0, 1.0]);
    out.color([1.0, 0.0, 0.0], 0.1, 0.7, 0.0, 0.7, 10.0, 0.0, 1.0);

    // lib_tx_rotate / lib_tx_translate each put the new step in front of the
    // current transform (row vectors: the last call applies first).
    let mut tx = vecmath::IDENTITY;
    tx = vecmath::multiply(&vecmath::rotate(Axis::Y, PI * 30.0 / 180.0), &tx);
    tx = vecmath::multiply(&vecmath::rotate(Axis::X, PI * -90.0 / 180.0), &tx);
    tx = vecmath::multiply(&vecmath::translate([-2.0, -2.5, 0.0]), &tx);
    let normal_tx = invert(&tx);
    let mut emit = |corners: [&(Vec3, Vec3); 3]| {
        // split_polygon moves the vertices by the transform and the normals by its inverse transpose.
        let vertices = corners.map(|c| vecmath::transform_point(c.0, &tx));
        let normals = corners.map(|c| transform_normal(c.1, &normal_tx));
        out.polypatch(&vertices, &normals);
    };

    // lib_output_polygon_nurb: rows of points at u = 0, du, 2du, … (summed in
    // f32), each joined to the previous row by two triangles per step in v.
    let (u_steps, v_steps) = (CONTROL.len() * RESOLUTION, CONTROL[0].len() * RESOLUTION);
    let u_delta = (CONTROL.len() + 1 - ORDER) as f32 / u_steps as f32;
    let v_delta = (CONTROL[0].len() + 1 - ORDER) as f32 / v_steps as f32;
    let mut previous: Vec<(Vec3, Vec3)> = Vec::new();
    let mut u = 0.0f32;
    for i in 0..=u_steps {
        let mut v = 0.0f32;
        let row: Vec<_> = (0..=v_steps)
            .map(|_| {
                let point = surface_point(u, v);
                v += v_delta;
                point
            })
            .collect();
        if i > 0 {
            for j in 0..v_steps {
                emit([&previous[j], &row[j], &row[j + 1]]);
                emit([&previous[j], &row[j + 1], &previous[j + 1]]);
            }
        }
        previous = row;
        u += u_delta;
    }
}

/// `NurbNormal` without weights: the point at (u, v) and its normal ∂p/∂v × ∂p/∂u.
fn surface_point(u: f32, v: f32) -> (Vec3, Vec3) {
    let (u_basis, u_deriv) = basis(u, CONTROL.len(), &U_KNOTS);
    let (v_basis, v_deriv) = basis(v, CONTROL[0].len(), &V_KNOTS);
    let (mut point, mut du, mut dv) = ([0.0; 3], [0.0; 3], [0.0; 3]);
    for (i, row) in CONTROL.iter().enumerate() {
        for (j, control) in row.iter().enumerate() {
            let weight = f64::from(u_basis[i] * v_basis[j]);
            let weight_du = f64::from(u_deriv[i] * v_basis[j]);
            let weight_dv = f64::from(u_basis[i] * v_deriv[j]);
            for k in 0..3 {
                point[k] += weight * control[k];
                du[k] += weight_du * control[k];
                dv[k] += weight_dv * control[k];
            }
        }
    }
    (point, vecmath::normalize(vecmath::cross(dv, du)))
}

/// `NurbDBasis`: the order-4 B-spline basis functions at `t` over `knots`, and
/// their derivatives, by the Cox–de Boor recursion in f32.
fn basis(t: f32, points: usize, knots: &[f32]) -> (Vec<f32>, Vec<f32>) {
    let n = knots.len();
    let mut basis: Vec<f32> = (0..n).map(|i| f32::from(i + 1 < n && t >= knots[i] && t < knots[i + 1])).collect();
    // The parameter at the top end belongs to the last span.
    if t >= knots[n - 1] {
        basis[points - 1] = 1.0;
    }
    let mut deriv = vec![0.0f32; n];
    for k in 2..=ORDER {
        // Index i is rewritten after its last read (as i - 1's right neighbour).
        for i in 0..n - k {
            // A nonzero function of the lower order has a span of nonzero length.
            let left = knots[i + k - 1] - knots[i];
            let right = knots[i + k] - knots[i + 1];
            let nonzero = |x: f32, value: f32| if x != 0.0 { value } else { 0.0 };
            let b1 = nonzero(basis[i], (t - knots[i]) * basis[i] / left);
            let b2 = nonzero(basis[i + 1], (knots[i + k] - t) * basis[i + 1] / right);
            let f1 = nonzero(basis[i], basis[i] / left);
            let f2 = nonzero(basis[i + 1], -basis[i + 1] / right);
            let f3 = nonzero(deriv[i], (t - knots[i]) * deriv[i] / left);
            let f4 = nonzero(deriv[i + 1], (knots[i + k] - t) * deriv[i + 1] / right);
            basis[i] = b1 + b2;
            deriv[i] = f1 + f2 + f3 + f4;
        }
    }
    (basis, deriv)
}

/// `lib_transform_normal`: `n` times the transpose of `m`.
fn transform_normal(n: Vec3, m: &Matrix) -> Vec3 {
    std::array::from_fn(|i| n[0] * m[i][0] + n[1] * m[i][1] + n[2] * m[i][2])
}

/// `lib_invert_matrix`: the adjoint over the determinant (identity if singular).
fn invert(m: &Matrix) -> Matrix {
    // The 3×3 minor without row `skip_row` and column `skip_col`, expanded as libvec's det3x3.
    let minor = |skip_row: usize, skip_col: usize| {
        let rows: Vec<usize> = (0..4).filter(|&r| r != skip_row).collect();
        let cols: Vec<usize> = (0..4).filter(|&c| c != skip_col).collect();
        let e = |col: usize, row: usize| m[rows[row]][cols[col]];
        e(0, 0) * (e(1, 1) * e(2, 2) - e(1, 2) * e(2, 1)) - e(1, 0) * (e(0, 1) * e(2, 2) - e(0, 2) * e(2, 1))
            + e(2, 0) * (e(0, 1) * e(1, 2) - e(0, 2) * e(1, 1))
    };
    let det = m[0][0] * minor(0, 0) - m[0][1] * minor(0, 1) + m[0][2] * minor(0, 2) - m[0][3] * minor(0, 3);
    if det.abs() < 1.0e-8 {
        return vecmath::IDENTITY;
    }
    std::array::from_fn(|i| {
        std::array::from_fn(|j| {
            let cofactor = minor(j, i);
            (if (i + j) % 2 == 1 { -cofactor } else { cofactor }) / det
        })
    })
}

#[cfg(test)]
mod tests {
    use super::{MAX_SIZE, generate, invert};
    use crate::nff_out::Counts;
    use crate::vecmath;

    fn text(size: u32) -> String {
        crate::nff_out::generated(generate, size)
    }

    #[test]
    fn primitive_counts_follow_the_tessellation() {
        // (6 control points × 5 steps) × (5 × 5) quads, two triangles each.
        let expected = Counts { patches: 2 * (6 * 5) * (5 * 5), lights: 1, ..Counts::default() };
        for size in 1..=3 {
            assert_eq!(Counts::of(&text(size)), expected, "size {size}");
        }
    }

    #[test]
    fn ignores_the_size_and_is_deterministic() {
        let scene = text(1);
        assert_eq!(text(1), scene);
        assert_eq!(text(2), scene);
        assert_eq!(text(MAX_SIZE), scene);
    }

    #[test]
    fn invert_undoes_a_transform() {
        let m = vecmath::multiply(&vecmath::rotate(vecmath::Axis::Z, 0.3), &vecmath::translate([1.0, -2.0, 3.0]));
        let product = vecmath::multiply(&m, &invert(&m));
        for (i, row) in product.iter().enumerate() {
            for (j, &value) in row.iter().enumerate() {
                assert!((value - f64::from(u8::from(i == j))).abs() < 1e-12, "{product:?}");
            }
        }
    }
}
