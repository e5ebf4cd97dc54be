//! Turning the tables of a TOML scene into the scene model: the image, camera,
//! render settings, depth cue, lights and materials, with every error and
//! warning at the position of the value it is about. Objects are built in
//! `object`, meshes and includes in `mesh`.

use std::cell::RefCell;
use std::collections::BTreeMap;
use std::path::Path;

use glam::Vec3;
use toml::Spanned;

use super::{colour_warning, looks_like_0_to_255, short_vector as vector};
use super::defs::{CameraDef, CheckerDef, DepthCueDef, FileDef, ImageDef, LightDef, MaterialDef, RenderDef};
use super::mesh::Meshes;
use crate::camera::radians_warning;
use super::values::{Num, Rgb};
use crate::scene::{MAX_DEPTH_LIMIT, MAX_IMAGE_SIDE};
use crate::{
    Attenuation, Camera, Checker, DepthCue, Light, LightKind, LoadError, Location, Material, Projection, RenderSettings,
    Scene, ShadowMode, SpecularModel,
};

pub(super) struct Builder<'a> {
    pub(super) source: &'a str,
    pub(super) path: &'a Path,
    /// Problems in this file that do not stop loading, with their offsets.
    pub(super) warnings: RefCell<Vec<(usize, LoadError)>>,
    /// The colours written 0 to 255 warned about so far: each is named once,
    /// however often it is written.
    pub(super) colours_0_to_255: RefCell<Vec<Vec3>>,
}

