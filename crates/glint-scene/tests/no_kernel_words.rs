//! glint-scene holds the model, the loaders, validation and the BVH build; how
//! the kernels are written and run is glint-encoding's and glint-gpu's
//! business. No file of its sources or tests names the kernels' language,
//! their dispatch groups or the programs the device runs.

use std::path::{Path, PathBuf};

/// The words, in lower case and in pieces, so that this file passes its own check.
fn kernel_words() -> [String; 3] {
    [["wg", "sl"].concat(), ["work", "group"].concat(), ["sha", "der"].concat()]
}

fn files_under(dir: &Path, files: &mut Vec<PathBuf>) {
    for entry in std::fs::read_dir(dir).unwrap_or_else(|e| panic!("{}: {e}", dir.display())) {
        let path = entry.unwrap().path();
        if path.is_dir() {
            files_under(&path, files);
        } else {
            files.push(path);
        }
    }
}

#[test]
fn the_scene_crate_never_names_how_the_kernels_are_written_or_run() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let mut files = Vec::new();
    for dir in ["src", "tests"] {
        files_under(&root.join(dir), &mut files);
    }
    assert!(files.iter().any(|f| f.ends_with("src/lib.rs")), "the walk found the sources");
    let mut found = Vec::new();
    for file in &files {
        let text = std::fs::read_to_string(file).unwrap_or_else(|e| panic!("{}: {e}", file.display()));
        for (i, line) in text.lines().enumerate() {
            let lower = line.to_lowercase();
            for word in kernel_words().iter().filter(|w| lower.contains(w.as_str())) {
                found.push(format!("{}:{}: {word}: {}", file.display(), i + 1, line.trim()));
            }
        }
    }
    assert!(found.is_empty(), "glint-scene names the kernels' concerns:\n{}", found.join("\n"));
}
