//! `glint info`: the adapter, the limits that matter for ray tracing (the
//! adapter's: devices are opened with WebGPU's defaults unless a scene needs
//! more) and the device profile.

use glint_gpu::Gpu;

use crate::Failure;

pub fn run() -> Result<(), Failure> {
    let gpu = Gpu::new()?;
    let info = gpu.info();
    let limits = gpu.adapter.limits();
    println!("adapter:      {}", info.name);
    println!("backend:      {:?}", info.backend);
    println!("device type:  {:?}", info.device_type);
    println!("driver:       {} {}", info.driver, info.driver_info);
    println!("profile:      {}", gpu.profile().describe());
    println!("max storage buffer binding size: {} bytes", limits.max_storage_buffer_binding_size);
    println!("max buffer size:                 {} bytes", limits.max_buffer_size);
    println!("max storage buffers per stage:   {}", limits.max_storage_buffers_per_shader_stage);
    println!(
        "max workgroup size:              {} x {} x {} ({} invocations)",
        limits.max_compute_workgroup_size_x,
        limits.max_compute_workgroup_size_y,
        limits.max_compute_workgroup_size_z,
        limits.max_compute_invocations_per_workgroup
    );
    println!("max workgroups per dimension:    {}", limits.max_compute_workgroups_per_dimension);
    if let Some(warning) = gpu.driver_warning() {
        eprintln!("{warning}");
    }
    Ok(())
}
