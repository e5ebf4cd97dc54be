//! SPD's `rings` database (`rings.c`): objects of six pentagonal rings through
//! the edge midpoints of a dodecahedron, each ring five cylinders with spheres
//! at the joints, stacked in a pyramid the viewer looks at from its tip. A wall
//! behind catches the shadows of three lights.

use crate::Output;
use crate::vecmath::{self, Axis, Vec3};
use std::f64::consts::PI;

/// Size 58 prints 2 million spheres and as many cylinders (200 MB of text).
pub const MAX_SIZE: u32 = 58;

/// Radius of the cylinders and of the spheres at their joints.
const TUBE_RADIUS: f64 = 0.07412;

pub fn generate(size: u32, out: &mut dyn Output) {
    // The pyramid's layers lie this far apart (rings.c's SPREAD_OUT of 1), its objects 2 apart within a layer.
    let spread = 1.0 / (PI / 8.0).sin();

    out.background([0.078, 0.361, 0.753]);
    let from = [-1.0, -spread, 0.5];
    out.viewpoint(from, [from[0], from[1] + 1.0, from[2]], [0.0, 0.0, 1.0], 45.0, 1.0, 512, 512);
    let lscale = out.light_scale(3);
    out.light([3.0, -spread, 3.0, lscale]);
    out.light([-4.0, -spread, 1.0, lscale]);
    out.light([2.0, -spread, -4.0, lscale]);

    out.color([1.0, 1.0, 1.0], 0.0, 1.0, 0.0, 0.0, 0.0, 0.0, 0.0);
    // Just spans the 45° view, plus 1%.
    let wall_y = spread * f64::from(size + 1);
    let half_width = 1.01 * (wall_y - from[1]) * (PI / 8.0).tan();
    out.polygon(&[
        [half_width + from[0], wall_y, half_width + from[2]],
        [-half_width + from[0], wall_y, half_width + from[2]],
        [-half_width + from[0], wall_y, -half_width + from[2]],
        [half_width + from[0], wall_y, -half_width + from[2]],
    ]);

    let ring_colors: [Vec3; 6] =
        [[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0], [0.0, 1.0, 1.0], [1.0, 0.0, 1.0], [1.0, 1.0, 0.0]];
    let joints = ring_joints();
    for depth in 0..size as i32 {
        let y = spread * f64::from(depth + 1);
        for z in 0..=depth {
            let z = f64::from(2 * z - depth);
            for x in 0..=depth {
                let offset = [f64::from(2 * x - depth), y, z];
                for (ring, color) in joints.chunks_exact(5).zip(&ring_colors) {
                    out.color(*color, 0.0, 0.5, 0.2, 0.3, 37.0, 0.0, 0.0);
                    for (i, joint) in ring.iter().enumerate() {
                        let previous = ring[(i + 4) % 5];
                        let base = [joint[0] + offset[0], joint[1] + offset[1], joint[2] + offset[2], TUBE_RADIUS];
                        let apex =
                            [previous[0] + offset[0], previous[1] + offset[1], previous[2] + offset[2], TUBE_RADIUS];
                        out.cylcone(base, apex);
                        out.sphere(base);
                    }
                }
            }
        }
    }
}

/// The 30 joints, five per ring, of an object scaled to fit the unit sphere:
/// one pentagon in the XY plane, and five copies tipped about X by the angle
/// between adjacent faces' normals of a dodecahedron, then turned a tenth plus
/// n fifths of a turn about Z.
fn ring_joints() -> [Vec3; 30] {
    let scale = 1.0 / (1.0 + TUBE_RADIUS);
    let mut joints = [[0.0; 3]; 30];
    for (i, joint) in joints[..5].iter_mut().enumerate() {
        let angle = i as f64 * 2.0 * PI / 5.0;
        *joint = [scale * angle.cos(), scale * angle.sin(), 0.0];
    }
    let tip = vecmath::rotate(Axis::X, 2.0 * ((PI / 3.0).cos() / (PI / 5.0).sin()).acos());
    for pentagon in 1..6 {
        let turn = vecmath::rotate(Axis::Z, PI * (2.0 * (pentagon - 1) as f64 + 1.0) / 5.0);
        for i in 0..5 {
            joints[5 * pentagon + i] = vecmath::transform_point(vecmath::transform_point(joints[i], &tip), &turn);
        }
    }
    joints
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
        for size in 1..=3usize {
            // Layer d (1..=size) holds d² objects of 30 joints: 5·size·(size+1)·(2·size+1) of each.
            let joints = 5 * size * (size + 1) * (2 * size + 1);
            let want = Counts { spheres: joints, cones: joints, polygons: 1, lights: 3, ..Counts::default() };
            assert_eq!(Counts::of(&scene(size as u32)), want, "size {size}");
        }
    }

    #[test]
    fn deterministic() {
        assert_eq!(scene(2), scene(2));
    }
}
