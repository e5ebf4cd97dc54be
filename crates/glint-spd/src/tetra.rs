//! SPD's `tetra` database (`tetra.c`): a Sierpinski tetrahedron, each
//! tetrahedron split into four half-size ones down to the size factor, with the
//! view and light of Kay & Kajiya's test scene.

use crate::Output;
use crate::vecmath::{Vec3, Vec4};

/// Size 10 prints a million triangles (92 MB of text); size 11 would print four times as much.
pub const MAX_SIZE: u32 = 10;

pub fn generate(size: u32, out: &mut dyn Output) {
    out.background([0.078, 0.361, 0.753]);
    out.viewpoint(
        [1.022846, -3.177154, -2.174512],
        [-0.004103, -0.004103, 0.216539],
        [-0.816497, -0.816497, 0.816497],
        45.0,
        1.0,
        512,
        512,
    );
    out.light([2.0, -18.0, -5.0, out.light_scale(1)]);
    out.color([1.0, 0.2, 0.2], 0.0, 1.0, 0.0, 0.0, 0.0, 0.0, 0.0);
    tetrahedron(out, size, [0.0, 0.0, 0.0, 1.0]);
}

/// The four corners (x, y, z) = (±1, ±1, ±1) with x·y·z = 1 of the cube around
/// `center` with half-width w, in tetra.c's order.
fn corners(center: Vec4, half_width: f64) -> [Vec3; 4] {
    let mut corners = [[0.0; 3]; 4];
    let mut n = 0;
    for x in [-1, 1] {
        for y in [-1, 1] {
            for z in [-1, 1] {
                if x * y * z == 1 {
                    corners[n] = [
                        center[0] + x as f64 * half_width,
                        center[1] + y as f64 * half_width,
                        center[2] + z as f64 * half_width,
                    ];
                    n += 1;
                }
            }
        }
    }
    corners
}

/// The tetrahedron inscribed in the cube `center` (half-width in w): at depth 1
/// its four faces, otherwise the four half-size tetrahedra at its corners.
fn tetrahedron(out: &mut dyn Output, depth: u32, center: Vec4) {
    if depth <= 1 {
        let [a, b, c, d] = corners(center, center[3]);
        // Counterclockwise seen from outside.
        for face in [[a, b, c], [d, c, b], [c, d, a], [b, a, d]] {
            out.polygon(&face);
        }
    } else {
        for [x, y, z] in corners(center, center[3] / 2.0) {
            tetrahedron(out, depth - 1, [x, y, z, center[3] / 2.0]);
        }
    }
}

#[cfg(test)]
mod tests {
    use super::generate;
    use crate::nff_out::Counts;

    fn scene(size: u32) -> String {
        crate::nff_out::generated(generate, size)
    }

    #[test]
    fn primitive_counts() {
        for size in 1..=3 {
            // 4^(size-1) tetrahedra of four triangles each: 4^size polygons.
            let want = Counts { polygons: 4usize.pow(size), lights: 1, ..Counts::default() };
            assert_eq!(Counts::of(&scene(size)), want, "size {size}");
        }
    }

    #[test]
    fn deterministic() {
        assert_eq!(scene(3), scene(3));
    }
}
