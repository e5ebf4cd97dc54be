//! Differential tests: random scenes of every primitive kind rendered by the GPU
//! kernels and by the independent CPU reference tracer (f64), which share the
//! scene model but no shading code. Every fourth scene is rendered again
//! under the plain profile, which must give the same bits (`support`): each
//! plain scene's kernels compile anew, and on lavapipe they compile slowly.
//! Every fifth scene lights its back faces with unturned normals, the
//! student's bug grading's diagnosis renders (`turn_normals` off).

mod support;

use std::io::Write;
use glint_encoding::gpu_types::View;
use glint_gpu::{Acceleration, RenderOptions};

const SEEDS: u64 = 20;
/// The scenes the plain profile renders again: seeds 0, 4, 8, ...
const PLAIN_EVERY: u64 = 4;
/// The scenes rendered with unturned normals: seeds 2, 7, 12, ...
const UNTURNED_EVERY: u64 = 5;
/// Colour tolerance per channel (linear radiance), relative above 1.
const TOLERANCE: f64 = 2.0 / 255.0;
/// Pixels whose ray trees change within this many pixels of the centre are on
/// an edge (silhouette, shadow boundary, ...), where f32 and f64 may disagree.
const EDGE_DELTA_PX: f64 = 0.05;

#[test]
fn gpu_agrees_with_the_cpu_reference_on_random_scenes() {
    let mut compared = 0;
    let mut summary = Vec::new();
    for seed in 0..SEEDS {
        let mut scene = glint_reference::random_scene(seed);
        scene.render.turn_normals = seed % UNTURNED_EVERY != 2;
        let (w, h) = (scene.width, scene.height);
        let reference = glint_reference::render(&scene, w, h);
        let stable = glint_reference::stability_mask(&scene, w, h, EDGE_DELTA_PX);
        let render = if seed % PLAIN_EVERY == 0 { support::render_options } else { support::render_device_profile };
        let (gpu, gpu_stats) = render(&scene, Acceleration::Bvh, RenderOptions::default());
        let (depth, _) = render(&scene, Acceleration::Bvh, RenderOptions { view: View::Depth, ..Default::default() });
        let depth = depth.with_misses_at_infinity();

        let mut off = 0;
        for j in 0..h {
            for i in 0..w {
                let k = reference.index(i, j);
                let expected = reference.rgb[k];
                let got = gpu.linear_at(i, j);
                let close = (0..3).all(|c| {
                    let e = expected[c];
                    (f64::from(got[c]) - e).abs() <= TOLERANCE * e.abs().max(1.0)
                });
                if !close {
                    off += 1;
                    assert!(
                        !stable[k],
                        "seed {seed}: pixel ({i}, {j}) is no edge, yet GPU {got:?} vs CPU {expected:?}"
                    );
                }
                let (d_gpu, d_ref) = (f64::from(depth.linear_at(i, j)[0]), reference.depth[k]);
                if d_ref.is_infinite() || d_gpu.is_infinite() {
                    assert!(
                        !stable[k] || d_gpu == d_ref,
                        "seed {seed}: depth at ({i}, {j}): GPU {d_gpu} vs CPU {d_ref}"
                    );
                } else if stable[k] {
                    assert!(((d_gpu - d_ref) / d_ref).abs() < 1e-4, "seed {seed}: depth at ({i}, {j}): GPU {d_gpu} vs CPU {d_ref}");
                }
            }
        }
        let pixels = (w * h) as usize;
        assert!(off * 200 <= pixels, "seed {seed}: {off} of {pixels} pixels differ (> 0.5%)");
        assert_eq!(gpu_stats.eye_hit, reference.stats.eye_hit, "seed {seed}: eye hits");
        assert_eq!(gpu_stats.eye_miss, reference.stats.eye_miss, "seed {seed}: eye misses");
        compared += pixels;
        summary.push(off);
    }
    // Written past the test harness's capture, so every run shows the summary.
    let _ = writeln!(std::io::stderr(), "differential: {SEEDS} random scenes, {compared} pixels compared, edge pixels off per scene: {summary:?}");
}
