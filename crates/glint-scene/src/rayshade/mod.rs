//! Rayshade's scene format (`.ray`), the subset the Standard Procedural
//! Databases write with `-r 8` and a little more, with the meanings Rayshade's
//! User's Guide (and its source, Rayshade 4.0) gives each keyword.
//!
//! The file is read as a stream of whitespace-separated tokens; `/* … */` and
//! `//` comments are skipped. Every token remembers its line and column, so
//! that errors name the place.
//!
//! | keyword | operands | becomes |
//! |---|---|---|
//! | `eyep`, `lookp`, `up` | `x y z` each | the camera (defaults (0, −10, 0), the origin, +z) |
//! | `fov` | `H [V]` | horizontal and vertical field of view, edge to edge (default 45; V = H·height/width); see [`fov_y`] |
//! | `screen` | `W H` | image size (default 512 × 512) |
//! | `background` | `r g b` | background colour (default black) |
//! | `sample` | `N [jitter\|nojitter]` | checked; Glint traces one sample per pixel unless `--spp` says more |
//! | `maxdepth`, `cutoff` | `N` | the ray tree's depth (eye ray = 0, so Glint's `max_depth` is N + 1; default 5) and weight cutoff (default 0.002) |
//! | `light` | `I point x y z`, `I directional x y z`, `I ambient` | a light of intensity I (one number, white, or `r g b`); without any point or directional light, Rayshade's default directional light from (1, −1, 1); the ambient light defaults to white, 1 |
//! | `surface` | `NAME` then `ambient C`, `diffuse C`, `specular C`, `specpow N`, `reflect N`, `transp N`, `body C`, `index N` | a material, see [`material`] |
//! | `sphere` | `[SURF] r x y z` | a sphere |
//! | `cone` | `[SURF] r1 x1 y1 z1 r2 x2 y2 z2` | an open cone |
//! | `cylinder` | `[SURF] r x1 y1 z1 x2 y2 z2` | an open cylinder |
//! | `polygon` | `[SURF] x y z …` (at least three vertices) | a planar polygon |
//! | `triangle` | `[SURF] p1 p2 p3`, or `p1 n1 p2 n2 p3 n3` | a triangle, flat or with vertex normals |
//! | `plane` | `[SURF] x y z nx ny nz` | an infinite plane |
//!
//! Every primitive becomes one [`Object`](crate::Object). Any other Rayshade
//! keyword (transformations, `list`, `grid`, `define`, textures, the other
//! light and object kinds, …) is an error naming it; a surface term Glint has
//! no way to express (`noshadow`, `extinct`) is a warning.

use std::path::Path;

use glam::Vec3;

mod parse;
#[cfg(test)]
mod tests;

use crate::{LoadError, Material, SpecularModel};

/// Rayshade's `EPSILON`: a highlight exponent below it turns highlights off.
const EPSILON: f32 = 1.0e-5;

/// A `surface` block, each component as Rayshade defaults it: colours and
/// coefficients 0, `body` white, `specpow` 15 and `index` 1.
#[derive(Debug, Clone, PartialEq)]
pub struct Surface {
    pub ambient: Vec3,
    pub diffuse: Vec3,
    pub specular: Vec3,
    pub specpow: f32,
    pub reflect: f32,
    pub transp: f32,
    pub body: Vec3,
    pub index: f32,
}

impl Default for Surface {
    fn default() -> Self {
        Self {
            ambient: Vec3::ZERO,
            diffuse: Vec3::ZERO,
            specular: Vec3::ZERO,
            specpow: 15.0,
            reflect: 0.0,
            transp: 0.0,
            body: Vec3::ONE,
            index: 1.0,
        }
    }
}

