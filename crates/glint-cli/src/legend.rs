//! One line per debug view saying what its pixels mean: the quantity, its
//! units and the range the picture maps to colour, with the range found in
//! this image. README.md's "Debug views" table gives the same formulas.

use std::collections::BTreeSet;

use glint_encoding::gpu_types::View;
use glint_gpu::{Channels, Image};

/// What a legend says about the image's values, gathered tile by tile as
/// the image is rendered, so no image need be kept for it.
#[derive(Debug)]
pub struct Summary {
    view: View,
    /// The first linear channel where the eye ray hit something (for depth,
    /// where it is finite): how many, least, greatest and sum.
    hits: u64,
    min: f32,
    max: f32,
    sum: f64,
    /// The largest linear channel of any pixel.
    brightest: f32,
    /// The object ids seen.
    ids: BTreeSet<i64>,
}

impl Summary {
    pub fn new(view: View) -> Self {
        Self { view, hits: 0, min: f32::INFINITY, max: f32::NEG_INFINITY, sum: 0.0, brightest: 0.0, ids: BTreeSet::new() }
    }

    /// Adds the pixels of a tile (or a whole image), as resolved for the view.
    pub fn add(&mut self, tile: &Image) {
        let firsts = tile.linear.iter().map(|p| p[0]);
        match self.view {
            View::Depth | View::Heatmap | View::RayDepth | View::RayCount => {
                for v in firsts.filter(|&v| self.view != View::Depth || v.is_finite()) {
                    self.hits += 1;
                    self.min = self.min.min(v);
                    self.max = self.max.max(v);
                    self.sum += f64::from(v);
                }
            }
            View::Diffuse => self.brightest = tile.linear.iter().map(|p| p[0].max(p[1]).max(p[2])).fold(self.brightest, f32::max),
            View::Id => self.ids.extend(firsts.filter(|&v| v >= 0.0).map(|v| v as i64)),
            _ => {}
        }
    }

    /// (min, max, mean) of the first channel where the eye ray hit something;
    /// `None` when it hit nothing anywhere.
    fn hit_range(&self) -> Option<(f32, f32, f64)> {
        (self.hits > 0).then(|| (self.min, self.max, self.sum / self.hits as f64))
    }
}

/// A number with about three significant digits.
fn short(v: f64) -> String {
    if v != 0.0 && (v.abs() >= 1000.0 || v.abs() < 0.01) {
        return format!("{v:.3e}");
    }
    let s = format!("{v:.3}");
    s.trim_end_matches('0').trim_end_matches('.').to_string()
}

/// What the float outputs of `view` hold: one channel for the data views that
/// are one number per pixel, with its EXR channel name (documented in README.md).
pub fn channels(view: View) -> Channels {
    match view {
        View::Depth => Channels::Single("Z"),
        View::Id => Channels::Single("id"),
        View::Heatmap => Channels::Single("nodes"),
        View::RayDepth => Channels::Single("depth"),
        View::RayCount => Channels::Single("rays"),
        _ => Channels::Rgb,
    }
}

