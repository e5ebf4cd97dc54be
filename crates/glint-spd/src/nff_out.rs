//! The NFF side of SPD's output library (libpr1–3, libply): each call prints
//! what the matching `lib_output_*` function prints for `OUTPUT_NFF` with
//! curved primitives, in the same words and number format.

use crate::output::{phong_pow, push_numbers, Output};
use crate::vecmath::{Vec3, Vec4};

/// NFF text under construction.
#[derive(Default)]
pub struct Nff {
    text: String,
}

impl Nff {
    pub fn new() -> Self {
        Self::default()
    }

    pub fn finish(self) -> String {
        self.text
    }

    fn line(&mut self, keyword: &str, values: &[f64]) {
        self.text.push_str(keyword);
        if !values.is_empty() {
            self.text.push(' ');
            push_numbers(&mut self.text, values);
        }
        self.text.push('\n');
    }

    fn line_of(&mut self, values: &[f64]) {
        push_numbers(&mut self.text, values);
        self.text.push('\n');
    }
}

impl Output for Nff {
    /// NFF has no light intensity: SPD gives its tracers 1 and lets them scale.
    fn light_scale(&self, _lights: u32) -> f64 {
        1.0
    }

    fn background(&mut self, color: Vec3) {
        self.line("b", &color);
    }

    fn viewpoint(&mut self, from: Vec3, at: Vec3, up: Vec3, angle: f64, hither: f64, resx: i32, resy: i32) {
        self.text.push_str("v\n");
        self.line("from", &from);
        self.line("at", &at);
        self.line("up", &up);
        self.line("angle", &[angle]);
        self.line("hither", &[hither]);
        self.text.push_str(&format!("resolution {resx} {resy}\n"));
    }

    /// The intensity in `[3]` is not part of NFF.
    fn light(&mut self, center: Vec4) {
        self.line("l", &center[..3]);
    }

    /// The highlight's half angle `ang` becomes the Phong exponent; `ka` and
    /// `ks_spec` are not part of NFF.
    fn color(&mut self, color: Vec3, _ka: f64, kd: f64, ks: f64, _ks_spec: f64, ang: f64, kt: f64, ior: f64) {
        self.line("f", &[color[0], color[1], color[2], kd, ks, phong_pow(ang), kt, ior]);
    }

    fn sphere(&mut self, center: Vec4) {
        self.line("s", &center);
    }

    /// On one line.
    fn cylcone(&mut self, base: Vec4, apex: Vec4) {
        self.line("c", &[base[0], base[1], base[2], base[3], apex[0], apex[1], apex[2], apex[3]]);
    }

    fn polygon_kept(&mut self, vertices: &[Vec3]) {
        self.text.push_str(&format!("p {}\n", vertices.len()));
        for v in vertices {
            self.line_of(v);
        }
    }

    fn polypatch(&mut self, vertices: &[Vec3; 3], normals: &[Vec3; 3]) {
        self.text.push_str("pp 3\n");
        for (v, n) in vertices.iter().zip(normals) {
            self.line_of(&[v[0], v[1], v[2], n[0], n[1], n[2]]);
        }
    }
}

/// The text `generate` writes at `size`, for the generators' tests.
#[cfg(test)]
pub fn generated(generate: fn(u32, &mut dyn Output), size: u32) -> String {
    let mut out = Nff::new();
    generate(size, &mut out);
    out.finish()
}

/// How many lines of `text` start with `keyword`, for the generators' tests.
#[cfg(test)]
pub fn count(text: &str, keyword: &str) -> usize {
    text.lines().filter(|line| line.split(' ').next() == Some(keyword)).count()
}

/// How many of each primitive a generated scene holds, for the generators' tests.
#[cfg(test)]
#[derive(Debug, PartialEq, Eq, Default)]
pub struct Counts {
    pub spheres: usize,
    pub cones: usize,
    pub polygons: usize,
    pub patches: usize,
    pub lights: usize,
}

#[cfg(test)]
impl Counts {
    pub fn of(text: &str) -> Self {
        Counts {
            spheres: count(text, "s"),
            cones: count(text, "c"),
            polygons: count(text, "p"),
            patches: count(text, "pp"),
            lights: count(text, "l"),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::{Counts, Nff};
    use crate::output::Output;

    #[test]
    fn polygon_drops_repeated_vertices_like_spd() {
        let mut out = Nff::new();
        out.polygon(&[[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1e-9]]);
        out.polygon(&[[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [1.0, 0.0, 0.0]]);
        assert_eq!(out.finish(), "p 3\n0 0 0\n1 0 0\n0 1 0\n");
    }

    #[test]
    fn counts_primitives_by_keyword() {
        let counts = Counts::of("l 1 2 3\np 3\n0 0 0\npp 3\ns 0 0 0 1\nc 0 0 0 1 1 1 1 1\n");
        assert_eq!(counts, Counts { spheres: 1, cones: 1, polygons: 1, patches: 1, lights: 1 });
    }
}