/// Glint's material for a Rayshade surface. Rayshade shades a hit as
///
/// ```text
/// ambient·I_a + Σ_lights I_l·(diffuse·(N·L) + specular·(R·L)^specpow)
///   + reflect·specular·I(reflected) + transp·body·I(transmitted)
/// ```
///
/// (R the mirror direction of the eye ray), and Glint's terms take it over
/// exactly: O_d = `diffuse` with k_d = 1; k_a·O_d = `ambient`, which needs
/// `ambient` to be a multiple of `diffuse` (otherwise the nearest multiple,
/// and a warning in the returned string); a Phong highlight (R·V = R·L) with
/// k_s = 1, O_s = `specular`, n = `specpow` (none when `specpow` is below
/// Rayshade's ε); k_m = `reflect`·`specular`; k_t = `transp`·`body`; `index`
/// as ior; no Fresnel term. A surface with no diffuse colour takes its
/// ambient colour as O_d, with k_d = 0. An error when a product of its terms
/// overflows 32-bit floats.
pub fn material(name: &str, surface: &Surface) -> Result<(Material, Option<String>), String> {
    let (color, ambient, diffuse, warning) = if surface.diffuse != Vec3::ZERO {
        let d = surface.diffuse;
        // In f64: the squared length of a tiny colour underflows in f32.
        let (a64, d64) = (surface.ambient.as_dvec3(), d.as_dvec3());
        let k = (a64.dot(d64) / d64.dot(d64)) as f32;
        let off = (surface.ambient - k * d).abs().max_element();
        let warning = (off > 1.0e-6 * surface.ambient.max_element().max(d.max_element())).then(|| {
            format!(
                "surface {name}: its ambient colour is not a multiple of its diffuse colour, and Glint's ambient term is k_a·O_d: it uses k_a = {k} (ambient {} in place of {})",
                fmt_color(k * d),
                fmt_color(surface.ambient)
            )
        });
        (d, k, 1.0, warning)
    } else if surface.ambient != Vec3::ZERO {
        (surface.ambient, 1.0, 0.0, None)
    } else {
        (Vec3::ZERO, 0.0, 0.0, None)
    };
    let highlights = surface.specpow >= EPSILON && surface.specular != Vec3::ZERO;
    let material = Material {
        name: name.to_string(),
        ambient,
        diffuse,
        specular: if highlights { 1.0 } else { 0.0 },
        shininess: if highlights { surface.specpow } else { 0.0 },
        color,
        specular_color: highlights.then_some(surface.specular),
        specular_model: SpecularModel::Phong,
        metallic_f0: None,
        reflect: surface.reflect * surface.specular,
        transmit: surface.transp * surface.body,
        ior: surface.index,
        fresnel: false,
        checker: None,
    };
    let finite = material.ambient.is_finite() && material.reflect.is_finite() && material.transmit.is_finite();
    if !finite {
        return Err(format!("surface {name}: its terms multiply beyond the range of 32-bit floats"));
    }
    Ok((material, warning))
}

fn fmt_color(c: Vec3) -> String {
    format!("{} {} {}", c.x, c.y, c.z)
}

/// The scene model's vertical, edge-to-edge field of view (degrees) for
/// Rayshade's `fov H [V]` on a `width` × `height` screen. Rayshade spans
/// `H` across the image's width and `V` across its height, edge to edge,
/// and without `V` takes V = H·height/width. Glint's pixels are square, so
/// it keeps `V` and the horizontal extent follows from it; the second value
/// is the horizontal angle that gives, to compare with `H`.
pub fn fov_y(h: f64, v: Option<f64>, width: u32, height: u32) -> (f64, f64) {
    let v = v.unwrap_or(h * f64::from(height) / f64::from(width));
    let half = (v.to_radians() / 2.0).tan() * f64::from(width) / f64::from(height);
    (v, 2.0 * half.atan().to_degrees())
}

/// Reads a Rayshade file into a scene.
pub fn load(path: &Path) -> Result<crate::Scene, LoadError> {
    let source = crate::read_text(path).map_err(|e| match e {
        crate::ReadError::Io(e) => LoadError::new(path, None, format!("cannot read Rayshade file: {e}")),
        crate::ReadError::NotText(e) => e,
    })?;
    parse(&source, path)
}

/// Parses Rayshade text; `path` names the file in errors and warnings.
pub fn parse(source: &str, path: &Path) -> Result<crate::Scene, LoadError> {
    parse::parse(source, path)
}
