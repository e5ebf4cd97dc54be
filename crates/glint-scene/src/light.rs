use glam::Vec3;

#[derive(Debug, Clone, Copy, PartialEq)]
pub enum LightKind {
    Point { position: Vec3 },
    /// `direction` is the way the light travels (from the light into the scene).
    Directional { direction: Vec3 },
}

/// How a point light's intensity falls off with distance d.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Attenuation {
    None,
    /// 1 / d²
    InverseSquare,
    /// min(1 / (c1 + c2·d + c3·d²), 1)
    Polynomial { c1: f32, c2: f32, c3: f32 },
}

impl Attenuation {
    /// The factor at distance `d`.
    pub fn factor(&self, d: f64) -> f64 {
        match *self {
            Attenuation::None => 1.0,
            Attenuation::InverseSquare => 1.0 / (d * d),
            Attenuation::Polynomial { c1, c2, c3 } => {
                let denom = f64::from(c1) + f64::from(c2) * d + f64::from(c3) * d * d;
                (1.0 / denom).min(1.0)
            }
        }
    }
}

#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Light {
    pub kind: LightKind,
    pub color: Vec3,
    pub intensity: f32,
    pub attenuation: Attenuation,
    pub enabled: bool,
}

impl Light {
    /// I_l: colour times intensity, or black when switched off.
    pub fn radiance(&self) -> Vec3 {
        if self.enabled { self.color * self.intensity } else { Vec3::ZERO }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn attenuation_forms() {
        assert_eq!(Attenuation::None.factor(7.0), 1.0);
        assert_eq!(Attenuation::InverseSquare.factor(2.0), 0.25);
        let p = Attenuation::Polynomial { c1: 1.0, c2: 0.5, c3: 0.25 };
        assert_eq!(p.factor(2.0), 1.0 / 3.0);
        let clamped = Attenuation::Polynomial { c1: 0.1, c2: 0.0, c3: 0.0 };
        assert_eq!(clamped.factor(5.0), 1.0, "min(…, 1) caps the gain");
    }
}
