//! The depth view's scale: the distance from the eye to the farthest corner
//! of the scene's primitives' bounds, measured again for every view. A view
//! of a million primitives would measure two million corners; the corners
//! are kept in runs with a box around each, and a run whose box is nowhere
//! farther than the farthest corner found so far is skipped. The result is
//! the same float as measuring every corner.

use glam::Vec3;

/// Corners to a run: a run's box is one distance to measure instead of its
/// corners', and few runs are measured whole.
const RUN: usize = 64;

pub(crate) struct Corners {
    /// Each box's lowest and highest corner, in the order of the boxes.
    points: Vec<Vec3>,
    /// The box around each run of RUN points.
    runs: Vec<(Vec3, Vec3)>,
}

impl Corners {
    /// The corners of `bounds`, boxes given by their lowest and highest corner.
    pub(crate) fn new(bounds: &[(Vec3, Vec3)]) -> Corners {
        let points: Vec<Vec3> = bounds.iter().flat_map(|&(lo, hi)| [lo, hi]).collect();
        let runs = points.chunks(RUN).map(|run| run.iter().fold((run[0], run[0]), |(lo, hi), &p| (lo.min(p), hi.max(p)))).collect();
        Corners { points, runs }
    }

    /// The distance from `eye` to the farthest corner (f32::MIN_POSITIVE
    /// when there is none, or all are at the eye).
    ///
    /// A run's far corner is, per axis, whichever of its box's planes is
    /// farther from the eye: no point of the run is farther from the eye on
    /// any axis, and since rounding is monotonic, no point's distance
    /// computed the same way exceeds the far corner's. So skipping runs whose
    /// far corner is no farther than the best distance so far leaves the
    /// maximum exactly as it is.
    pub(crate) fn farthest(&self, eye: Vec3) -> f32 {
        let reach: Vec<f32> = self.runs.iter().map(|&(lo, hi)| far_corner(lo, hi, eye).distance(eye)).collect();
        let measure = |i: usize, best: f32| self.points[i * RUN..((i + 1) * RUN).min(self.points.len())].iter().map(|p| p.distance(eye)).fold(best, f32::max);
        // The run that reaches farthest first, so that few others pass the test.
        let first = (0..reach.len()).max_by(|&a, &b| reach[a].total_cmp(&reach[b]));
        let mut best = first.map_or(0.0, |i| measure(i, 0.0));
        for (i, &r) in reach.iter().enumerate() {
            if r > best {
                best = measure(i, best);
            }
        }
        best.max(f32::MIN_POSITIVE)
    }
}

/// The corner of box [lo, hi] farthest from `eye` on every axis.
fn far_corner(lo: Vec3, hi: Vec3, eye: Vec3) -> Vec3 {
    Vec3::select((eye - lo).abs().cmpge((hi - eye).abs()), lo, hi)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// What `farthest` must equal: every corner measured.
    fn every_corner(bounds: &[(Vec3, Vec3)], eye: Vec3) -> f32 {
        bounds.iter().flat_map(|&(lo, hi)| [lo, hi]).map(|c| c.distance(eye)).fold(0.0f32, f32::max).max(f32::MIN_POSITIVE)
    }

    #[test]
    fn the_farthest_corner_is_the_one_every_corner_gives_bit_for_bit() {
        // A small generator, so that the cases are the same on every run.
        let mut state = 0x2545_f491_4f6c_dd1du64;
        let mut next = move || {
            state ^= state << 13;
            state ^= state >> 7;
            state ^= state << 17;
            (state >> 40) as f32 / (1u64 << 24) as f32
        };
        for case in 0..200 {
            let count = [0, 1, 5, 63, 64, 65, 1000, 5000][case % 8];
            let scale = [1e-3, 1.0, 1e4][case % 3];
            let bounds: Vec<(Vec3, Vec3)> = (0..count)
                .map(|_| {
                    let lo = Vec3::new(next(), next(), next()) * scale - scale / 2.0;
                    (lo, lo + Vec3::new(next(), next(), next()) * scale / 10.0)
                })
                .collect();
            let corners = Corners::new(&bounds);
            for _ in 0..5 {
                let eye = (Vec3::new(next(), next(), next()) * 3.0 - 1.5) * scale;
                assert_eq!(corners.farthest(eye).to_bits(), every_corner(&bounds, eye).to_bits(), "case {case}, {count} boxes, eye {eye}");
            }
        }
        let at_eye = [(Vec3::ONE, Vec3::ONE)];
        assert_eq!(Corners::new(&at_eye).farthest(Vec3::ONE), f32::MIN_POSITIVE);
        assert_eq!(Corners::new(&[]).farthest(Vec3::ZERO), f32::MIN_POSITIVE);
    }
}
