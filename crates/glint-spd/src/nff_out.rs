//! The NFF side of SPD's output library (libpr1–3, libply): each call prints
//! what the matching `lib_output_*` function prints for `OUTPUT_NFF` with
//! curved primitives, in the same words and number format.

use crate::fmt_g;

/// A point or colour, as SPD's `COORD3`.
pub type Vec3 = [f64; 3];
/// A point with a radius (spheres, cone ends) or a light with an intensity, as SPD's `COORD4`.
pub type Vec4 = [f64; 4];

/// SPD's `EPSILON2`: edges shorter than this make a polygon vertex a duplicate.
const DEGENERATE_EDGE: f64 = 1.0e-6;

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

    fn numbers(&mut self, values: &[f64]) {
        for (i, v) in values.iter().enumerate() {
            if i > 0 {
                self.text.push(' ');
            }
            self.text.push_str(&fmt_g(*v));
        }
    }

    fn line(&mut self, keyword: &str, values: &[f64]) {
        self.text.push_str(keyword);
        if !values.is_empty() {
            self.text.push(' ');
            self.numbers(values);
        }
        self.text.push('\n');
    }

    /// `lib_output_background_color`.
    pub fn background(&mut self, color: Vec3) {
        self.line("b", &color);
    }

    /// `lib_output_viewpoint` (the aspect ratio is not part of NFF).
    #[allow(clippy::too_many_arguments)]
    pub fn viewpoint(&mut self, from: Vec3, at: Vec3, up: Vec3, angle: f64, hither: f64, resx: i32, resy: i32) {
        self.text.push_str("v\n");
        self.line("from", &from);
        self.line("at", &at);
        self.line("up", &up);
        self.line("angle", &[angle]);
        self.line("hither", &[hither]);
        self.text.push_str(&format!("resolution {resx} {resy}\n"));
    }

    /// `lib_output_light` (the intensity in `[3]` is not part of NFF).
    pub fn light(&mut self, center: Vec4) {
        self.line("l", &center[..3]);
    }

    /// `lib_output_color`: the highlight's half angle `ang` (degrees) becomes
    /// the Phong exponent as SPD computes it.
    #[allow(clippy::too_many_arguments)]
    pub fn color(&mut self, color: Vec3, _ka: f64, kd: f64, ks: f64, _ks_spec: f64, ang: f64, kt: f64, ior: f64) {
        let ang_radians = std::f64::consts::PI * ang / 180.0;
        let phong_pow = if ang_radians <= 0.0 {
            100000.0
        } else if ang_radians >= std::f64::consts::PI / 2.0 {
            1.0
        } else {
            0.5f64.ln() / ang_radians.cos().ln()
        };
        self.line("f", &[color[0], color[1], color[2], kd, ks, phong_pow, kt, ior]);
    }

    /// `lib_output_sphere`.
    pub fn sphere(&mut self, center: Vec4) {
        self.line("s", &center);
    }

    /// `lib_output_cylcone`: an open cone or cylinder between two ends, on one line.
    pub fn cylcone(&mut self, base: Vec4, apex: Vec4) {
        self.line("c", &[base[0], base[1], base[2], base[3], apex[0], apex[1], apex[2], apex[3]]);
    }

    /// `lib_output_polygon`: a vertex closer than 1e-6 to the next one (cyclically)
    /// is dropped, and what is left is printed only if it still has three vertices.
    pub fn polygon(&mut self, vertices: &[Vec3]) {
        let mut kept = vertices.to_vec();
        let mut i = 0;
        while i < kept.len() {
            let next = kept[(i + 1) % kept.len()];
            if crate::vecmath::length(crate::vecmath::sub(kept[i], next)) < DEGENERATE_EDGE {
                kept.remove(i);
            } else {
                i += 1;
            }
        }
        if kept.len() < 3 {
            return;
        }
        self.text.push_str(&format!("p {}\n", kept.len()));
        for v in &kept {
            self.line_of(v);
        }
    }

    /// `lib_output_polypatch`: a triangle with a normal per vertex (SPD
    /// splits every larger patch into triangles, so its files hold only these).
    pub fn polypatch(&mut self, vertices: &[Vec3; 3], normals: &[Vec3; 3]) {
        self.text.push_str("pp 3\n");
        for (v, n) in vertices.iter().zip(normals) {
            self.numbers(&[v[0], v[1], v[2], n[0], n[1], n[2]]);
            self.text.push('\n');
        }
    }

    fn line_of(&mut self, v: &Vec3) {
        self.numbers(v);
        self.text.push('\n');
    }
}

/// The text `generate` writes at `size`, for the generators' tests.
#[cfg(test)]
pub fn generated(generate: fn(u32, &mut Nff), size: u32) -> String {
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
