//! The resolve kernel against its CPU twin (`glint_gpu::display`): random
//! accumulated samples, every view and tone map, exposure and scale; the GPU's
//! linear and display values must be the twin's.

mod support;

use glint_encoding::gpu_types::{View, MISS};
use glint_gpu::shaders::{Kernel, ShaderSource};
use glint_gpu::{display, Acceleration, DeviceProfile, RenderOptions, Renderer, SceneBuffers, ToneMap};

/// Samples covering what the kernels write: radiance sums of several samples,
/// zeros, unit normals, depths and misses, ids and −1, node counts, NaN.
fn samples(count: usize) -> Vec<[f32; 4]> {
    let mut state = 0x2545_F491_4F6C_DD1Du64;
    let mut unit = move || {
        state ^= state << 13;
        state ^= state >> 7;
        state ^= state << 17;
        (state >> 40) as f32 / (1u64 << 24) as f32
    };
    (0..count)
        .map(|i| {
            let n = [1.0, 4.0, 16.0][i % 3];
            match i % 8 {
                0 => [0.0, 0.0, 0.0, n],
                1 => [MISS, MISS, MISS, 1.0],
                2 => [-1.0, -1.0, -1.0, 1.0],
                3 => [f32::NAN, 0.5, 1.0, 1.0],
                4 => {
                    let v = [unit() - 0.5, unit() - 0.5, unit() - 0.5];
                    let len = v.iter().map(|c| c * c).sum::<f32>().sqrt().max(1e-3);
                    [v[0] / len, v[1] / len, v[2] / len, 1.0]
                }
                5 => [(unit() * 1000.0).floor(), 0.0, 0.0, 1.0],
                _ => [unit() * 3.0 * n, unit() * n, unit() * 0.01 * n, n],
            }
        })
        .collect()
}

#[test]
fn the_resolve_kernel_matches_its_cpu_twin() {
    let renderer = support::renderer();
    let (width, height) = (37, 11);
    let input = samples((width * height) as usize);
    for view in View::ALL {
        for (tone_map, exposure, view_scale) in [(ToneMap::Clamp, 1.0, 50.0), (ToneMap::Reinhard, 2.5, 7.0), (ToneMap::Aces, 0.3, 300.0)] {
            let options = RenderOptions { view, tone_map, exposure, view_scale, ..RenderOptions::default() };
            let image = renderer.resolve_samples(&input, width, height, &options).unwrap();
            for (i, sample) in input.iter().enumerate() {
                // The kernels never write NaN into a data view, nor anything but
                // whole numbers or −1 into the id view; WGSL leaves clamp() and
                // u32() of such values to the implementation.
                let an_id = sample[0] == -1.0 || (sample[0] >= 0.0 && sample[0] < 16_777_216.0 && sample[0].fract() == 0.0);
                if (view.is_data() && sample[0].is_nan()) || (view == View::Id && !an_id) {
                    continue;
                }
                let (want_linear, want_display) = (display::linear_value(*sample, &options), display::display_value(*sample, &options));
                let (linear, shown) = (image.linear[i], image.display[i]);
                for c in 0..3 {
                    let same = |a: f32, b: f32, tol: f32| a == b || (a.is_nan() && b.is_nan()) || (a - b).abs() <= tol * b.abs().max(1.0);
                    assert!(same(linear[c], want_linear[c], 1e-6), "{view:?} {tone_map:?}, sample {sample:?}: linear {linear:?}, twin {want_linear:?}");
                    assert!(same(shown[c], want_display[c], 2e-5), "{view:?} {tone_map:?}, sample {sample:?}: display {shown:?}, twin {want_display:?}");
                }
            }
        }
    }
}

/// One exposure rule for every output format: light views are scaled in the
/// linear values (EXR, PFM) as in the display values (PNG); data views never.
#[test]
fn exposure_scales_light_views_in_every_output_and_data_views_in_none() {
    let renderer = support::renderer();
    let input = vec![[0.2, 0.1, 0.05, 1.0]];
    for view in View::ALL {
        let at = |exposure| renderer.resolve_samples(&input, 1, 1, &RenderOptions { view, exposure, ..RenderOptions::default() }).unwrap();
        let (one, two) = (at(1.0), at(2.0));
        let expected = if view.is_data() { one.linear[0][0] } else { 2.0 * one.linear[0][0] };
        assert!((two.linear[0][0] - expected).abs() < 1e-6, "{view:?}: {} at exposure 2, {} at 1", two.linear[0][0], one.linear[0][0]);
    }
}

