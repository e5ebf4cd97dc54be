//! The Rayshade side of SPD's output library (libpr1–3, libply): each call
//! prints what the matching `lib_output_*` function prints for
//! `OUTPUT_RAYSHADE` (`-r 8`), in the same words, spacing and number format.

use crate::output::{phong_pow, push_numbers, Output};
use crate::vecmath::{Vec3, Vec4};

/// Rayshade text under construction.
#[derive(Default)]
pub struct Rayshade {
    text: String,
    /// SPD's `gTexture_count`: how many surfaces have been written.
    surfaces: u32,
    /// The surface the objects that follow name, once there is one.
    surface: Option<String>,
}

impl Rayshade {
    pub fn new() -> Self {
        Self::default()
    }

    pub fn finish(self) -> String {
        self.text
    }

    fn numbers(&mut self, values: &[f64]) {
        push_numbers(&mut self.text, values);
    }

    /// `keyword`, then the current surface's name and a space, as every
    /// primitive starts.
    fn primitive(&mut self, keyword: &str) {
        self.text.push_str(keyword);
        self.text.push(' ');
        if let Some(name) = &self.surface {
            self.text.push_str(name);
            self.text.push(' ');
        }
    }
}

/// SPD's `create_surface_name`: `txt%03d` into a buffer of 7 bytes, so a
/// thousandth surface loses its last digit as `snprintf` cuts it.
fn surface_name(count: u32) -> String {
    let mut name = format!("txt{count:03}");
    name.truncate(6);
    name
}

impl Output for Rayshade {
    /// Rayshade does not scale intensities, so SPD divides them by √n.
    fn light_scale(&self, lights: u32) -> f64 {
        1.0 / f64::from(lights).sqrt()
    }

    fn background(&mut self, color: Vec3) {
        self.text.push_str("background ");
        self.numbers(&color);
        self.text.push('\n');
    }

    /// `fov` is the horizontal angle (aspect ratio × angle, with SPD's aspect
    /// of 1) and the vertical one; `hither` is not part of Rayshade's view.
    fn viewpoint(&mut self, from: Vec3, at: Vec3, up: Vec3, angle: f64, _hither: f64, resx: i32, resy: i32) {
        for (keyword, v) in [("eyep", from), ("lookp", at), ("up", up)] {
            self.text.push_str(keyword);
            self.text.push(' ');
            self.numbers(&v);
            self.text.push('\n');
        }
        self.text.push_str("fov ");
        self.numbers(&[angle, angle]);
        self.text.push_str(&format!("\nscreen {resx} {resy}\nsample 1 nojitter\n"));
    }

    /// An intensity of 0 means 1, as `lib_output_light` reads it.
    fn light(&mut self, center: Vec4) {
        let intensity = if center[3] != 0.0 { center[3] } else { 1.0 };
        self.text.push_str("light ");
        self.numbers(&[intensity]);
        self.text.push_str(" point ");
        self.numbers(&center[..3]);
        self.text.push('\n');
    }

    /// A named surface: ambient and diffuse are the colour scaled by `ka` and
    /// `kd`; highlights only when `ks_spec` is set; a mirror (`ks`) without
    /// highlights gets a white specular colour, which Rayshade's reflection
    /// is scaled by, and a highlight exponent of 0, which turns highlights off.
    fn color(&mut self, color: Vec3, ka: f64, kd: f64, ks: f64, ks_spec: f64, ang: f64, kt: f64, ior: f64) {
        self.surfaces += 1;
        let name = surface_name(self.surfaces);
        self.text.push_str(&format!("surface {name}\n"));
        let component = |text: &mut String, keyword: &str, values: &[f64]| {
            text.push_str("    ");
            text.push_str(keyword);
            text.push(' ');
            push_numbers(text, values);
            text.push('\n');
        };
        component(&mut self.text, "ambient", &color.map(|c| ka * c));
        component(&mut self.text, "diffuse", &color.map(|c| kd * c));
        if ks_spec != 0.0 {
            component(&mut self.text, "specular", &[ks_spec; 3]);
            component(&mut self.text, "specpow", &[phong_pow(ang)]);
        }
        if ks != 0.0 {
            if ks_spec == 0.0 {
                self.text.push_str("    specular 1.0 1.0 1.0\n    specpow 0.0\n");
            }
            component(&mut self.text, "reflect", &[ks]);
        }
        if kt != 0.0 {
            self.text.push_str("    transp ");
            self.numbers(&[kt]);
            self.text.push_str(" index ");
            self.numbers(&[ior]);
            self.text.push('\n');
        }
        self.surface = Some(name);
    }

