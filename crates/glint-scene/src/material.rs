use glam::Vec3;

#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum SpecularModel {
    /// k_s·I·(R·V)^n
    Phong,
    /// k_s·I·(N·H)^n
    BlinnPhong,
}

/// The Whitted material: Phong terms plus mirror reflection and refraction.
#[derive(Debug, Clone, PartialEq)]
pub struct Material {
    pub name: String,
    /// k_a
    pub ambient: f32,
    /// k_d
    pub diffuse: f32,
    /// k_s
    pub specular: f32,
    /// Phong exponent n
    pub shininess: f32,
    /// O_d
    pub color: Vec3,
    /// O_s; `None` gives white highlights.
    pub specular_color: Option<Vec3>,
    pub specular_model: SpecularModel,
    /// Schlick F0 for metallic highlights: the highlight colour becomes
    /// F0 + (1 − F0)(1 − V·H)^5 in place of k_s·O_s.
    pub metallic_f0: Option<Vec3>,
    /// k_m: how much of the mirror ray is added.
    pub reflect: Vec3,
    /// k_t: how much of the refracted ray is added; also tints shadows in tinted mode.
    pub transmit: Vec3,
    /// Index of refraction of the material (the outside is air, 1.0).
    pub ior: f32,
    /// Weight reflection and refraction by Schlick's Fresnel term.
    pub fresnel: bool,
    /// A checkerboard of O_d: `color` and the checker's colour in alternate tiles.
    pub checker: Option<Checker>,
}

/// Whitted's checkerboard, on any material: at each hit, O_d is the
/// material's `color` on even tiles and `color` here on odd ones. Tiles have
/// side `size` and a corner at the world origin: squares in the plane's own
/// coordinates on planes and polygons, cubes (a solid checker) on other
/// shapes (docs/scene-format.md, `checker`).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Checker {
    /// O_d of the odd tiles.
    pub color: Vec3,
    /// The side of a tile, > 0.
    pub size: f32,
}

impl Default for Material {
    fn default() -> Self {
        Self {
            name: "default".into(),
            ambient: 0.1,
            diffuse: 0.8,
            specular: 0.2,
            shininess: 32.0,
            color: Vec3::splat(0.8),
            specular_color: None,
            specular_model: SpecularModel::BlinnPhong,
            metallic_f0: None,
            reflect: Vec3::ZERO,
            transmit: Vec3::ZERO,
            ior: 1.0,
            fresnel: false,
            checker: None,
        }
    }
}

impl Material {
    pub fn is_transmissive(&self) -> bool {
        self.transmit.max_element() > 0.0
    }
}
