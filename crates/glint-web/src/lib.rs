//! Glint's viewer in a browser tab. `glint-viewer`'s app (its panels, the
//! inspector, progressive accumulation) runs in eframe's web runner, and
//! `glint-gpu`'s kernels run on the browser's WebGPU; where the two crates
//! have a native-only way (threads, blocking read-backs, naga IR, files on
//! disk), a `cfg(target_arch = "wasm32")` picks the browser's.
//!
//! This crate adds what only a page has: a menu of the built-in scenes
//! (`catalogue.rs`), files opened by picker or drag and drop (`files.rs`,
//! `opening.rs`), downloads (`download.rs`), a link that holds the scene and
//! camera (`fragment.rs`), and the state the page publishes for its test
//! (`web_app.rs`). `web/build.sh` builds it; `tests/browser.rs` drives it in
//! headless Chromium.

pub mod catalogue;
pub mod fragment;
pub mod opening;

#[cfg(target_arch = "wasm32")]
mod download;
#[cfg(target_arch = "wasm32")]
mod files;
#[cfg(target_arch = "wasm32")]
mod web_app;

/// Starts the viewer on the page's canvas `glint`.
#[cfg(target_arch = "wasm32")]
#[wasm_bindgen::prelude::wasm_bindgen(start)]
pub fn start() {
    wasm_bindgen_futures::spawn_local(web_app::run());
}
