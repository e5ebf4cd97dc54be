//! ARCHITECTURE.md's recipe for adding a primitive kind stays true: it lists
//! at most eight files, each of which handles the worked example, the cone;
//! no other source file names the cone's kind but a short list of the cone's
//! own tests; and the scene format's page names every object type.

mod support;

use std::path::{Path, PathBuf};

/// How code names the cone's kind: its variant, the reference's geometry and
/// random kind, its code and its flag.
const CONE_WORDS: [&str; 5] = ["Shape::Cone", "Geom::Cone", "Kind::Cone", "PRIM_CONE", "HAS_CONES"];

/// Files that name the cone's kind without being a step of the recipe.
const NOT_STEPS: [(&str, &str); 4] = [
    ("crates/glint-encoding/src/gpu_types.rs", "re-exports the codes for its callers; a new kind needs none"),
    ("crates/glint-scene/src/nff/tests.rs", "NFF's own cone statement"),
    ("crates/glint-scene/src/toml_scene/tests.rs", "the TOML cone's keys"),
    ("crates/glint-reference/src/tests.rs", "the reference's cone silhouettes and normals"),
];

fn root() -> &'static Path {
    Path::new(env!("CARGO_MANIFEST_DIR"))
}

fn read(path: &Path) -> String {
    std::fs::read_to_string(path).unwrap_or_else(|e| panic!("{}: {e}", path.display()))
}

/// The files of the recipe's numbered steps, with `<kind>` read as the cone.
/// ARCHITECTURE.md writes crate paths from `crates/`.
fn recipe() -> Vec<PathBuf> {
    let architecture = read(&root().join("ARCHITECTURE.md"));
    let section = architecture.split("## Adding a primitive kind").nth(1).expect("ARCHITECTURE.md has the recipe");
    let section = section.split("\n## ").next().unwrap();
    section
        .lines()
        .filter(|line| line.split_once(". ").is_some_and(|(n, _)| !n.is_empty() && n.chars().all(|c| c.is_ascii_digit())))
        .map(|line| {
            let path = line.split('`').nth(1).unwrap_or_else(|| panic!("the step names no file: {line}")).replace("<kind>", "cone");
            [root().join(&path), root().join("crates").join(&path)].into_iter().find(|p| p.is_file()).unwrap_or_else(|| panic!("no file {path}: {line}"))
        })
        .collect()
}

#[test]
fn the_recipe_lists_at_most_eight_files_each_handling_the_cone() {
    let steps = recipe();
    assert!((1..=8).contains(&steps.len()), "the recipe lists {} files: {steps:?}", steps.len());
    for file in &steps {
        assert!(read(file).to_lowercase().contains("cone"), "{} does not handle the cone", file.display());
    }
}

#[test]
fn no_source_file_outside_the_recipe_names_the_cone_s_kind() {
    let steps = recipe();
    let mut files = Vec::new();
    for dir in ["crates", "tests", "shaders"] {
        support::source_files(&root().join(dir), &["rs", "wgsl"], &mut files);
    }
    // This file names the words it looks for.
    files.retain(|f| *f != root().join(file!()));
    let naming: Vec<PathBuf> = files.into_iter().filter(|f| CONE_WORDS.iter().any(|word| read(f).contains(word))).collect();
    for file in &naming {
        let listed = steps.contains(file) || NOT_STEPS.iter().any(|(path, _)| root().join(path) == *file);
        assert!(listed, "{} names the cone's kind: a step of ARCHITECTURE.md's recipe, or one of NOT_STEPS", file.display());
    }
    for (path, why) in NOT_STEPS {
        assert!(naming.contains(&root().join(path)), "{path} ({why}) no longer names the cone's kind: take it off NOT_STEPS");
    }
}

#[test]
fn the_scene_format_page_names_every_object_type() {
    let page = read(&root().join("docs/scene-format.md"));
    for kind in glint_scene::toml_scene::object_types() {
        assert!(page.contains(&format!("\"{kind}\"")), "docs/scene-format.md does not name the object type \"{kind}\"");
    }
}
