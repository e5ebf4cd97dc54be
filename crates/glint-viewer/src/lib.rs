//! `glint view`: an interactive viewer for Glint scenes. eframe draws the UI
//! with its wgpu renderer on the same device the ray tracer uses; the rendered
//! image is a texture the present kernel fills and egui draws, so no frame goes
//! through the CPU.
//!
//! The image refines progressively while the view is still and restarts on any
//! change. Lights, materials and render settings are edited live; clicking the
//! image selects the object under the pointer; in inspect mode (I, or a
//! Ctrl-click) it pins a pixel and shows its ray tree, and observer mode (O)
//! freezes that tree to be seen from outside. The scene file and the WGSL in
//! `shaders/` are reloaded when they change on disk; a broken file shows its
//! error and the last good scene or pipeline keeps running.

mod app;
mod camera_control;
mod document;
mod engine;
mod first_image;
mod host;
mod image;
mod inspector;
mod jobs;
mod observer;
mod panel;
mod selection;
mod settings;
mod shaders;
mod viewport;
mod warm_up;
mod watch;

use std::path::PathBuf;
#[cfg(not(target_arch = "wasm32"))]
use std::sync::Arc;

pub use app::{StartError, ViewerApp, ViewerOptions};
pub use first_image::{FirstImage, FirstImageWatch};

/// What the viewer opens.
pub enum Scene {
    /// Nothing: a scene is opened from the window.
    None,
    /// A scene file (or `spd:NAME[:SIZE]`), reloaded when it changes.
    File(PathBuf),
    /// TOML text built into the program, called `name`.
    BuiltIn { name: PathBuf, text: &'static str },
}

/// Why the viewer could not run.
#[derive(Debug)]
pub enum RunError {
    /// There is no display to open a window on (no X11 or Wayland server).
    NoDisplay(String),
    /// Anything else: the GPU, or the viewer itself.
    Failed(StartError),
}

impl std::fmt::Display for RunError {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            RunError::NoDisplay(m) => f.write_str(m),
            RunError::Failed(e) => e.fmt(f),
        }
    }
}

impl std::error::Error for RunError {}

/// Opens the viewer window on `scene` and returns when it is closed.
#[cfg(not(target_arch = "wasm32"))]
pub fn run(scene: Option<PathBuf>) -> Result<(), StartError> {
    run_scene(scene.map_or(Scene::None, Scene::File), None).map_err(|e| match e {
        RunError::NoDisplay(m) => StartError(m),
        RunError::Failed(e) => e,
    })
}

/// [`run`], telling a missing display apart from other failures; with
/// `first_image`, the window closes once the first image (or a problem) is shown.
#[cfg(not(target_arch = "wasm32"))]
pub fn run_scene(scene: Scene, first_image: Option<FirstImageWatch>) -> Result<(), RunError> {
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
    let options = match scene {
        Scene::None => ViewerOptions::new(None),
        Scene::File(path) => ViewerOptions::new(Some(path)),
        Scene::BuiltIn { name, text } => ViewerOptions { scene_text: Some(text), ..ViewerOptions::new(Some(name)) },
    };
    let options = ViewerOptions { first_image, ..options };
    eframe::run_native("glint", native, Box::new(|cc| Ok(Box::new(ViewerApp::new(cc, options)?)))).map_err(|e| match e {
        // The event loop could not start: no window system to talk to. winit's
        // message names its own source file; say what it means instead.
        eframe::Error::WinitEventLoop(e) => RunError::NoDisplay(format!(
            "cannot open a window: no display could be reached ({}); run `glint view` on a desktop, \
or under `xvfb-run glint view`",
            without_source_paths(&e.to_string()).trim_start_matches("os error").trim()
        )),
        e => RunError::Failed(StartError(without_source_paths(&one_line(e)))),
    })
}

/// `message` without the "at /path/to/file.rs:123" that some errors carry.
#[cfg(not(target_arch = "wasm32"))]
fn without_source_paths(message: &str) -> String {
    let words: Vec<&str> = message.split_whitespace().collect();
    let mut kept = Vec::new();
    let mut i = 0;
    while i < words.len() {
        let is_source = |w: &str| w.contains(".rs:") || w.contains("/.cargo/") || w.contains("/registry/src/");
        if words[i] == "at" && words.get(i + 1).is_some_and(|w| is_source(w)) {
            i += 2;
            continue;
        }
        if is_source(words[i]) {
            i += 1;
            continue;
        }
        kept.push(words[i]);
        i += 1;
    }
    kept.join(" ")
}

/// An error message on one line.
pub(crate) fn one_line(message: impl std::fmt::Display) -> String {
    message.to_string().split_whitespace().collect::<Vec<_>>().join(" ")
}

#[cfg(all(test, not(target_arch = "wasm32")))]
mod tests {
    #[test]
    fn source_paths_are_left_out_of_messages() {
        let m = "os error at /root/.cargo/registry/src/index.crates.io-1949cf8c6b5b557f/winit-0.30.13/src/platform_impl/linux/mod.rs:765: \
neither WAYLAND_DISPLAY nor WAYLAND_SOCKET nor DISPLAY is set.";
        assert_eq!(super::without_source_paths(m), "os error neither WAYLAND_DISPLAY nor WAYLAND_SOCKET nor DISPLAY is set.");
    }
}

/// How eframe opens its device for Glint: an adapter chosen as `glint render`
/// chooses one (a real GPU first, `GLINT_ADAPTER` pins one by name; only
/// adapters with compute shaders qualify), with what its device profile uses.
/// eframe's device is never opened again, so it gets the adapter's limits of
/// a scene's size at once.
#[cfg(not(target_arch = "wasm32"))]
pub fn wgpu_setup() -> egui_wgpu::WgpuSetup {
    let mut setup = egui_wgpu::WgpuSetupCreateNew::without_display_handle();
    setup.instance_descriptor.backends = glint_gpu::backends();
    setup.native_adapter_selector = Some(Arc::new(choose_adapter));
    setup.device_descriptor = Arc::new(|adapter| glint_gpu::device_descriptor(adapter, glint_gpu::SceneLimits::Adapter));
    egui_wgpu::WgpuSetup::CreateNew(setup)
}

#[cfg(not(target_arch = "wasm32"))]
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
    usable.sort_by_key(|a| glint_gpu::adapter_rank(a));
    usable.first().map(|a| (*a).clone()).ok_or_else(|| {
        format!("no GPU adapter with compute shaders can draw to this window: {}", glint_gpu::NO_ADAPTER_HINT)
    })
}
