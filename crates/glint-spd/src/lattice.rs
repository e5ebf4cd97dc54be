//! SPD's `lattice` database (`lattice.c`, by Antonio Costa): a cubic lattice
//! in the unit cube, shiny spheres at the (size + 1)³ grid points joined to
//! their neighbours by matte red, green and blue cylinders along x, y and z.
//! Six lights, and a material statement before every object.

use crate::Output;
use crate::vecmath::Vec3;

/// Size 80 prints 531 441 spheres and 1.6 million cylinders (188 MB of text); size 81
/// would print 222 MB, as its coordinates take more digits.
pub const MAX_SIZE: u32 = 80;

/// Sphere and cylinder radii as fractions of the grid spacing.
const SPHERE_RADIUS: f64 = 1.0 / 4.0;
const CYLINDER_RADIUS: f64 = 1.0 / 16.0;

/// One unit out from the middle of each face of the unit cube.
const LIGHTS: [Vec3; 6] =
    [[2.0, 0.5, 0.5], [-1.0, 0.5, 0.5], [0.5, 2.0, 0.5], [0.5, -1.0, 0.5], [0.5, 0.5, 2.0], [0.5, 0.5, -1.0]];

pub fn generate(size: u32, out: &mut dyn Output) {
    let n = f64::from(size);
    let spacing = 1.0 / n;
    let sphere_radius = SPHERE_RADIUS / n;
    let cylinder_radius = CYLINDER_RADIUS / n;
    // How far from a grid point its cylinders start: inside the sphere.
    let inset = (sphere_radius * (1.0 - (CYLINDER_RADIUS / SPHERE_RADIUS).sqrt())) * 0.99;

    out.background([0.078, 0.361, 0.753]);
    let eye_x = (f64::from(size >> 1) + 0.5) * spacing;
    let from = [eye_x, 1.0, 1.0 - 1.0 / f64::from(size << 1)];
    let at = [eye_x, -1.0, -1.0 - 1.0 / f64::from(size << 1)];
    out.viewpoint(from, at, [0.2, 1.0, 0.0], 60.0, 0.0, 512, 512);
    for [x, y, z] in LIGHTS {
        out.light([x, y, z, 1.0 / 6.0f64.sqrt()]);
    }

    let axis_colors: [Vec3; 3] = [[0.9, 0.1, 0.1], [0.1, 0.9, 0.1], [0.1, 0.1, 0.9]];
    for x in 0..=size {
        for y in 0..=size {
            for z in 0..=size {
                let grid = [x, y, z];
                let center = grid.map(|i| f64::from(i) / n);
                out.color([0.9, 0.9, 0.9], 0.0, 0.5, 0.5, 0.5, 37.0, 0.0, 0.0);
                out.sphere([center[0], center[1], center[2], sphere_radius]);
                for axis in 0..3 {
                    if grid[axis] == size {
                        continue;
                    }
                    out.color(axis_colors[axis], 0.1, 0.99, 0.0, 0.0, 0.0, 0.0, 0.0);
                    let mut base = [center[0], center[1], center[2], cylinder_radius];
                    let mut apex = base;
                    base[axis] = center[axis] + inset;
                    apex[axis] = center[axis] + spacing - inset;
                    out.cylcone(base, apex);
                }
            }
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
        for size in 1..=3usize {
            // (size+1)³ grid points; along each axis size·(size+1)² edges join them.
            let spheres = (size + 1).pow(3);
            let cones = 3 * size * (size + 1).pow(2);
            let want = Counts { spheres, cones, lights: 6, ..Counts::default() };
            assert_eq!(Counts::of(&scene(size as u32)), want, "size {size}");
        }
    }

    #[test]
    fn deterministic() {
        assert_eq!(scene(3), scene(3));
    }
}
