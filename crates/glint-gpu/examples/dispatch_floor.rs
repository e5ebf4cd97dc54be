//! What a 512×512 dispatch costs before it traces anything: kernels that do
//! nothing, or only write a pixel, at one pixel and at 2×2 and 4×4 pixels an
//! invocation, timed on the adapter Glint picks (docs/performance.md, "What is
//! slow, and why"). On lavapipe every invocation and every
//! component a lane stores has a price of its own; this shows both.
//!
//!     cargo run --release -p glint-gpu --example dispatch_floor

use std::time::Instant;

const SIDE: u32 = 512;
const WARM_UP: usize = 3;
const TIMED: usize = 41;

/// (name, body of the kernel, side of the block of pixels an invocation covers)
const KERNELS: &[(&str, &str, u32)] = &[
    ("nothing", "if gid.x == 123456u { out[0] = vec4<f32>(1.0); }", 1),
    ("write vec4", "out[gid.y * SIDE + gid.x] = vec4<f32>(f32(gid.x), 0.0, 0.0, 1.0);", 1),
    ("write f32 of a vec4", "out[gid.y * SIDE + gid.x].x = f32(gid.x);", 1),
    ("eye ray, write vec4", "let d = normalize(vec3<f32>(vec2<f32>(gid.xy) / f32(SIDE) - 0.5, -1.0)); out[gid.y * SIDE + gid.x] = vec4<f32>(d, 1.0);", 1),
    ("2x2: nothing", "if gid.x == 123456u { out[0] = vec4<f32>(1.0); }", 2),
    ("2x2: write 4 vec4", "for (var k = 0u; k < 4u; k++) { out[(2u * gid.y + (k >> 1u)) * SIDE + 2u * gid.x + (k & 1u)] = vec4<f32>(f32(gid.x), 0.0, 0.0, 1.0); }", 2),
    ("4x4: nothing", "if gid.x == 123456u { out[0] = vec4<f32>(1.0); }", 4),
];

fn main() {
    let gpu = glint_gpu::Gpu::new().unwrap_or_else(|e| panic!("no adapter: {e}"));
    let (device, queue) = (&gpu.device, &gpu.queue);
    println!("{}, {SIDE}x{SIDE}, median and fastest of {TIMED} dispatches, ms", gpu.info().name);
    let out = device.create_buffer(&wgpu::BufferDescriptor {
        label: Some("pixels"),
        size: u64::from(SIDE * SIDE) * 16,
        usage: wgpu::BufferUsages::STORAGE,
        mapped_at_creation: false,
    });
    for (name, body, side) in KERNELS {
        let source = format!(
            "const SIDE: u32 = {SIDE}u;\n\
             @group(0) @binding(0) var<storage, read_write> out: array<vec4<f32>>;\n\
             @compute @workgroup_size(8, 4) fn main(@builtin(global_invocation_id) gid: vec3<u32>) {{ {body} }}"
        );
        let descriptor = wgpu::ShaderModuleDescriptor { label: Some(name), source: wgpu::ShaderSource::Wgsl(source.into()) };
        // SAFETY: every index above is inside the buffer; Glint's own kernels run unchecked too.
        let module = unsafe { device.create_shader_module_trusted(descriptor, wgpu::ShaderRuntimeChecks::unchecked()) };
        let pipeline = device.create_compute_pipeline(&wgpu::ComputePipelineDescriptor {
            label: Some(name),
            layout: None,
            module: &module,
            entry_point: Some("main"),
            compilation_options: Default::default(),
            cache: None,
        });
        let bind = device.create_bind_group(&wgpu::BindGroupDescriptor {
            label: Some(name),
            layout: &pipeline.get_bind_group_layout(0),
            entries: &[wgpu::BindGroupEntry { binding: 0, resource: out.as_entire_binding() }],
        });
        let mut times: Vec<f64> = (0..WARM_UP + TIMED)
            .map(|_| {
                let mut encoder = device.create_command_encoder(&Default::default());
                {
                    let mut pass = encoder.begin_compute_pass(&Default::default());
                    pass.set_pipeline(&pipeline);
                    pass.set_bind_group(0, &bind, &[]);
                    pass.dispatch_workgroups(SIDE / side / 8, SIDE / side / 4, 1);
                }
                let start = Instant::now();
                queue.submit([encoder.finish()]);
                device.poll(wgpu::PollType::wait_indefinitely()).expect("the dispatch failed");
                start.elapsed().as_secs_f64() * 1e3
            })
            .skip(WARM_UP)
            .collect();
        times.sort_by(f64::total_cmp);
        println!("{name:<22} {:>7.3} {:>7.3}", times[TIMED / 2], times[0]);
    }
}
