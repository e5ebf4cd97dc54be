//! SPD's `gears` database (`gears.c`): a cube of SIZE³ meshing gears, each a
//! concave 144-gon top and bottom joined by 144 rectangles, over a reflective
//! square; some gears are glassy. Five lights.

use std::f64::consts::PI;

use crate::Output;
use crate::vecmath::Vec3;

/// Output grows as SIZE³ (about 21 kB a gear): size 20 is 8000 gears, 173 MB.
pub const MAX_SIZE: u32 = 20;

/// Teeth per gear (a multiple of 4).
const TEETH: usize = 36;
/// The outer radius is a little short of the full one so that meshing gears
/// never share a surface.
const OUTER_EDGE_RATIO: f64 = 0.995;
const INNER_EDGE_RATIO: f64 = 0.9;
const EDGE_DIFF: f64 = 1.0 - INNER_EDGE_RATIO;
/// Thickness of a gear over its width.
const DEPTH_RATIO: f64 = 0.1;

pub fn generate(size: u32, out: &mut dyn Output) {
    let sf = f64::from(size);
    out.background([0.078, 0.361, 0.753]);
    out.viewpoint([-1.1, -2.1, 2.6], [0.0, 0.0, 0.0], [0.0, 0.0, 1.0], 45.0, 1.0, 512, 512);
    for light in [[2.0, 4.0, 4.0], [-2.0, 4.0, 3.0], [2.0, -2.5, 2.5], [-1.0, -4.0, 2.0], [-1.111, -2.121, 2.626]] {
        out.light([light[0], light[1], light[2], out.light_scale(5)]);
    }

    out.color([1.0, 0.85, 0.7], 0.0, 0.3, 0.6, 0.3, 37.0, 0.0, 0.0);
    out.polygon(&[[2.0, 2.0, 0.0], [-2.0, 2.0, 0.0], [-2.0, -2.0, 0.0], [2.0, -2.0, 0.0]]);

    let outer_radius = 1.0 / (sf - f64::from(size - 1) * EDGE_DIFF / 2.0);
    let zero_pt = [-1.0 + outer_radius, -1.0 + outer_radius, 1.0];
    let offset = [outer_radius * (2.0 - EDGE_DIFF), outer_radius * (2.0 - EDGE_DIFF), -1.0 / sf];
    let thickness = if DEPTH_RATIO < 1.0 / (2.0 * sf) { DEPTH_RATIO } else { 1.0 / (2.0 * sf) };
    for iz in 0..size {
        for iy in 0..size {
            for ix in 0..size {
                let center = [
                    zero_pt[0] + f64::from(ix) * offset[0],
                    zero_pt[1] + f64::from(iy) * offset[1],
                    zero_pt[2] + f64::from(iz) * offset[2],
                ];
                let color = gear_color(ix, iy, iz);
                if (ix * 4 + iy * 2 + iz) % 5 == 0 {
                    out.color(color, 0.0, 0.2, 0.0, 0.0, 0.0, 0.8, 1.1);
                } else {
                    out.color(color, 0.0, 1.0, 0.0, 0.0, 0.0, 0.0, 0.0);
                }
                // Neighbours turn half a tooth apart so that their teeth mesh.
                let angle = PI * f64::from((ix + iy + iz) % 2) / TEETH as f64;
                let gear = Gear {
                    center,
                    offset_angle: angle,
                    outer_radius: OUTER_EDGE_RATIO * outer_radius,
                    inner_radius: (1.0 - EDGE_DIFF) * outer_radius,
                    thickness,
                };
                gear.output(out);
            }
        }
    }
}

/// A pseudo-random colour whose brightest channel is 1.
fn gear_color(ix: u32, iy: u32, iz: u32) -> Vec3 {
    let fraction = |a: f64| a - f64::from(a as i32);
    let mut color = [
        0.01 + fraction(f64::from(ix * 3 + iy * 2 + iz + 1) * 5.0 / 7.0),
        0.01 + fraction(f64::from(iy * 3 + iz * 2 + ix + 1) * 3.0 / 7.0),
        0.01 + fraction(f64::from(iz * 3 + ix * 2 + iy + 1) * 2.0 / 7.0),
    ];
    let max = |a: f64, b: f64| if a > b { a } else { b };
    let scale = max(max(color[0], color[1]), color[2]);
    for c in &mut color {
        *c /= scale;
    }
    color
}

struct Gear {
    center: Vec3,
    offset_angle: f64,
    outer_radius: f64,
    inner_radius: f64,
    thickness: f64,
}

impl Gear {
    /// Top face, the sides of the teeth, then the bottom face (wound the other way).
    fn output(&self, out: &mut dyn Output) {
        let top = self.face(0.0, 1.0);
        out.polygon(&top);
        let below = |p: Vec3| [p[0], p[1], p[2] - self.thickness];
        for (i, &a) in top.iter().enumerate() {
            let b = top[(i + 1) % top.len()];
            out.polygon(&[a, below(a), below(b), b]);
        }
        out.polygon(&self.face(-self.thickness, -1.0));
    }

    /// The 4·TEETH outline at height `z` (relative to the centre), going round
    /// counterclockwise (`turn` 1) or clockwise (-1). Multiplying by ±1 and
    /// adding the negation are exact, so this matches SPD's `+`/`-` forms bit for bit.
    fn face(&self, z: f64, turn: f64) -> Vec<Vec3> {
        let tooth_angle = turn * (2.0 * PI / TEETH as f64);
        let outer_pt = [self.outer_radius, 0.0, z];
        let inner_pt = [self.inner_radius, 0.0, z];
        let mut points = Vec::with_capacity(4 * TEETH);
        for tooth in 0..TEETH {
            let gear_angle = self.offset_angle + turn * (2.0 * PI * tooth as f64 / TEETH as f64);
            // The tooth's two tip corners, then the two corners of the gap after it.
            for (pt, at) in [(outer_pt, -0.19), (outer_pt, 0.19), (inner_pt, 0.3), (inner_pt, 0.7)] {
                let p = rotate_z(pt, gear_angle + at * tooth_angle);
                points.push([p[0] + self.center[0], p[1] + self.center[1], p[2] + self.center[2]]);
            }
        }
        points
    }
}

/// `lib_transform_vector` by `lib_create_rotate_matrix(Z_AXIS, angle)`, every
/// product and sum as SPD does them (so the zeros keep their signs).
fn rotate_z(v: Vec3, angle: f64) -> Vec3 {
    let (sine, cosine) = (angle.sin(), angle.cos());
    [
        v[0] * cosine + v[1] * -sine + v[2] * 0.0,
        v[0] * sine + v[1] * cosine + v[2] * 0.0,
        v[0] * 0.0 + v[1] * 0.0 + v[2] * 1.0,
    ]
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
            let gears = (size * size * size) as usize;
            // The ground, then per gear two faces and one rectangle per face edge.
            assert_eq!(count(&text, "p"), 1 + gears * (2 + 4 * TEETH), "size {size}");
            assert_eq!(count(&text, "f"), 1 + gears, "size {size}");
            assert_eq!(count(&text, "l"), 5);
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
