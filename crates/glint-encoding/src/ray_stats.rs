//! Rays traced, by kind: what the kernels' statistics buffer counts, and what
//! the CPU reference counts the same way, so the two compare as one type.

use std::ops::AddAssign;

use crate::gpu_types::{STAT_COUNT, STAT_EYE_HIT, STAT_EYE_MISS, STAT_REFLECT, STAT_REFRACT, STAT_SHADOW};

#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub struct RayStats {
    /// Eye rays (depth 1) that hit something.
    pub eye_hit: u64,
    /// Eye rays that hit nothing.
    pub eye_miss: u64,
    /// Shadow rays actually cast.
    pub shadow: u64,
    /// Reflected rays traced.
    pub reflect: u64,
    /// Refracted rays traced.
    pub refract: u64,
}

impl RayStats {
    pub fn total(&self) -> u64 {
        self.eye_hit + self.eye_miss + self.shadow + self.reflect + self.refract
    }

    /// The counts of a statistics buffer read back: slots of `STAT_COUNT`
    /// counters, one a kind, summed over the slots.
    pub fn from_slots(counts: &[u32]) -> RayStats {
        let mut stats = RayStats::default();
        for slot in counts.chunks_exact(STAT_COUNT as usize) {
            let count = |kind: u32| u64::from(slot[kind as usize]);
            stats += RayStats {
                eye_hit: count(STAT_EYE_HIT),
                eye_miss: count(STAT_EYE_MISS),
                shadow: count(STAT_SHADOW),
                reflect: count(STAT_REFLECT),
                refract: count(STAT_REFRACT),
            };
        }
        stats
    }
}

impl AddAssign for RayStats {
    fn add_assign(&mut self, o: RayStats) {
        self.eye_hit += o.eye_hit;
        self.eye_miss += o.eye_miss;
        self.shadow += o.shadow;
        self.reflect += o.reflect;
        self.refract += o.refract;
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_slots_of_a_buffer_sum_by_kind() {
        let mut counts = vec![0u32; 2 * STAT_COUNT as usize];
        for (slot, base) in [(0usize, 1u32), (1, 10)] {
            for (kind, n) in [(STAT_EYE_HIT, 1), (STAT_EYE_MISS, 2), (STAT_SHADOW, 3), (STAT_REFLECT, 4), (STAT_REFRACT, 5)] {
                counts[slot * STAT_COUNT as usize + kind as usize] = base * n;
            }
        }
        let stats = RayStats::from_slots(&counts);
        assert_eq!(stats, RayStats { eye_hit: 11, eye_miss: 22, shadow: 33, reflect: 44, refract: 55 });
        assert_eq!(stats.total(), 165);
        let mut twice = stats;
        twice += stats;
        assert_eq!(twice, RayStats { eye_hit: 22, eye_miss: 44, shadow: 66, reflect: 88, refract: 110 });
    }
}
