//! The tables of a TOML scene as they are written: one plain struct per
//! table, `deny_unknown_fields`, every value that an error may point at kept
//! `Spanned`. Turning them into the scene model is `build`'s job.

use std::collections::BTreeMap;

use serde::Deserialize;
use toml::Spanned;

use super::animation::AnimationDef;
use super::values::{Inline, Matrix, Num, Rgb, Scale, V2, V3};

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
pub(super) struct FileDef {
    pub(super) image: Spanned<ImageDef>,
    pub(super) camera: Spanned<CameraDef>,
    pub(super) ambient: Option<AmbientDef>,
    pub(super) render: Option<Spanned<RenderDef>>,
    pub(super) depth_cue: Option<Spanned<DepthCueDef>>,
    #[serde(default)]
    pub(super) light: Vec<Spanned<LightDef>>,
    #[serde(default)]
    pub(super) material: BTreeMap<String, Spanned<MaterialDef>>,
    #[serde(default)]
    pub(super) object: Vec<Spanned<ObjectDef>>,
    #[serde(default)]
    pub(super) include: Vec<Spanned<IncludeDef>>,
    pub(super) animation: Option<Spanned<AnimationDef>>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
pub(super) struct IncludeDef {
    pub(super) path: Spanned<String>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
pub(super) struct ImageDef {
    pub(super) width: Spanned<i64>,
    pub(super) height: Spanned<i64>,
    pub(super) background: Option<Spanned<Rgb>>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
pub(super) struct CameraDef {
    #[serde(rename = "type")]
    pub(super) kind: Option<Spanned<String>>,
    pub(super) eye: V3,
    pub(super) look_at: V3,
    pub(super) up: Option<Spanned<V3>>,
    pub(super) fov: Option<Spanned<Num>>,
    pub(super) height: Option<Spanned<Num>>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
pub(super) struct AmbientDef {
    pub(super) color: Option<Spanned<Rgb>>,
    pub(super) intensity: Option<Spanned<Num>>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
pub(super) struct RenderDef {
    pub(super) max_depth: Option<Spanned<i64>>,
    pub(super) cutoff: Option<Spanned<Num>>,
    pub(super) shadows: Option<bool>,
    pub(super) shadow_mode: Option<Spanned<String>>,
    pub(super) reflections: Option<bool>,
    pub(super) refractions: Option<bool>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
pub(super) struct DepthCueDef {
    pub(super) color: Spanned<Rgb>,
    pub(super) near: Num,
    pub(super) far: Num,
    pub(super) near_scale: Option<Spanned<Num>>,
    pub(super) far_scale: Spanned<Num>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
pub(super) struct LightDef {
    #[serde(rename = "type")]
    pub(super) kind: Spanned<String>,
    pub(super) position: Option<V3>,
    pub(super) direction: Option<V3>,
    pub(super) color: Option<Spanned<Rgb>>,
    pub(super) intensity: Option<Spanned<Num>>,
    pub(super) attenuation: Option<Spanned<String>>,
    pub(super) coefficients: Option<Spanned<V3>>,
    pub(super) enabled: Option<bool>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
pub(super) struct MaterialDef {
    pub(super) color: Spanned<Rgb>,
    pub(super) ka: Option<Spanned<Num>>,
    pub(super) kd: Option<Spanned<Num>>,
    pub(super) ks: Option<Spanned<Num>>,
    pub(super) shininess: Option<Spanned<Num>>,
    pub(super) specular_color: Option<Spanned<Rgb>>,
    pub(super) model: Option<Spanned<String>>,
    pub(super) metallic: Option<Spanned<Rgb>>,
    pub(super) reflect: Option<Spanned<Rgb>>,
    pub(super) transmit: Option<Spanned<Rgb>>,
    pub(super) ior: Option<Spanned<Num>>,
    pub(super) fresnel: Option<bool>,
    pub(super) checker: Option<Spanned<Inline<CheckerDef>>>,
}

/// `checker = { color = …, size = … }` in a material.
#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
pub(super) struct CheckerDef {
    pub(super) color: Spanned<Rgb>,
    pub(super) size: Spanned<Num>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
pub(super) struct ObjectDef {
    #[serde(rename = "type")]
    pub(super) kind: Spanned<String>,
    pub(super) material: Option<Spanned<String>>,
    pub(super) center: Option<V3>,
    pub(super) radius: Option<Spanned<Num>>,
    pub(super) vertices: Option<Spanned<Vec<V3>>>,
    pub(super) normals: Option<Spanned<Vec<V3>>>,
    pub(super) base: Option<V3>,
    pub(super) base_radius: Option<Spanned<Num>>,
    pub(super) apex: Option<V3>,
    pub(super) apex_radius: Option<Spanned<Num>>,
    pub(super) path: Option<Spanned<String>>,
    pub(super) translate: Option<V3>,
    pub(super) rotate: Option<V3>,
    pub(super) scale: Option<Spanned<Scale>>,
    pub(super) matrix: Option<Spanned<Matrix>>,
    pub(super) subdivisions: Option<Spanned<i64>>,
    pub(super) displacement: Option<Spanned<Num>>,
    pub(super) point: Option<V3>,
    pub(super) normal: Option<Spanned<V3>>,
    pub(super) size: Option<Spanned<V2>>,
}
