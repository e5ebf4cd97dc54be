//! `glint view`: the interactive viewer.

use std::path::PathBuf;
use std::time::Instant;

use clap::Args;
use glint_viewer::{FirstImage, FirstImageWatch};

use crate::{exit, Failure};

/// The scene `glint view` opens when none is named: the showcase, built into
/// the program so that it opens from any directory. It is plain TOML that
/// names no other file.
pub const DEFAULT_SCENE: &str = include_str!("../../../scenes/showcase.toml");

/// What the built-in default scene is called in the window and in messages.
const DEFAULT_NAME: &str = "showcase.toml";
/// The built-in scene's entry in the record of scenes viewed or rendered
/// before: no file has this path.
const DEFAULT_RECORD: &str = "glint:showcase.toml";

#[derive(Args)]
pub struct ViewArgs {
    /// Scene file (.toml, .nff, .ray or .obj), or spd:NAME[:SIZE]; default: the showcase, built in
    #[arg(value_parser = crate::scene_arg::parse)]
    scene: Option<PathBuf>,
    /// Close once the first complete image is on screen and print how long it
    /// took from the start (window, scene, kernels compiled, one sample per
    /// pixel) and, where the device profile chooses them, which kernels it compiled
    #[arg(long)]
    first_image: bool,
}

/// Why no window can be opened here, when that is clear before trying: on
/// Linux and the BSDs, no X11 or Wayland display is named in the environment.
fn missing_display() -> Option<String> {
    if cfg!(any(target_os = "windows", target_os = "macos", target_os = "ios", target_os = "android")) {
        return None;
    }
    let set = |name: &str| std::env::var_os(name).is_some_and(|v| !v.is_empty());
    if set("DISPLAY") || set("WAYLAND_DISPLAY") || set("WAYLAND_SOCKET") {
        return None;
    }
    Some(
        "cannot open a window: there is no display (neither DISPLAY nor WAYLAND_DISPLAY is set); run `glint view` on a \
desktop, or under `xvfb-run glint view`; `glint render` needs no display"
            .into(),
    )
}

pub fn run(args: ViewArgs) -> Result<(), Failure> {
    let start = Instant::now();
    if let Some(message) = missing_display() {
        return Err(Failure::new(exit::NO_DISPLAY, message));
    }
    let record = args.scene.clone().unwrap_or_else(|| DEFAULT_RECORD.into());
    let viewed_scenes = glint_gpu::RenderedScenes::on_this_machine();
    // Before eframe makes the device.
    glint_gpu::Workload::interactive(viewed_scenes.contains(&record)).prepare_driver()?;
    let scene = match args.scene {
        Some(path) => glint_viewer::Scene::File(path),
        None => glint_viewer::Scene::BuiltIn { name: DEFAULT_NAME.into(), text: DEFAULT_SCENE },
    };
    let watch = args.first_image.then(|| FirstImageWatch::new(start));
    glint_viewer::run_scene(scene, watch.clone()).map_err(|e| match e {
        glint_viewer::RunError::NoDisplay(message) => Failure::new(exit::NO_DISPLAY, message),
        glint_viewer::RunError::Failed(e) => Failure::new(exit::GPU, e),
    })?;
    let outcome = watch.map(|w| w.outcome());
    if matches!(outcome, None | Some(Some(FirstImage::Shown { .. }))) {
        viewed_scenes.insert(&record);
    }
    match outcome {
        None => Ok(()),
        Some(Some(FirstImage::Shown { after, adapter })) => {
            println!("first image after {:.2} s{}", after.as_secs_f64(), kernels_note(&adapter));
            Ok(())
        }
        Some(Some(FirstImage::SceneError(e))) => Err(Failure::new(exit::INPUT, e)),
        Some(Some(FirstImage::Failed(e))) => Err(Failure::new(exit::GPU, e)),
        Some(None) => Err(Failure::new(exit::GPU, "the window was closed before the first image was shown")),
    }
}

/// Which kernels the driver compiled, where the device profile chooses
/// them, for a report of how long they took.
fn kernels_note(adapter: &wgpu::AdapterInfo) -> String {
    glint_gpu::CompiledKernels::on(adapter).map_or_else(String::new, |kernels| format!(" ({kernels})"))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_built_in_scene_is_the_showcase_and_stands_alone() {
        let on_disk = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../../scenes/showcase.toml");
        let from_disk = glint_scene::load(&on_disk).unwrap();
        let built_in = glint_scene::toml_scene::parse(DEFAULT_SCENE, std::path::Path::new(DEFAULT_NAME)).unwrap();
        assert_eq!(built_in, from_disk);
        assert!(built_in.warnings.is_empty(), "{:?}", built_in.warnings);
        // Nothing else to read: no meshes, no includes.
        assert!(!DEFAULT_SCENE.contains("path"), "the built-in scene must not name other files");
    }
}
