//! A device lost during a render is reported as an error, not a hang.

mod support;

use glint_gpu::shaders::ShaderSource;
use glint_gpu::{Acceleration, Gpu, RenderOptions, Renderer};

#[test]
fn a_lost_device_is_reported_not_hung() {
    // A device of its own: destroying the shared test device would break the
    // other tests of this binary.
    let gpu = Gpu::new().unwrap_or_else(|e| panic!("GPU tests need an adapter: {e}"));
    let renderer = Renderer::new(gpu.device.clone(), gpu.queue.clone(), &ShaderSource::Embedded).unwrap();
    let scene = support::parse(
        "[image]\nwidth = 64\nheight = 64\n[camera]\neye = [0, 0, 5]\nlook_at = [0, 0, 0]\nfov = 40\n[[object]]\ntype = \"sphere\"\ncenter = [0, 0, 0]\nradius = 1\n",
    );
    let prepared = renderer.prepare(&scene, 64, 64, Acceleration::Bvh).unwrap();
    gpu.device.destroy();
    let err = renderer
        .render(&prepared.buffers, &RenderOptions::default(), &mut |_, _| {})
        .err()
        .expect("rendering on a destroyed device must fail");
    assert!(err.to_string().to_lowercase().contains("lost"), "{err}");
}