/// On a CPU adapter (lavapipe, where the tests run) a render is resolved by
/// the kernel's twin on the host, so it never compiles the resolve kernel.
#[test]
fn a_render_on_a_cpu_adapter_resolves_on_the_host_without_compiling_the_resolve_kernel() {
    let gpu = support::gpu();
    assert_eq!(gpu.info().device_type, wgpu::DeviceType::Cpu, "the GPU tests run on lavapipe");
    let renderer = Renderer::new(gpu.device.clone(), gpu.queue.clone(), &ShaderSource::Embedded).unwrap();
    assert!(renderer.resolves_on_host());
    let scene = support::parse(
        "[image]\nwidth = 16\nheight = 8\nbackground = [0.25, 0.5, 0]\n[camera]\neye = [0, 0, 5]\nlook_at = [0, 0, 0]\nfov = 30\n\
[ambient]\nintensity = 1\n[material.white]\ncolor = 1\nka = 1\n[[object]]\ntype = \"sphere\"\ncenter = [0, 0, 0]\nradius = 1\nmaterial = \"white\"\n",
    );
    let prepared = renderer.prepare(&scene, 16, 8, Acceleration::Bvh).unwrap();
    let options = RenderOptions { exposure: 0.5, ..RenderOptions::default() };
    let (image, _) = renderer.render(&prepared.buffers, &options, &mut |_, _| {}).unwrap();
    for ((x, y), linear) in [((8, 4), [0.5; 3]), ((0, 0), [0.125, 0.25, 0.0])] {
        let want = display::display_value([linear[0] / 0.5, linear[1] / 0.5, linear[2] / 0.5, 1.0], &options);
        let (got_linear, got_display) = (image.linear_at(x, y), image.display[(y * 16 + x) as usize]);
        assert_eq!(got_linear[..3], linear, "pixel ({x}, {y})");
        assert_eq!(got_display[..3], want, "pixel ({x}, {y})");
    }
    let kernels = renderer.kernels_created();
    assert!(kernels.contains(&Kernel::Trace) && !kernels.contains(&Kernel::Resolve), "{kernels:?}");
}

/// Depth and the heat map store one number a pixel and leave the rest of the
/// accumulation as it was: after a shaded render of several samples in the
/// same buffers, they must read as they do in fresh ones, whether resolved on
/// the host or by the kernel.
#[test]
fn a_view_of_one_number_reads_the_same_over_another_views_samples() {
    let gpu = support::gpu();
    let scene = support::parse(
        "[image]\nwidth = 12\nheight = 10\nbackground = [0.25, 0.5, 0]\n[camera]\neye = [0, 0, 5]\nlook_at = [0, 0, 0]\nfov = 30\n\
[ambient]\nintensity = 1\n[material.white]\ncolor = 1\nka = 1\n[[object]]\ntype = \"sphere\"\ncenter = [0, 0, 0]\nradius = 1\nmaterial = \"white\"\n\
[[object]]\ntype = \"sphere\"\ncenter = [1.2, 0.8, -1]\nradius = 0.4\nmaterial = \"white\"\n",
    );
    let on_device = DeviceProfile { resolves_on_host: false, ..*support::renderer().profile() };
    let renderers = [support::renderer(), &Renderer::with_profile(gpu.device.clone(), gpu.queue.clone(), &ShaderSource::Embedded, on_device).unwrap()];
    for renderer in renderers {
        let render = |buffers: &SceneBuffers, view| {
            let options = RenderOptions { view, spp: 3, view_scale: 10.0, ..RenderOptions::default() };
            renderer.render(buffers, &options, &mut |_, _| {}).unwrap().0
        };
        for view in View::ALL.into_iter().filter(|view| view.is_one_number()) {
            let fresh = render(&renderer.prepare(&scene, 12, 10, Acceleration::Bvh).unwrap().buffers, view);
            let used = renderer.prepare(&scene, 12, 10, Acceleration::Bvh).unwrap().buffers;
            render(&used, View::Shaded);
            let over = render(&used, view);
            assert!(fresh.linear.iter().any(|p| p[0] != fresh.linear[0][0]), "{view:?} shows the spheres");
            assert_eq!(over.linear, fresh.linear, "{view:?}, resolved on the host: {}", renderer.resolves_on_host());
            assert_eq!(over.display, fresh.display, "{view:?}");
        }
    }
}
