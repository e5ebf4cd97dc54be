//! SPD's `shells` database (`shells.c`): a sea shell grown by Pickover's method
//! (IEEE CG&A, November 1989), a logarithmic spiral of ever larger overlapping
//! spheres under one light. Meant as a pathological case: lots of overlap,
//! many tiny spheres.

use crate::Output;
use std::f64::consts::PI;

/// Size 14 prints 2.9 million spheres (120 MB of text); size 15 would print twice as much.
pub const MAX_SIZE: u32 = 14;

/// shells.c's default shape parameters (its `-g`, `-b` and `-e` options and
/// `k`); its `-a` (alpha) defaults to 0, which selects z = beta·r.
const GAMMA: f64 = 1.0;
const BETA: f64 = -2.0;
const EXPONENT: f64 = 0.15;
const RELATIVE_SIZE: f64 = 1.0;

pub fn generate(size: u32, out: &mut dyn Output) {
    out.background([0.078, 0.361, 0.753]);
    out.viewpoint([-6.0, -60.0, 35.0], [0.0, 8.0, -15.0], [0.0, 0.0, 1.0], 45.0, 0.5, 512, 512);
    out.light([-100.0, -100.0, 100.0, 1.0]);
    out.color([1.0, 0.8, 0.4], 0.0, 0.8, 0.2, 0.5, 10.0, 0.0, 1.0);

    // Nine turns of the spiral, angle -12π to 6π; the first six stay inside the unit radius.
    let steps = 180 * (1i64 << size);
    for i in -steps * 2 / 3..=steps / 3 {
        let angle = 3.0 * 6.0 * PI * i as f64 / steps as f64;
        let r = RELATIVE_SIZE * (EXPONENT * angle).exp();
        out.sphere([r * angle.sin(), r * angle.cos(), BETA * r, r / GAMMA]);
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
            // i runs from -2/3 to 1/3 of steps = 180·2^size: 180·2^size + 1 spheres.
            let want = Counts { spheres: 180 * (1 << size) + 1, lights: 1, ..Counts::default() };
            assert_eq!(Counts::of(&scene(size)), want, "size {size}");
        }
    }

    #[test]
    fn deterministic() {
        assert_eq!(scene(2), scene(2));
    }
}
