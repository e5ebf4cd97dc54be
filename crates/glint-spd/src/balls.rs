//! SPD's `balls` database (`balls.c`), the "sphereflake": a sphere with nine
//! spheres of a third its radius sprouting from it, each of them sprouting nine
//! more, down to the size factor; a square floor and three lights.

use crate::Output;
use crate::vecmath::{self, Axis, Matrix, Vec3, Vec4};
use std::f64::consts::PI;

/// Size 6 prints 597 871 spheres (25 MB of text); size 7 would print 5.4 million (about 230 MB).
pub const MAX_SIZE: u32 = 6;

pub fn generate(size: u32, out: &mut dyn Output) {
    let radius = 1.0;
    out.background([0.078, 0.361, 0.753]);
    out.viewpoint([2.1, 1.3, 1.7], [0.0, 0.0, 0.0], [0.0, 0.0, 1.0], 45.0, 0.01, 512, 512);
    let lscale = out.light_scale(3);
    out.light([4.0, 3.0, 2.0, lscale]);
    out.light([1.0, -4.0, 4.0, lscale]);
    out.light([-3.0, 1.0, 5.0, lscale]);

    out.color([1.0, 0.75, 0.33], 0.2, 0.8, 0.0, 0.0, 0.0, 0.0, 1.0);
    let [x, y, z] = [12.0 * radius, 12.0 * radius, -radius / 2.0];
    out.polygon(&[[x, y, z], [-x, y, z], [-x, -y, z], [x, -y, z]]);

    out.color([1.0, 0.9, 0.7], 0.0, 0.5, 0.5, 0.5, 37.0, 0.0, 1.0);
    let flake = Flake { child_directions: child_directions() };
    flake.output(out, size, [0.0, 0.0, 0.0, radius / 2.0], [0.0, 0.0, 1.0, 1.0 / 3.0]);
}

struct Flake {
    /// Where the nine children sit around a parent growing along +Z, as unit
    /// vectors: a trio (one above the equator, two on it) repeated at 120° turns.
    child_directions: [Vec4; 9],
}

impl Flake {
    /// The sphere `center` (radius in w), and `depth` generations of children
    /// growing along `direction` (whose w is the child/parent radius ratio).
    fn output(&self, out: &mut dyn Output, depth: u32, center: Vec4, direction: Vec4) {
        out.sphere(center);
        if depth == 0 {
            return;
        }
        let to_direction = rotation_from_z([direction[0], direction[1], direction[2]]);
        let scale = center[3] * (1.0 + direction[3]);
        for child_direction in &self.child_directions {
            let offset = vecmath::transform_coord(*child_direction, &to_direction);
            let child: Vec4 = [
                offset[0] * scale + center[0],
                offset[1] * scale + center[1],
                offset[2] * scale + center[2],
                center[3] * direction[3],
            ];
            let grow = [
                (child[0] - center[0]) / scale,
                (child[1] - center[1]) / scale,
                (child[2] - center[2]) / scale,
                direction[3],
            ];
            self.output(out, depth - 1, child, grow);
        }
    }
}

/// The rotation taking +Z to `direction`, a unit vector up to rounding (hence
/// the tolerance on the two poles).
fn rotation_from_z(direction: Vec3) -> Matrix {
    let z_axis = [0.0, 0.0, 1.0];
    if direction[2] >= 0.9999 {
        vecmath::IDENTITY
    } else if direction[2] <= -0.9999 {
        vecmath::rotate(Axis::Y, PI)
    } else {
        let axis = vecmath::normalize(vecmath::cross(z_axis, direction));
        vecmath::rotate_about(axis, vecmath::dot(z_axis, direction).acos())
    }
}

fn child_directions() -> [Vec4; 9] {
    let dist = 1.0 / 2.0f64.sqrt();
    // Three face diagonals of a cube, tipped about (1, -1, 0) so that one points
    // up and two lie on the equator.
    let tip = vecmath::rotate_about(vecmath::normalize([1.0, -1.0, 0.0]), (2.0 / 6.0f64.sqrt()).asin());
    let trio = [[dist, dist, 0.0, 0.0], [dist, 0.0, -dist, 0.0], [0.0, dist, -dist, 0.0]]
        .map(|v| vecmath::transform_coord(v, &tip));
    let mut directions = [[0.0; 4]; 9];
    for set in 0..3 {
        let turn = vecmath::rotate(Axis::Z, set as f64 * 2.0 * PI / 3.0);
        for (i, v) in trio.iter().enumerate() {
            directions[set * 3 + i] = vecmath::transform_coord(*v, &turn);
        }
    }
    directions
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
            // Each sphere has nine children down to depth `size`: (9^(size+1) - 1) / 8 spheres.
            let spheres = (9usize.pow(size + 1) - 1) / 8;
            let want = Counts { spheres, polygons: 1, lights: 3, ..Counts::default() };
            assert_eq!(Counts::of(&scene(size)), want, "size {size}");
        }
    }

    #[test]
    fn deterministic() {
        assert_eq!(scene(2), scene(2));
    }
}