/// The legend of the image `summary` sums up, or `None` for the shaded
/// render. `scale` is the view scale the image was resolved with,
/// `bvh_nodes` and `objects` the scene's counts.
pub fn legend(summary: &Summary, scale: f32, bvh_nodes: usize, objects: usize) -> Option<String> {
    let view = summary.view;
    let tree_range = || {
        summary.hit_range().map_or(String::new(), |(min, max, mean)| {
            format!("; this image {} to {}, mean {}", short(min.into()), short(max.into()), short(mean))
        })
    };
    let nothing = "the eye rays hit nothing";
    Some(match view {
        View::Shaded => return None,
        View::Normal => "normal: the unit geometric normal N, turned towards the eye, as the colour 0.5 + 0.5·N \
(x → red, y → green, z → blue: (0.5, 1, 0.5) faces up); misses black"
            .into(),
        View::Depth => {
            let range = summary
                .hit_range()
                .map_or(nothing.into(), |(min, max, _)| format!("nearest hit {}, farthest {}", short(min.into()), short(max.into())));
            format!(
                "depth: distance t along the eye ray in scene units, white at 0 to black at {} (the farthest corner \
of the scene's bounds); misses black (+inf in .pfm/.exr); {range}",
                short(scale.into())
            )
        }
        View::Albedo => "albedo: the diffuse colour O_d of the material hit, unlit; misses black".into(),
        View::Diffuse => {
            let brightest = summary.brightest;
            let mut text = format!(
                "diffuse: direct diffuse light Σ k_d·O_d·I_l·max(0, N·L)·V/d² over the lights, d the distance to \
each light in scene units (always 1/d², whatever the scene's attenuation; d = 1 for a directional light), no \
ambient, highlights or mirrors; brightest value {}",
                short(brightest.into())
            );
            if brightest > 0.0 && brightest < 0.25 {
                let exposure = (1.0 / f64::from(brightest)).round().max(2.0);
                text.push_str(&format!(": try --exposure {exposure} to see it"));
            }
            text
        }
        View::Id => {
            format!(
                "id: object index, 0 to {} in file order ({objects} objects), one colour each; misses black (-1 in \
.pfm/.exr); {} objects seen",
                objects.saturating_sub(1),
                summary.ids.len()
            )
        }
        View::Heatmap => {
            let range = summary
                .hit_range()
                .map_or(nothing.into(), |(min, max, mean)| format!("this image {} to {}, mean {}", short(min.into()), short(max.into()), short(mean)));
            format!(
                "heatmap: BVH nodes visited by each eye ray, blue at 0 through green to red at {} (2·log2 of the \
{bvh_nodes} nodes + 8) and beyond; {range}",
                short(scale.into())
            )
        }
        View::RayDepth => format!(
            "ray-depth: the deepest level each pixel's ray tree reached (the eye ray is level 1, each reflection or refraction one more), blue at 0 through green to red at {} (the maximum depth){}",
            short(scale.into()),
            tree_range()
        ),
        View::RayCount => format!(
            "ray-count: rays each pixel traced (eye, shadow, reflected, refracted), blue at 0 through green to red at {} ((1 + lights) × maximum depth) and beyond{}",
            short(scale.into()),
            tree_range()
        ),
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The summary of `view` over an image of `values`, given in tiles of two pixels.
    fn image(view: View, values: &[f32]) -> Summary {
        let mut summary = Summary::new(view);
        for tile in values.chunks(2) {
            let linear: Vec<[f32; 4]> = tile.iter().map(|&v| [v, v, v, 1.0]).collect();
            summary.add(&Image { width: tile.len() as u32, height: 1, display: linear.clone(), linear });
        }
        summary
    }

    #[test]
    fn legends_state_the_range_and_units() {
        let depth = legend(&image(View::Depth, &[2.0, f32::INFINITY, 5.5]), 12.0, 9, 3).unwrap();
        assert!(depth.contains("scene units") && depth.contains("black at 12") && depth.contains("nearest hit 2, farthest 5.5"), "{depth}");
        let id = legend(&image(View::Id, &[-1.0, 0.0, 2.0, 2.0]), 1.0, 9, 3).unwrap();
        assert!(id.contains("0 to 2 in file order (3 objects)") && id.contains("2 objects seen"), "{id}");
        let heat = legend(&image(View::Heatmap, &[3.0, 7.0, 5.0]), 14.3, 41, 3).unwrap();
        assert!(heat.contains("red at 14.3") && heat.contains("41 nodes") && heat.contains("this image 3 to 7, mean 5"), "{heat}");
        let diffuse = legend(&image(View::Diffuse, &[0.0, 0.02, 0.01]), 1.0, 9, 3).unwrap();
        assert!(diffuse.contains("1/d²") && diffuse.contains("brightest value 0.02: try --exposure 50"), "{diffuse}");
        assert!(legend(&image(View::Shaded, &[1.0]), 1.0, 9, 3).is_none());
        for view in [View::Normal, View::Depth, View::Albedo, View::Diffuse, View::Id, View::Heatmap] {
            assert_eq!(legend(&image(view, &[0.5]), 1.0, 9, 3).unwrap().lines().count(), 1);
        }
        let nothing = legend(&image(View::Depth, &[f32::INFINITY; 3]), 12.0, 9, 3).unwrap();
        assert!(nothing.contains("the eye rays hit nothing"), "{nothing}");
    }
}