impl Builder<'_> {
    pub(super) fn error_at<T>(&self, spanned: &Spanned<T>, message: impl Into<String>) -> LoadError {
        self.error_at_offset(spanned.span().start, message)
    }

    /// An error at byte `offset` of the file.
    pub(super) fn error_at_offset(&self, offset: usize, message: impl Into<String>) -> LoadError {
        LoadError::new(self.path, Some(Location::of_offset(self.source, offset)), message)
    }

    pub(super) fn warn_at<T>(&self, spanned: &Spanned<T>, message: impl Into<String>) {
        self.warn_at_offset(spanned.span().start, message);
    }

    /// A warning at byte `offset` of the file.
    pub(super) fn warn_at_offset(&self, offset: usize, message: impl Into<String>) {
        let warning = LoadError::new(self.path, Some(Location::of_offset(self.source, offset)), message);
        self.warnings.borrow_mut().push((offset, warning));
    }

    /// A colour's value, with a warning when it is out of its usual range
    /// (see [`colour_warning`]).
    pub(super) fn colour(&self, c: &Spanned<Rgb>, key: &str, reflectance: bool) -> Vec3 {
        let value = c.get_ref().0;
        if let Some(warning) = colour_warning(key, value, reflectance) {
            if looks_like_0_to_255(value) {
                if self.colours_0_to_255.borrow().contains(&value) {
                    return value;
                }
                self.colours_0_to_255.borrow_mut().push(value);
            }
            self.warn_at(c, warning);
        }
        value
    }

    pub(super) fn optional_colour(&self, c: &Option<Spanned<Rgb>>, key: &str, reflectance: bool) -> Option<Vec3> {
        c.as_ref().map(|c| self.colour(c, key, reflectance))
    }

    /// A number that must lie in `range`, reported at its own position.
    pub(super) fn ranged(&self, v: &Option<Spanned<Num>>, key: &str, default: f32, lo: f32, hi: f32) -> Result<f32, LoadError> {
        match v {
            None => Ok(default),
            Some(s) if (lo..=hi).contains(&s.get_ref().0) => Ok(s.get_ref().0),
            Some(s) => Err(self.error_at(s, format!("{key}: {} is outside {lo}..={hi}", s.get_ref().0))),
        }
    }

    pub(super) fn build(&self, file: FileDef) -> Result<Scene, LoadError> {
        let (width, height, background) = self.image(&file.image)?;
        let camera = self.camera(&file.camera)?;
        let ambient = match &file.ambient {
            None => Vec3::ZERO,
            Some(a) => {
                let ambient = self.optional_colour(&a.color, "color", false).unwrap_or(Vec3::ONE) * self.ranged(&a.intensity, "intensity", 1.0, 0.0, f32::MAX)?;
                self.no_overflow(&a.intensity, ambient)?
            }
        };
        let render = match &file.render {
            None => RenderSettings::default(),
            Some(r) => self.render(r.get_ref())?,
        };
        let depth_cue = file.depth_cue.as_ref().map(|d| self.depth_cue(d)).transpose()?;
        let mut lights: Vec<Light> = file.light.iter().map(|l| self.light(l)).collect::<Result<_, _>>()?;

        let mut materials = vec![Material::default()];
        let mut names = BTreeMap::new();
        for (name, def) in &file.material {
            names.insert(name.as_str(), materials.len());
            materials.push(self.material(name, def.get_ref())?);
        }
        // Only the file's own [[light]]s are keyed: included lights come later.
        let animation = file.animation.as_ref().map(|a| self.animation(a, &camera, &lights)).transpose()?;
        let mut meshes = Meshes::default();
        let mut objects = Vec::with_capacity(file.object.len());
        for o in &file.object {
            self.object(o, &names, &mut materials, &mut meshes, &mut objects)?;
        }
        // This file's own warnings in file order, then those of the files it names.
        let mut warnings: Vec<(usize, LoadError)> = self.warnings.take();
        warnings.sort_by_key(|(offset, _)| *offset);
        let mut warnings: Vec<LoadError> = warnings.into_iter().map(|(_, w)| w).chain(meshes.warnings).collect();
        for include in &file.include {
            self.include(include, &mut materials, &mut objects, &mut lights, &mut warnings)?;
        }

        Ok(Scene { width, height, background, camera, ambient, lights, materials, objects, depth_cue, render, animation, warnings })
    }

    fn image(&self, image: &Spanned<ImageDef>) -> Result<(u32, u32, Vec3), LoadError> {
        let def = image.get_ref();
        let side = |v: &Spanned<i64>, key: &str| {
            u32::try_from(*v.get_ref())
                .ok()
                .filter(|s| (1..=MAX_IMAGE_SIDE).contains(s))
                .ok_or_else(|| self.error_at(v, format!("{key}: {} is outside 1..={MAX_IMAGE_SIDE}", v.get_ref())))
        };
        let background = self.optional_colour(&def.background, "background", false).unwrap_or(Vec3::ZERO);
        Ok((side(&def.width, "width")?, side(&def.height, "height")?, background))
    }

    fn camera(&self, camera: &Spanned<CameraDef>) -> Result<Camera, LoadError> {
        let def = camera.get_ref();
        let kind = def.kind.as_ref().map_or("perspective", |k| k.get_ref().as_str());
        let projection = match kind {
            "perspective" => {
                if let Some(h) = &def.height {
                    return Err(self.error_at(h, "height: only an orthographic camera has a view-plane height"));
                }
                let fov = def.fov.as_ref().ok_or_else(|| self.error_at(camera, "camera: missing field `fov`"))?;
                Projection::Perspective { fov_y_degrees: self.fov(fov)? }
            }
            "orthographic" => {
                if let Some(f) = &def.fov {
                    return Err(self.error_at(f, "fov: an orthographic camera has a view-plane `height`, not a field of view"));
                }
                let h = def.height.as_ref().ok_or_else(|| self.error_at(camera, "camera: missing field `height`"))?;
                Projection::Orthographic { height: self.view_height(h)? }
            }
            other => {
                let k = def.kind.as_ref().expect("a non-default kind was written");
                return Err(self.error_at(k, format!("type: unknown camera type `{other}`, expected `perspective` or `orthographic`")));
            }
        };
        let camera_value = Camera { eye: def.eye.0, look_at: def.look_at.0, up: def.up.as_ref().map_or(Vec3::Y, |u| u.get_ref().0), projection };
        if crate::view_overflows(&camera_value) {
            return Err(self.error_at(camera, "camera: eye and look_at are too far apart (the view direction overflows 32-bit floats)"));
        }
        if camera_value.basis().is_none() {
            let view = camera_value.look_at - camera_value.eye;
            if view == Vec3::ZERO {
                return Err(self.error_at(camera, "camera: eye and look_at are the same point, so the camera looks nowhere"));
            }
            let try_up = crate::camera::suggested_up(view);
            let (v, t) = (vector(view.normalize()), vector(try_up));
            return Err(match &def.up {
                Some(up) => self.error_at(up, format!("up: {} is parallel to the view direction {v}, from eye to look_at; try up = {t}", vector(up.get_ref().0))),
                None => self.error_at(
                    camera,
                    format!("camera: `up` is not set, and its default [0, 1, 0] is parallel to the view direction {v}, from eye to look_at; add up = {t}"),
                ),
            });
        }
        Ok(camera_value)
    }

    /// A perspective camera's vertical field of view, in degrees.
    pub(super) fn fov(&self, fov: &Spanned<Num>) -> Result<f32, LoadError> {
        let degrees = fov.get_ref().0;
        if !(degrees > 0.0 && degrees < 180.0) {
            return Err(self.error_at(fov, format!("fov: {degrees} is not between 0 and 180 degrees")));
        }
        if let Some(warning) = radians_warning("fov", degrees) {
            self.warn_at(fov, warning);
        }
        Ok(degrees)
    }

    /// An orthographic camera's view-plane height.
    pub(super) fn view_height(&self, height: &Spanned<Num>) -> Result<f32, LoadError> {
        if height.get_ref().0 <= 0.0 {
            return Err(self.error_at(height, "height: must be positive"));
        }
        Ok(height.get_ref().0)
    }

    fn render(&self, def: &RenderDef) -> Result<RenderSettings, LoadError> {
        let d = RenderSettings::default();
        let max_depth = match &def.max_depth {
            None => d.max_depth,
            Some(v) => u32::try_from(*v.get_ref())
                .ok()
                .filter(|m| (1..=MAX_DEPTH_LIMIT).contains(m))
                .ok_or_else(|| self.error_at(v, format!("max_depth: {} is outside 1..={MAX_DEPTH_LIMIT}", v.get_ref())))?,
        };
        let shadow_mode = match def.shadow_mode.as_ref() {
            None => d.shadow_mode,
            Some(m) => match m.get_ref().as_str() {
                "opaque" => ShadowMode::Opaque,
                "tinted" => ShadowMode::Tinted,
                other => return Err(self.error_at(m, format!("shadow_mode: unknown mode `{other}`, expected `opaque` or `tinted`"))),
            },
        };
        Ok(RenderSettings {
            max_depth,
            cutoff: self.ranged(&def.cutoff, "cutoff", d.cutoff, 0.0, 1.0)?,
            shadows: def.shadows.unwrap_or(d.shadows),
            shadow_mode,
            reflections: def.reflections.unwrap_or(d.reflections),
            refractions: def.refractions.unwrap_or(d.refractions),
            ..d
        })
    }

    fn depth_cue(&self, cue: &Spanned<DepthCueDef>) -> Result<DepthCue, LoadError> {
        let def = cue.get_ref();
        if def.far.0 <= def.near.0 {
            return Err(self.error_at(cue, "depth_cue: `far` must be greater than `near`"));
        }
        Ok(DepthCue {
            color: self.colour(&def.color, "color", false),
            near: def.near.0,
            far: def.far.0,
            near_scale: self.ranged(&def.near_scale, "near_scale", 1.0, 0.0, 1.0)?,
            far_scale: self.ranged(&Some(def.far_scale.clone()), "far_scale", 0.0, 0.0, 1.0)?,
        })
    }

    fn light(&self, light: &Spanned<LightDef>) -> Result<Light, LoadError> {
        let def = light.get_ref();
        let kind = match def.kind.get_ref().as_str() {
            "point" => {
                if def.direction.is_some() {
                    return Err(self.error_at(light, "light: a point light has a `position`, not a `direction`"));
                }
                let p = def.position.ok_or_else(|| self.error_at(light, "light: missing field `position`"))?;
                LightKind::Point { position: p.0 }
            }
            "directional" => {
                if def.position.is_some() {
                    return Err(self.error_at(light, "light: a directional light has a `direction`, not a `position`"));
                }
                let d = def.direction.ok_or_else(|| self.error_at(light, "light: missing field `direction`"))?;
                let direction = crate::unit(d.0).ok_or_else(|| self.error_at(light, "direction: must not be zero"))?;
                LightKind::Directional { direction }
            }
            other => return Err(self.error_at(&def.kind, format!("type: unknown light type `{other}`, expected `point` or `directional`"))),
        };
        let attenuation = match def.attenuation.as_ref().map(|a| a.get_ref().as_str()) {
            None | Some("none") => Attenuation::None,
            Some("inverse_square") => Attenuation::InverseSquare,
            Some("polynomial") => {
                let c = def.coefficients.as_ref().ok_or_else(|| {
                    self.error_at(light, "light: polynomial attenuation needs `coefficients = [c1, c2, c3]`")
                })?;
                let v = c.get_ref().0;
                if v.min_element() < 0.0 || v.max_element() <= 0.0 {
                    return Err(self.error_at(c, "coefficients: must be non-negative and not all zero"));
                }
                Attenuation::Polynomial { c1: v.x, c2: v.y, c3: v.z }
            }
            Some(other) => {
                let a = def.attenuation.as_ref().expect("matched Some");
                return Err(self.error_at(a, format!("attenuation: unknown form `{other}`, expected `none`, `inverse_square` or `polynomial`")));
            }
        };
        if let (LightKind::Directional { .. }, Some(a)) = (kind, &def.attenuation) {
            return Err(self.error_at(a, "attenuation: a directional light has no distance to attenuate over"));
        }
        if let (Some(c), Attenuation::None | Attenuation::InverseSquare) = (&def.coefficients, attenuation) {
            return Err(self.error_at(c, "coefficients: only polynomial attenuation takes coefficients"));
        }
        let color = self.optional_colour(&def.color, "color", false).unwrap_or(Vec3::ONE);
        let intensity = self.ranged(&def.intensity, "intensity", 1.0, 0.0, f32::MAX)?;
        self.no_overflow(&def.intensity, color * intensity)?;
        Ok(Light { kind, color, intensity, attenuation, enabled: def.enabled.unwrap_or(true) })
    }

    /// `light` (a colour times `intensity`) when it is finite: the product of
    /// two finite numbers can overflow 32-bit floats.
    pub(super) fn no_overflow(&self, intensity: &Option<Spanned<Num>>, light: Vec3) -> Result<Vec3, LoadError> {
        match intensity {
            Some(i) if !light.is_finite() => {
                Err(self.error_at(i, "intensity: the colour times the intensity overflows 32-bit floats"))
            }
            _ => Ok(light),
        }
    }

    fn material(&self, name: &str, def: &MaterialDef) -> Result<Material, LoadError> {
        let d = Material::default();
        let specular_model = match def.model.as_ref() {
            None => d.specular_model,
            Some(m) => match m.get_ref().as_str() {
                "phong" => SpecularModel::Phong,
                "blinn" => SpecularModel::BlinnPhong,
                other => return Err(self.error_at(m, format!("model: unknown specular model `{other}`, expected `phong` or `blinn`"))),
            },
        };
        Ok(Material {
            name: name.to_string(),
            ambient: self.ranged(&def.ka, "ka", d.ambient, 0.0, f32::MAX)?,
            diffuse: self.ranged(&def.kd, "kd", d.diffuse, 0.0, f32::MAX)?,
            specular: self.ranged(&def.ks, "ks", d.specular, 0.0, f32::MAX)?,
            shininess: self.ranged(&def.shininess, "shininess", d.shininess, 0.0, 1e6)?,
            color: self.colour(&def.color, "color", true),
            specular_color: self.optional_colour(&def.specular_color, "specular_color", true),
            specular_model,
            metallic_f0: self.optional_colour(&def.metallic, "metallic", true),
            reflect: self.optional_colour(&def.reflect, "reflect", true).unwrap_or(Vec3::ZERO),
            transmit: self.optional_colour(&def.transmit, "transmit", true).unwrap_or(Vec3::ZERO),
            ior: self.ranged(&def.ior, "ior", 1.0, 0.01, 100.0)?,
            fresnel: def.fresnel.unwrap_or(false),
            checker: def.checker.as_ref().map(|c| self.checker(&c.get_ref().0)).transpose()?,
        })
    }

    fn checker(&self, def: &CheckerDef) -> Result<Checker, LoadError> {
        let size = def.size.get_ref().0;
        if size <= 0.0 {
            return Err(self.error_at(&def.size, format!("size: a checker's tiles must be larger than 0, found {size}")));
        }
        Ok(Checker { color: self.colour(&def.color, "color", true), size })
    }
}
