//! SPD's `tree` database (`tree.c`): a binary tree grown by Aono and Kunii's
//! method (IEEE CG&A, May 1984), each branch a cone capped by a sphere, over
//! a square field. Seven lights.

use std::f64::consts::PI;

use crate::Output;
use crate::vecmath::Vec4;

/// Output doubles with each size (2^(SIZE+1) - 1 branches, about 120 bytes
/// each): size 19 is about 125 MB.
pub const MAX_SIZE: u32 = 19;

/// The two child branches' angles from their parent (degrees), length
/// contractions, and turns about the parent (degrees).
const BR_ANGLE: [f64; 2] = [40.0, 25.0];
const BR_CONTR: [f64; 2] = [0.65, 0.70];
const DIV_ANGLE: [f64; 2] = [90.0, 140.0 + 90.0];
/// Radius contraction along a branch and from parent to child.
const BR_DIAMETER: f64 = 0.67;
const WIDTH_HEIGHT_RATIO: f64 = 0.15;

pub fn generate(size: u32, out: &mut dyn Output) {
    out.background([0.078, 0.361, 0.753]);
    out.viewpoint([4.5, 0.4, 2.0], [0.0, 0.0, 1.5], [0.0, 0.0, 1.0], 45.0, 1.0, 512, 512);
    let lights = [
        [-5.0, 5.0, 50.0],
        [30.0, -30.0, 30.0],
        [-40.0, -30.0, 20.0],
        [10.0, 30.0, 40.0],
        [-30.0, 40.0, 10.0],
        [50.0, 25.0, 20.0],
        [-10.0, -60.0, 30.0],
    ];
    for light in lights {
        out.light([light[0], light[1], light[2], out.light_scale(7)]);
    }

    out.color([0.2, 0.7, 0.2], 0.0, 1.0, 0.0, 0.0, 0.0, 0.0, 0.0);
    out.polygon(&[[50.0, 50.0, 0.0], [-50.0, 50.0, 0.0], [-50.0, -50.0, 0.0], [50.0, -50.0, 0.0]]);

    out.color([0.55, 0.4, 0.2], 0.0, 1.0, 0.0, 0.0, 0.0, 0.0, 0.0);
    let branch = [0, 1].map(|i| {
        let rotate = multiply(
            &rotate_matrix(Axis::X, BR_ANGLE[i] * PI / 180.0),
            &rotate_matrix(Axis::Z, DIV_ANGLE[i] * PI / 180.0),
        );
        let mut scale_translate = identity();
        for (k, row) in scale_translate.iter_mut().take(3).enumerate() {
            row[k] = BR_CONTR[i];
        }
        // The child starts at its parent's tip.
        scale_translate[3][2] = 1.0;
        multiply(&rotate, &scale_translate)
    });
    grow_tree(&identity(), 1.0, size, &branch, out);
}

/// Outputs the unit branch along z placed by `mx`, then its two children.
fn grow_tree(mx: &Matrix, scale: f64, depth: u32, branch: &[Matrix; 2], out: &mut dyn Output) {
    let base = transform_point([0.0, 0.0, 0.0], mx, scale * WIDTH_HEIGHT_RATIO);
    let apex = transform_point([0.0, 0.0, 1.0], mx, base[3] * BR_DIAMETER);
    out.cylcone(base, apex);
    out.sphere(apex);
    if depth > 0 {
        for child in branch {
            grow_tree(&multiply(child, mx), scale * BR_DIAMETER, depth - 1, branch, out);
        }
    }
}

/// SPD's `MATRIX`: row-major, applied to row vectors (`v · M`).
type Matrix = [[f64; 4]; 4];

enum Axis {
    X,
    Z,
}

fn identity() -> Matrix {
    std::array::from_fn(|i| std::array::from_fn(|j| if i == j { 1.0 } else { 0.0 }))
}

/// `lib_create_rotate_matrix`.
fn rotate_matrix(axis: Axis, angle: f64) -> Matrix {
    let (cosine, sine) = (angle.cos(), angle.sin());
    let mut mx = identity();
    let (a, b) = match axis {
        Axis::X => (1, 2),
        Axis::Z => (0, 1),
    };
    mx[a][a] = cosine;
    mx[b][b] = cosine;
    mx[a][b] = sine;
    mx[b][a] = -sine;
    mx
}

/// `lib_matrix_multiply`: `m1 · m2`, each sum from left to right.
fn multiply(m1: &Matrix, m2: &Matrix) -> Matrix {
    std::array::from_fn(|i| {
        std::array::from_fn(|j| m1[i][0] * m2[0][j] + m1[i][1] * m2[1][j] + m1[i][2] * m2[2][j] + m1[i][3] * m2[3][j])
    })
}

/// `lib_transform_point` of `v`, with `radius` as the fourth coordinate.
fn transform_point(v: [f64; 3], mx: &Matrix, radius: f64) -> Vec4 {
    let column = |j: usize| v[0] * mx[0][j] + v[1] * mx[1][j] + v[2] * mx[2][j] + mx[3][j];
    [column(0), column(1), column(2), radius]
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
            // A full binary tree of depth SIZE: 2^(SIZE+1) - 1 branches, each a cone and a sphere.
            let branches = (1 << (size + 1)) - 1;
            assert_eq!(count(&text, "c"), branches, "size {size}");
            assert_eq!(count(&text, "s"), branches, "size {size}");
            assert_eq!(count(&text, "p"), 1);
            assert_eq!(count(&text, "l"), 7);
            assert_eq!(count(&text, "pp"), 0);
        }
    }

    #[test]
    fn deterministic() {
        assert_eq!(text(3), text(3));
    }
}
