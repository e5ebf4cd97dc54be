//! SPD's `sombrero` database (`sombrero.c`, by Alexander Enzmann): the height
//! field of a damped cosine ripple, `cos(2πr)·e^-r`, sampled on a
//! 32·2^(SIZE-1) square grid and output as triangles. One light.

use crate::Output;

/// Output grows as 4^SIZE: size 6 (a 1024² grid, 2.1 million triangles) is
/// about 173 MB.
pub const MAX_SIZE: u32 = 6;

pub fn generate(size: u32, out: &mut dyn Output) {
    out.background([0.078, 0.361, 0.753]);
    out.viewpoint([0.0, 5.0, -8.0], [0.0, 0.0, 0.0], [0.0, 0.0, 1.0], 40.0, 0.01, 512, 512);
    out.light([10.0, 10.0, -10.0, 1.0]);
    out.color([1.0, 0.1, 0.1], 0.1, 0.8, 0.0, 0.5, 40.0, 0.0, 1.0);

    let width = 32 << (size - 1);
    let data = create_sombrero(width, -4.0, 4.0);
    output_height(&data, [-4.0, 4.0], -3.0, [-4.0, 4.0], out);
}

/// SPD's π, rounded to 12 digits; the heights depend on it, so it stays.
#[expect(clippy::approx_constant, reason = "SPD's own rounding of the constant")]
const PI: f64 = 3.14159265358;

/// Rows of samples over the square [lo, hi]², y by row and x by column,
/// stored in single precision as SPD's `float **` holds them.
fn create_sombrero(width: usize, lo: f64, hi: f64) -> Vec<Vec<f32>> {
    let (a, b, c) = (1.0, 1.0, 3.0);
    let two_pi_a = 2.0 * PI * a;
    let delta = (hi - lo) / width as f64;
    // SPD steps x and y by repeated addition, not by multiplication.
    let steps = || std::iter::successors(Some(lo), move |v| Some(v + delta)).take(width);
    steps()
        .map(|y| {
            steps()
                .map(|x| {
                    let r = (x * x + y * y).sqrt();
                    (c * (two_pi_a * r).cos() * (-b * r).exp() / 3.0) as f32
                })
                .collect()
        })
        .collect()
}

/// `lib_output_polygon_height`: each grid cell as two triangles, the height
/// along y (offset by `y0`), rows along z and columns along x.
fn output_height(data: &[Vec<f32>], x: [f64; 2], y0: f64, z: [f64; 2], out: &mut dyn Output) {
    let (height, width) = (data.len(), data[0].len());
    let xdelta = (x[1] - x[0]) / (width - 1) as f64;
    let zdelta = (z[1] - z[0]) / (height - 1) as f64;
    let vertex = |i: usize, j: usize| [x[0] + j as f64 * xdelta, y0 + f64::from(data[i][j]), z[0] + i as f64 * zdelta];
    for i in 0..height - 1 {
        for j in 0..width - 1 {
            out.polygon(&[vertex(i, j), vertex(i + 1, j + 1), vertex(i, j + 1)]);
            out.polygon(&[vertex(i, j), vertex(i + 1, j), vertex(i + 1, j + 1)]);
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
            // A grid of n = 32·2^(SIZE-1) samples a side has (n-1)² cells of two triangles.
            let cells = (32usize << (size - 1)) - 1;
            assert_eq!(count(&text, "p"), 2 * cells * cells, "size {size}");
            assert_eq!(count(&text, "l"), 1);
            for other in ["s", "c", "pp"] {
                assert_eq!(count(&text, other), 0);
            }
        }
    }

    #[test]
    fn deterministic() {
        assert_eq!(text(2), text(2));
    }
}
