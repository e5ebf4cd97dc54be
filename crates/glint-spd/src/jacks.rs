//! SPD's `jacks` database (`jacks.c`, by Alexander Enzmann): a jack (three
//! crossed cylinders with spheres on their ends) with a half-size copy in each
//! of its eight octants, recursively, down to the size factor. One light.

use crate::Output;
use crate::vecmath::{self, Axis, Matrix, Vec4};
use std::f64::consts::PI;

/// Size 7 prints 299 593 jacks (147 MB of text); size 8 would print eight times as much.
pub const MAX_SIZE: u32 = 7;

pub fn generate(size: u32, out: &mut dyn Output) {
    out.background([0.2, 0.05, 0.2]);
    out.viewpoint([0.0, 0.0, -8.0], [0.0, 0.0, 0.0], [0.0, 1.0, 0.0], 25.0, 0.001, 256, 256);
    out.light([-10.0, 3.0, -20.0, 1.0]);
    // Each of jacks.c's transform calls acts before the ones so far: the scene turns
    // -20° about Y, then -30° about X.
    let tilt =
        vecmath::multiply(&vecmath::rotate(Axis::Y, -20.0 * PI / 180.0), &vecmath::rotate(Axis::X, -30.0 * PI / 180.0));
    out.color([0.737, 0.561, 0.561], 0.1, 0.7, 0.7, 0.4, 20.0, 0.0, 1.0);
    jack_and_children(out, size, &tilt);
}

/// The jack placed by `transform`, and `generations - 1` generations of
/// half-size jacks in its octants.
fn jack_and_children(out: &mut dyn Output, generations: u32, transform: &Matrix) {
    jack(out, &vecmath::multiply(&vecmath::scale([0.75; 3]), transform));
    if generations <= 1 {
        return;
    }
    for x in [-0.5, 0.5] {
        for y in [-0.5, 0.5] {
            for z in [-0.5, 0.5] {
                let moved = vecmath::multiply(&vecmath::translate([x, y, z]), transform);
                jack_and_children(out, generations - 1, &vecmath::multiply(&vecmath::scale([0.5; 3]), &moved));
            }
        }
    }
}

/// A jack spanning -1..1 on each axis before `transform`.
fn jack(out: &mut dyn Output, transform: &Matrix) {
    let arm = |axis: usize, end: f64, radius: f64| {
        let mut point = [0.0, 0.0, 0.0, radius];
        point[axis] = end;
        place(point, transform)
    };
    for axis in 0..3 {
        out.cylcone(arm(axis, -1.0, 0.1), arm(axis, 1.0, 0.1));
    }
    for end in [1.0, -1.0] {
        for axis in 0..3 {
            out.sphere(arm(axis, end, 0.2));
        }
    }
}

/// What SPD's NFF output does to a sphere or cone end under a transform: moves
/// the centre and scales the radius by the transform's x scale (it assumes
/// uniform scaling), the length of the first matrix row. The matrices here
/// never have a perspective part, so SPD's division by `m[3][3]` is one by 1.
fn place(point: Vec4, transform: &Matrix) -> Vec4 {
    let [x, y, z] = vecmath::transform_point([point[0], point[1], point[2]], transform);
    let x_scale = vecmath::length([transform[0][0], transform[0][1], transform[0][2]]);
    [x, y, z, point[3] * x_scale]
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
            // 1 + 8 + ... + 8^(size-1) = (8^size - 1) / 7 jacks, each 3 cylinders and 6 spheres.
            let jacks = (8usize.pow(size) - 1) / 7;
            let want = Counts { spheres: 6 * jacks, cones: 3 * jacks, lights: 1, ..Counts::default() };
            assert_eq!(Counts::of(&scene(size)), want, "size {size}");
        }
    }

    #[test]
    fn deterministic() {
        assert_eq!(scene(2), scene(2));
    }
}
