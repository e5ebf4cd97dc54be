//! `glint view`: an interactive viewer for Glint scenes. eframe draws the UI
//! with its wgpu renderer on the same device the ray tracer uses; the rendered
//! image is a texture the present kernel fills and egui draws, so no frame goes
//! through the CPU.
//!
//! The image refines progressively while the view is still and restarts on any
//! change. Lights, materials and render settings are edited live; clicking the
//! image selects the object under the pointer. The scene file and the WGSL in
//! `shaders/` are reloaded when they change on disk; a broken file shows its
//! error and the last good scene or pipeline keeps running.

mod app;
mod camera_control;
mod engine;
mod jobs;
mod panel;
mod watch;

use std::path::PathBuf;
use std::sync::Arc;

pub use app::{StartError, ViewerApp, ViewerOptions};

/// Opens the viewer window on `scene` and returns when it is closed.
pub fn run(scene: Option<PathBuf>) -> Result<(), StartError> {
    let native = eframe::NativeOptions {
        viewport: egui::ViewportBuilder::default()
            .with_title("Glint")
            .with_inner_size([1280.0, 800.0])
            .with_min_inner_size([480.0, 320.0])
            .with_drag_and_drop(true),
        renderer: eframe::Renderer::Wgpu,
        wgpu_options: egui_wgpu::WgpuConfiguration { wgpu_setup: wgpu_setup(), ..Default::default() },
        ..Default::default()
    };
    let options = ViewerOptions::new(scene);
    eframe::run_native("glint", native, Box::new(|cc| Ok(Box::new(ViewerApp::new(cc, options)?))))
        .map_err(|e| StartError(app::one_line(e)))
}

/// How eframe opens its device for Glint: an adapter chosen as `glint render`
/// chooses one (a real GPU first, `GLINT_ADAPTER` pins one by name; only
/// adapters with compute shaders qualify), with the adapter's own limits rather
/// than wgpu's conservative defaults.
pub fn wgpu_setup() -> egui_wgpu::WgpuSetup {
    let mut setup = egui_wgpu::WgpuSetupCreateNew::without_display_handle();
    // GL has no compute shaders.
    setup.instance_descriptor.backends = wgpu::Backends::from_env().unwrap_or(wgpu::Backends::PRIMARY);
    setup.native_adapter_selector = Some(Arc::new(choose_adapter));
    setup.device_descriptor = Arc::new(|adapter| wgpu::DeviceDescriptor {
        label: Some("glint view"),
        required_limits: adapter.limits(),
        ..Default::default()
    });
    egui_wgpu::WgpuSetup::CreateNew(setup)
}

fn choose_adapter(adapters: &[wgpu::Adapter], surface: Option<&wgpu::Surface<'_>>) -> Result<wgpu::Adapter, String> {
    let mut usable: Vec<&wgpu::Adapter> = adapters
        .iter()
        .filter(|a| a.get_downlevel_capabilities().flags.contains(wgpu::DownlevelFlags::COMPUTE_SHADERS))
        .filter(|a| surface.is_none_or(|s| a.is_surface_supported(s)))
        .collect();
    if let Ok(wanted) = std::env::var(glint_gpu::ADAPTER_ENV) {
        let names: Vec<String> = usable.iter().map(|a| a.get_info().name).collect();
        return usable
            .into_iter()
            .find(|a| a.get_info().name.to_lowercase().contains(&wanted.to_lowercase()))
            .cloned()
            .ok_or_else(|| format!("{}={wanted} matches no usable adapter; found: {}", glint_gpu::ADAPTER_ENV, names.join(", ")));
    }
    let rank = |a: &&wgpu::Adapter| {
        let info = a.get_info();
        let kind = match info.device_type {
            wgpu::DeviceType::DiscreteGpu => 0,
            wgpu::DeviceType::IntegratedGpu => 1,
            wgpu::DeviceType::VirtualGpu => 2,
            wgpu::DeviceType::Other => 3,
            wgpu::DeviceType::Cpu => 4,
        };
        (kind, info.backend != wgpu::Backend::Vulkan)
    };
    usable.sort_by_key(rank);
    usable.first().map(|a| (*a).clone()).ok_or_else(|| {
        "no GPU adapter with compute shaders can draw to this window: install a Vulkan driver \
(without a GPU, lavapipe: `bash .ci/setup`)"
            .into()
    })
}
