//! What `glint check` notes about a TOML scene's materials beyond what
//! loading warns about: an object without `material` (it silently gets the
//! default) and a material no object uses. Both are valid, and a scene Glint
//! writes may hold them, so loading stays quiet; a student checking a scene
//! learns of them here.

use std::collections::BTreeMap;
use std::path::Path;

use serde::Deserialize;
use toml::Spanned;

use crate::{LoadError, Location};

/// Only the keys the notes need; everything else was checked by loading.
#[derive(Deserialize)]
struct Materials {
    #[serde(default)]
    material: BTreeMap<String, Spanned<toml::Value>>,
    #[serde(default)]
    object: Vec<Spanned<ObjectMaterial>>,
}

#[derive(Deserialize)]
struct ObjectMaterial {
    #[serde(rename = "type")]
    kind: String,
    material: Option<String>,
}

/// The notes for the TOML scene `source`, read from `path`, in file order.
pub fn material_notes(source: &str, path: &Path) -> Vec<LoadError> {
    let Ok(file) = toml::from_str::<Materials>(source) else { return Vec::new() };
    let at = |offset: usize, message: String| (offset, LoadError::new(path, Some(Location::of_offset(source, offset)), message));
    let mut notes = Vec::new();
    for object in &file.object {
        let ObjectMaterial { kind, material } = object.get_ref();
        // A mesh without `material` keeps its MTL materials.
        if material.is_none() && kind != "mesh" {
            notes.push(at(object.span().start, format!("object: this {kind} has no `material`, so it gets the default, a matte light grey")));
        }
    }
    for (name, def) in &file.material {
        if !file.object.iter().any(|o| o.get_ref().material.as_ref() == Some(name)) {
            notes.push(at(def.span().start, format!("material.{name}: defined but never used: no object has `material = \"{name}\"`")));
        }
    }
    notes.sort_by_key(|(offset, _)| *offset);
    notes.into_iter().map(|(_, note)| note).collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn objects_without_a_material_and_materials_never_used_are_noted() {
        let source = "[material.red]\ncolor = 0.5\n[material.blue]\ncolor = [0, 0, 1]\n\n\
[[object]]\ntype = \"sphere\"\nradius = 1\n\n[[object]]\ntype = \"sphere\"\nmaterial = \"red\"\n\n[[object]]\ntype = \"mesh\"\npath = \"a.obj\"\n";
        let notes: Vec<String> = material_notes(source, Path::new("s.toml")).iter().map(ToString::to_string).collect();
        assert_eq!(
            notes,
            [
                "s.toml:3:1: material.blue: defined but never used: no object has `material = \"blue\"`",
                "s.toml:6:1: object: this sphere has no `material`, so it gets the default, a matte light grey",
            ]
        );
    }
}
