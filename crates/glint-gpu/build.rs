//! Embeds every WGSL file under the repository's `shaders/` folder, at any
//! depth, named by its path relative to that folder ("lib/camera.wgsl"). A
//! new shader file so needs no Rust edit: `src/shaders.rs` includes the list
//! written here.

use std::fmt::Write;
use std::path::{Path, PathBuf};

fn main() {
    let manifest = PathBuf::from(std::env::var_os("CARGO_MANIFEST_DIR").expect("cargo sets CARGO_MANIFEST_DIR"));
    let shaders = manifest.join("../../shaders");
    let shaders = shaders.canonicalize().unwrap_or_else(|e| panic!("{}: {e}", shaders.display()));
    // A directory is scanned whole, so an added, removed or edited file rebuilds.
    println!("cargo::rerun-if-changed={}", shaders.display());
    let mut files = Vec::new();
    wgsl_files(&shaders, "", &mut files);
    files.sort();
    let mut out = String::from("/// Every WGSL file, relative to `shaders/`.\npub const SOURCES: &[&str] = &[\n");
    for (name, _) in &files {
        writeln!(out, "    {name:?},").unwrap();
    }
    out.push_str("];\n\nconst EMBEDDED: &[(&str, &str)] = &[\n");
    for (name, path) in &files {
        writeln!(out, "    ({name:?}, include_str!({:?})),", path.display().to_string()).unwrap();
    }
    out.push_str("];\n");
    let target = PathBuf::from(std::env::var_os("OUT_DIR").expect("cargo sets OUT_DIR")).join("shader_files.rs");
    std::fs::write(&target, out).unwrap_or_else(|e| panic!("{}: {e}", target.display()));
}

/// Appends the `.wgsl` files under `dir`, whose path relative to `shaders/`
/// is `prefix`, as (name relative to `shaders/`, path).
fn wgsl_files(dir: &Path, prefix: &str, files: &mut Vec<(String, PathBuf)>) {
    let entries = std::fs::read_dir(dir).unwrap_or_else(|e| panic!("{}: {e}", dir.display()));
    for entry in entries {
        let path = entry.unwrap_or_else(|e| panic!("{}: {e}", dir.display())).path();
        let file_name = path.file_name().and_then(|n| n.to_str()).unwrap_or_else(|| panic!("{}: not a UTF-8 name", path.display()));
        let name = format!("{prefix}{file_name}");
        if path.is_dir() {
            wgsl_files(&path, &format!("{name}/"), files);
        } else if name.ends_with(".wgsl") {
            files.push((name, path));
        }
    }
}