    /// Radius first, then the centre, with SPD's doubled and trailing spaces.
    fn sphere(&mut self, center: Vec4) {
        self.primitive("sphere");
        self.text.push(' ');
        self.numbers(&[center[3], center[0], center[1], center[2]]);
        self.text.push_str(" \n");
    }

    /// Each end as radius, then centre.
    fn cylcone(&mut self, base: Vec4, apex: Vec4) {
        self.primitive("cone");
        self.text.push(' ');
        self.numbers(&[base[3], base[0], base[1], base[2], apex[3], apex[0], apex[1], apex[2]]);
        self.text.push('\n');
    }

    /// Three vertices to a line, each followed by a space.
    fn polygon_kept(&mut self, vertices: &[Vec3]) {
        self.primitive("polygon");
        for (i, v) in vertices.iter().enumerate() {
            if i % 3 == 0 {
                self.text.push('\n');
            }
            self.numbers(v);
            self.text.push(' ');
        }
        self.text.push('\n');
    }

    /// A Phong triangle: each vertex followed by its normal.
    fn polypatch(&mut self, vertices: &[Vec3; 3], normals: &[Vec3; 3]) {
        self.primitive("triangle");
        for (v, n) in vertices.iter().zip(normals) {
            self.numbers(v);
            self.text.push(' ');
            self.numbers(n);
            self.text.push(' ');
        }
        self.text.push('\n');
    }
}

#[cfg(test)]
mod tests {
    use super::{surface_name, Rayshade};
    use crate::output::Output;

    #[test]
    fn writes_spd_spacing() {
        let mut out = Rayshade::new();
        out.sphere([0.0, 0.0, 0.0, 1.0]);
        out.color([1.0, 0.5, 0.25], 0.2, 0.8, 0.5, 0.0, 0.0, 0.9, 1.5);
        out.sphere([1.0, 2.0, 3.0, 0.5]);
        out.cylcone([0.0, 0.0, 0.0, 1.0], [0.0, 0.0, 1.0, 0.5]);
        out.polygon(&[[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [1.0, 1.0, 0.0], [0.0, 1.0, 0.0]]);
        let want = "sphere  1 0 0 0 \n\
                    surface txt001\n    ambient 0.2 0.1 0.05\n    diffuse 0.8 0.4 0.2\n\
                    \x20   specular 1.0 1.0 1.0\n    specpow 0.0\n    reflect 0.5\n    transp 0.9 index 1.5\n\
                    sphere txt001  0.5 1 2 3 \n\
                    cone txt001  1 0 0 0 0.5 0 0 1\n\
                    polygon txt001 \n0 0 0 1 0 0 1 1 0 \n0 1 0 \n";
        assert_eq!(out.finish(), want);
    }

    #[test]
    fn lights_share_one_over_root_n() {
        let mut out = Rayshade::new();
        let scale = out.light_scale(4);
        out.light([1.0, 2.0, 3.0, scale]);
        out.light([1.0, 2.0, 3.0, 0.0]);
        assert_eq!(out.finish(), "light 0.5 point 1 2 3\nlight 1 point 1 2 3\n");
    }

    #[test]
    fn surface_names_are_cut_to_six_characters() {
        assert_eq!(surface_name(7), "txt007");
        assert_eq!(surface_name(1234), "txt123");
    }
}
