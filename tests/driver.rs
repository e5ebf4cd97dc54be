//! Checks of the driver itself. Debian 12's Mesa 22.3 lavapipe silently ends
//! every loop after 65,535 iterations of an invocation, giving wrong pixels and
//! no error; this fails on such a driver.

mod support;

use wgpu::util::DeviceExt;

const LOOP_KERNEL: &str = r#"
@group(0) @binding(0) var<storage, read_write> out: array<u32>;

@compute @workgroup_size(1)
fn main() {
    var count = 0u;
    for (var i = 0u; i < 100000u; i++) {
        count += 1u;
    }
    out[0] = count;
}
"#;

#[test]
fn long_shader_loops_run_to_the_end() {
    let gpu = support::gpu();
    let device = &gpu.device;
    let module = device.create_shader_module(wgpu::ShaderModuleDescriptor {
        label: Some("loop"),
        source: wgpu::ShaderSource::Wgsl(LOOP_KERNEL.into()),
    });
    let pipeline = device.create_compute_pipeline(&wgpu::ComputePipelineDescriptor {
        label: Some("loop"),
        layout: None,
        module: &module,
        entry_point: Some("main"),
        compilation_options: Default::default(),
        cache: None,
    });
    let out = device.create_buffer_init(&wgpu::util::BufferInitDescriptor {
        label: None,
        contents: &[0u8; 4],
        usage: wgpu::BufferUsages::STORAGE | wgpu::BufferUsages::COPY_SRC,
    });
    let readback = device.create_buffer(&wgpu::BufferDescriptor {
        label: None,
        size: 4,
        usage: wgpu::BufferUsages::MAP_READ | wgpu::BufferUsages::COPY_DST,
        mapped_at_creation: false,
    });
    let bind = device.create_bind_group(&wgpu::BindGroupDescriptor {
        label: None,
        layout: &pipeline.get_bind_group_layout(0),
        entries: &[wgpu::BindGroupEntry { binding: 0, resource: out.as_entire_binding() }],
    });
    let mut encoder = device.create_command_encoder(&Default::default());
    {
        let mut pass = encoder.begin_compute_pass(&Default::default());
        pass.set_pipeline(&pipeline);
        pass.set_bind_group(0, &bind, &[]);
        pass.dispatch_workgroups(1, 1, 1);
    }
    encoder.copy_buffer_to_buffer(&out, 0, &readback, 0, 4);
    gpu.queue.submit([encoder.finish()]);
    readback.map_async(wgpu::MapMode::Read, .., |r| r.unwrap());
    device.poll(wgpu::PollType::wait_indefinitely()).unwrap();
    let count = u32::from_le_bytes(readback.get_mapped_range(..).unwrap()[..4].try_into().unwrap());
    let info = gpu.info();
    assert_eq!(
        count, 100_000,
        "{} ({}) truncated a 100,000-iteration loop: install Mesa 25 or newer (bash .ci/setup)",
        info.name, info.driver_info
    );
}
