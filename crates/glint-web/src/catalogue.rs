//! The scenes built into the page, offered in its Scene menu: the files of
//! `scenes/` that need nothing beside them, and the Standard Procedural
//! Databases, which Glint generates (`spd:NAME`).

/// A scene file built into the page.
pub struct BuiltIn {
    /// Its path under `scenes/`: its name in the menu and in links, and the
    /// file name its loader sees.
    pub name: &'static str,
    pub text: &'static str,
}

macro_rules! built_in {
    ($($path:literal),* $(,)?) => {
        &[$(BuiltIn { name: $path, text: include_str!(concat!("../../../scenes/", $path)) }),*]
    };
}

/// The scene the page opens when its link names none.
pub const FIRST: &str = "showcase.toml";

pub const SCENES: &[BuiltIn] = built_in![
    "showcase.toml",
    "whitted1980.toml",
    "tutorial.toml",
    "first.toml",
    "turntable.toml",
    "cone_tree.nff",
    "sphereflake.nff",
];

/// The gallery: one lecture term per scene.
pub const GALLERY: &[BuiltIn] = built_in![
    "gallery/ambient.toml",
    "gallery/attenuation.toml",
    "gallery/depth_cue.toml",
    "gallery/glass.toml",
    "gallery/highlights.toml",
    "gallery/lambert.toml",
    "gallery/mirror.toml",
    "gallery/orthographic.toml",
    "gallery/phong_vs_blinn.toml",
    "gallery/primitives.toml",
    "gallery/shadows.toml",
    "gallery/total_internal_reflection.toml",
];

/// The names the menu offers for the Standard Procedural Databases.
pub fn spd_names() -> impl Iterator<Item = String> {
    glint_spd::DATABASES.iter().map(|d| format!("spd:{}", d.name))
}

/// The built-in scene file called `name`.
pub fn built_in(name: &str) -> Option<&'static BuiltIn> {
    SCENES.iter().chain(GALLERY).find(|s| s.name == name)
}

/// Whether `name` is a scene the page can open without a file: a built-in
/// one or a database.
pub fn is_known(name: &str) -> bool {
    built_in(name).is_some() || spd_names().any(|n| n == name)
}

#[cfg(test)]
mod tests {
    use std::path::Path;

    use super::*;

    #[test]
    fn every_built_in_scene_loads_as_the_page_opens_it() {
        for scene in SCENES.iter().chain(GALLERY) {
            glint_scene::opened_files::provide(scene.name, scene.text.as_bytes());
            if let Err(e) = glint_scene::load(Path::new(scene.name)) {
                panic!("{e}");
            }
        }
        assert!(built_in(FIRST).is_some());
        let names: Vec<_> = SCENES.iter().chain(GALLERY).map(|s| s.name).collect();
        let mut unique = names.clone();
        unique.sort();
        unique.dedup();
        assert_eq!(unique.len(), names.len(), "two built-in scenes share a name: {names:?}");
    }

    #[test]
    fn every_database_is_offered() {
        assert_eq!(spd_names().count(), glint_spd::DATABASES.len());
        assert!(is_known("spd:teapot") && is_known("gallery/glass.toml") && !is_known("spd:nothing") && !is_known("mine.nff"));
    }
}
