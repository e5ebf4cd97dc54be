//! Glint's native scene format: TOML, documented in docs/scene-format.md.
//!
//! Every table is a plain struct with `deny_unknown_fields` (no serde enums, which
//! would buffer the input and lose positions), numbers go through newtypes that
//! reject NaN and infinity while the parser still knows where they are, and
//! checks that need the whole table report the table's own line.
//!
//! Two kinds of entries bring in other files, named relative to the scene file:
//!
//! * an object of `type = "mesh"` with `path = "model.obj"` places an OBJ mesh
//!   (its MTL materials, unless `material = "name"` overrides them all) with an
//!   optional transform: `scale = s` or `[sx, sy, sz]`, `rotate = [rx, ry, rz]`
//!   (degrees, about X, then Y, then Z), `translate = [x, y, z]`, applied in that
//!   order; or instead `matrix = [[..4..], [..], [..], [..]]`, a row-major affine
//!   4×4 matrix (last row `[0, 0, 0, 1]`) acting on column vectors. Normals
//!   transform by the inverse transpose. An OBJ named by several objects is read
//!   once and copied, transformed, into each; each OBJ part becomes one object.
//! * `[[include]]` with `path = "part.nff"` (or `spd:NAME[:SIZE]`) merges an NFF file's objects, lights
//!   and materials (after the TOML file's own objects, in include order); its
//!   `v` block (optional in an included file) and background are ignored, the
//!   TOML file's camera and image apply. Its lights keep their NFF intensity
//!   1/√n, n counting the lights of that NFF file.
//!
//! An error in the reference (a missing file, a bad transform) names the TOML
//! line; an error inside the OBJ, MTL or NFF file names that file.
//!
//! An `[animation]` table (`animation`) moves the camera and the point lights
//! from frame to frame.

mod animation;
mod build;
mod defs;
mod mesh;
mod notes;
mod object;
#[cfg(test)]
mod tests;
mod values;

pub use notes::material_notes;
pub use object::object_types;
pub(crate) use object::{written_object, Written};

use std::cell::RefCell;
use std::path::Path;

use glam::Vec3;

use crate::toml_errors;
use crate::{LoadError, ReadError, Scene};
use animation::{AnimationDef, CameraKeyDef, LightKeyDef, OrbitDef};
use build::Builder;

use defs::{AmbientDef, CameraDef, CheckerDef, DepthCueDef, FileDef, ImageDef, IncludeDef, LightDef, MaterialDef, ObjectDef, RenderDef};

pub fn load(path: &Path) -> Result<Scene, LoadError> {
    let source = crate::read_text(path).map_err(|e| match e {
        ReadError::Io(e) => LoadError::new(path, None, format!("cannot read scene file: {e}")),
        ReadError::NotText(e) => e,
    })?;
    parse(&source, path)
}

/// Parses TOML scene text; `path` names the file in errors.
pub fn parse(source: &str, path: &Path) -> Result<Scene, LoadError> {
    let file: FileDef = toml::from_str(source).map_err(|e| toml_errors::explain(source, path, &e, &SCHEMA))?;
    Builder { source, path, warnings: RefCell::new(Vec::new()), colours_0_to_255: RefCell::new(Vec::new()) }.build(file)
}

/// The tables and keys of the format, for errors about unknown keys.
const SCHEMA: toml_errors::Schema = toml_errors::Schema { fields: schema_fields, object_keys: object::object_keys };

fn schema_fields(path: &[&str]) -> Option<&'static [&'static str]> {
    use toml_errors::fields_of;
    Some(match path {
        [] => fields_of::<FileDef>(),
        ["image"] => fields_of::<ImageDef>(),
        ["camera"] => fields_of::<CameraDef>(),
        ["ambient"] => fields_of::<AmbientDef>(),
        ["render"] => fields_of::<RenderDef>(),
        ["depth_cue"] => fields_of::<DepthCueDef>(),
        ["light"] => fields_of::<LightDef>(),
        ["material", _] => fields_of::<MaterialDef>(),
        ["material", _, "checker"] => fields_of::<CheckerDef>(),
        ["object"] => fields_of::<ObjectDef>(),
        ["include"] => fields_of::<IncludeDef>(),
        ["animation"] => fields_of::<AnimationDef>(),
        ["animation", "camera"] => fields_of::<CameraKeyDef>(),
        ["animation", "light"] => fields_of::<LightKeyDef>(),
        ["animation", "orbit"] => fields_of::<OrbitDef>(),
        _ => return None,
    })
}

/// A number in at most two decimals, as messages show one: `0.5`, `-1`
/// (and `0`, never `-0`).
fn short_number(v: f32) -> String {
    let s = format!("{:.2}", (v * 100.0).round() / 100.0 + 0.0);
    s.trim_end_matches('0').trim_end_matches('.').to_string()
}

/// `[0, -0.71, 0.71]`.
pub(super) fn short_vector(v: Vec3) -> String {
    format!("[{}, {}, {}]", short_number(v.x), short_number(v.y), short_number(v.z))
}

/// Whole numbers above 1 and up to 255: a colour written 0 to 255.
pub(super) fn looks_like_0_to_255(c: Vec3) -> bool {
    c.max_element() > 1.0 && c.to_array().iter().all(|v| v.fract() == 0.0 && *v <= 255.0)
}

/// A warning for a colour with a component above 1, saying how the image
/// will look. `reflectance`: a colour that must lie in [0, 1] (a
/// material's); otherwise light (or the background), which may be brighter
/// than 1 and is warned about only when it looks like 0–255 values.
pub(super) fn colour_warning(key: &str, c: Vec3, reflectance: bool) -> Option<String> {
    if c.max_element() <= 1.0 {
        return None;
    }
    let whole = looks_like_0_to_255(c);
    if !reflectance && !whole {
        return None;
    }
    let shown = |c: Vec3| if c.x == c.y && c.y == c.z { short_number(c.x) } else { short_vector(c) };
    let (brightness, effect) = match (reflectance, key) {
        (true, _) => ("", "what this material colours renders white"),
        (false, "background") => ("", "the background renders white"),
        (false, _) => (" (set the brightness with `intensity`)", "this light washes the image out to white"),
    };
    Some(if whole {
        format!("{key}: {} looks like 0–255 values, but colours are 0 to 1{brightness}, so {effect}; did you mean {}?", shown(c), shown(c / 255.0))
    } else {
        format!("{key}: {} is above 1, but a material's colours are 0 to 1: it would reflect more light than arrives", shown(c))
    })
}

