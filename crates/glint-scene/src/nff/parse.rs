//! The NFF reader proper: tokens that remember their line and column, and a
//! parser that turns each statement into lights, materials and objects.

use std::collections::HashMap;
use std::path::Path;

use glam::Vec3;

use super::{fov_y_from_angle, light_intensity, material, NffContents, NffOptions, NffView};
use crate::quoted;
use crate::scene::MAX_IMAGE_SIDE;
use crate::shape::{polygon_normal, ShapeProblem};
use crate::token_reader::{Cursor, Token, TokenReader};
use crate::{Attenuation, Camera, Light, LightKind, LoadError, Material, Object, Projection, Shape};

/// Parses NFF text without requiring a `v` block.
pub fn parse_contents(source: &str, path: &Path, options: &NffOptions) -> Result<NffContents, LoadError> {
    let mut parser = Parser {
        cursor: Cursor::new(source, path, tokenize(source)),
        options,
        contents: NffContents {
            view: None,
            background: None,
            lights: Vec::new(),
            materials: Vec::new(),
            objects: Vec::new(),
            warnings: Vec::new(),
        },
        current_material: None,
        material_ids: HashMap::new(),
        light_specs: Vec::new(),
    };
    parser.run()?;
    let mut contents = parser.contents;
    let intensity = light_intensity(parser.light_specs.len());
    contents.lights = parser
        .light_specs
        .iter()
        .map(|&(position, color)| Light {
            kind: LightKind::Point { position },
            color,
            intensity,
            attenuation: Attenuation::None,
            enabled: true,
        })
        .collect();
    if contents.materials.is_empty() {
        contents.materials.push(default_material());
    }
    Ok(contents)
}

/// What primitives before the first `f` get: white, fully diffuse.
fn default_material() -> Material {
    material("nff default".into(), Vec3::ONE, 1.0, 0.0, 0.0, 0.0, 1.0)
}

fn tokenize(source: &str) -> Vec<Token<'_>> {
    let mut tokens = Vec::with_capacity(source.len() / 6);
    let mut line_start = 0;
    for (index, line) in source.split('\n').enumerate() {
        let code = line.split_once('#').map_or(line, |(code, _)| code);
        let mut rest = code;
        let mut consumed = 0;
        loop {
            let trimmed = rest.trim_start();
            consumed += rest.len() - trimmed.len();
            if trimmed.is_empty() {
                break;
            }
            let end = trimmed.find(char::is_whitespace).unwrap_or(trimmed.len());
            tokens.push(Token { text: &trimmed[..end], offset: line_start + consumed, line: index + 1 });
            consumed += end;
            rest = &trimmed[end..];
        }
        line_start += line.len() + 1;
    }
    tokens
}

const KEYWORDS: &[&str] = &["v", "b", "l", "f", "c", "s", "p", "pp"];

struct Parser<'a> {
    cursor: Cursor<'a>,
    options: &'a NffOptions,
    contents: NffContents,
    current_material: Option<usize>,
    /// Material index by the bits of its `f` operands, so repeated `f` lines share one.
    material_ids: HashMap<[u32; 8], usize>,
    light_specs: Vec<(Vec3, Vec3)>,
}

impl<'a> TokenReader<'a> for Parser<'a> {
    fn cursor(&self) -> &Cursor<'a> {
        &self.cursor
    }

    fn cursor_mut(&mut self) -> &mut Cursor<'a> {
        &mut self.cursor
    }

    fn warnings(&mut self) -> &mut Vec<LoadError> {
        &mut self.contents.warnings
    }

    /// Primitives before the first `f` get the default material.
    fn push(&mut self, shapes: Vec<Shape>) {
        let material = match self.current_material {
            Some(m) => m,
            None => {
                let m = self.contents.materials.len();
                self.contents.materials.push(default_material());
                self.current_material = Some(m);
                m
            }
        };
        self.contents.objects.push(Object { material, shapes });
    }
}

impl<'a> Parser<'a> {
    /// A count of vertices: a whole number, at least `min`.
    fn count(&mut self, what: &str, min: usize) -> Result<usize, LoadError> {
        let t = self.expect(what)?;
        let n: usize = t.text.parse().map_err(|_| {
            self.error(&t, format!("expected a whole number ({what}) for {}, found {}", self.statement_name(), quoted(t.text)))
        })?;
        if n < min {
            return Err(self.error(&t, format!("{what}: needs at least {min}, found {n}")));
        }
        Ok(n)
    }

    fn run(&mut self) -> Result<(), LoadError> {
        while let Some(t) = self.peek() {
            self.cursor.pos += 1;
            if !KEYWORDS.contains(&t.text) {
                let message = if t.text.parse::<f64>().is_ok() {
                    format!("unexpected number {}: too many values for {}", quoted(t.text), self.statement_name())
                } else {
                    format!("unknown keyword {}", quoted(t.text))
                };
                return Err(self.error(&t, message));
            }
            self.cursor.statement = Some(t);
            match t.text {
                "v" => self.view(t)?,
                "b" => {
                    let c = self.color("background")?;
                    self.contents.background = Some(c);
                }
                "l" => self.light()?,
                "f" => self.fill(t)?,
                "s" => self.sphere(t)?,
                "c" => self.cone(t)?,
                "p" => self.polygon(t)?,
                "pp" => self.patch(t)?,
                _ => unreachable!("every keyword is handled"),
            }
        }
        Ok(())
    }

    fn view(&mut self, v: Token<'a>) -> Result<(), LoadError> {
        if self.contents.view.is_some() {
            return Err(self.error(&v, "a second `v` block: an NFF file has one viewpoint"));
        }
        let (mut from, mut at, mut up, mut angle, mut hither, mut resolution) = (None, None, None, None, None, None);
        while let Some(t) = self.peek() {
            let seen = match t.text {
                "from" => from.is_some(),
                "at" => at.is_some(),
                "up" => up.is_some(),
                "angle" => angle.is_some(),
                "hither" => hither.is_some(),
                "resolution" => resolution.is_some(),
                _ => break,
            };
            if seen {
                return Err(self.error(&t, format!("`{}` given twice in the `v` block", t.text)));
            }
            self.cursor.pos += 1;
            self.cursor.statement = Some(t);
            match t.text {
                "from" => from = Some(self.vec3("from")?),
                "at" => at = Some(self.vec3("at")?),
                "up" => up = Some(self.vec3("up")?),
                "angle" => {
                    let a = self.number("angle")?;
                    if !(a > 0.0 && a < 180.0) {
                        let tok = self.cursor.tokens[self.cursor.pos - 1];
                        return Err(self.error(&tok, format!("angle: {a} is not between 0 and 180 degrees")));
                    }
                    if let Some(warning) = crate::camera::radians_warning("angle", a) {
                        let tok = self.cursor.tokens[self.cursor.pos - 1];
                        self.warn(&tok, warning);
                    }
                    angle = Some((a, t));
                }
                "hither" => hither = Some(self.non_negative("hither")?),
                _ => {
                    let side = |parser: &mut Self, what: &str| -> Result<u32, LoadError> {
                        let tok = parser.expect(what)?;
                        tok.text.parse::<u32>().ok().filter(|s| (1..=MAX_IMAGE_SIDE).contains(s)).ok_or_else(|| {
                            parser.error(&tok, format!("resolution: {what} {} is not a whole number in 1..={MAX_IMAGE_SIDE}", quoted(tok.text)))
                        })
                    };
                    let w = side(self, "width")?;
                    let h = side(self, "height")?;
                    resolution = Some((w, h));
                }
            }
        }
        self.cursor.statement = Some(v);
        let missing = |name: &str| self.error(&v, format!("the `v` block has no `{name}`"));
        let from = from.ok_or_else(|| missing("from"))?;
        let at = at.ok_or_else(|| missing("at"))?;
        let up = up.ok_or_else(|| missing("up"))?;
        let (angle, angle_token) = angle.ok_or_else(|| missing("angle"))?;
        let (width, height) = resolution.ok_or_else(|| missing("resolution"))?;
        let fov = fov_y_from_angle(f64::from(angle), height, self.options.angle).ok_or_else(|| {
            self.error(&angle_token, "angle: a one-row image has no distance between its top and bottom pixel centres (read the angle edge to edge instead)")
        })?;
        let camera = Camera { eye: from, look_at: at, up, projection: Projection::Perspective { fov_y_degrees: fov as f32 } };
        if crate::view_overflows(&camera) {
            return Err(self.error(&v, "`from` and `at` are too far apart (the view direction overflows 32-bit floats)"));
        }
        if camera.basis().is_none() {
            return Err(self.error(&v, "`up` is parallel to the view direction (or `from` equals `at`)"));
        }
        self.contents.view = Some(NffView { camera, width, height, hither });
        Ok(())
    }

    fn light(&mut self) -> Result<(), LoadError> {
        let position = self.vec3("light position")?;
        // The colour is optional: it is there when a number follows.
        let has_color = self.peek().is_some_and(|t| !KEYWORDS.contains(&t.text) && t.text.parse::<f64>().is_ok());
        let color = if has_color { self.color("light colour")? } else { Vec3::ONE };
        self.light_specs.push((position, color));
        Ok(())
    }

    fn fill(&mut self, f: Token<'a>) -> Result<(), LoadError> {
        let color = self.color("colour")?;
        let kd = self.non_negative("Kd")?;
        let ks = self.non_negative("Ks")?;
        let shine = self.non_negative("Shine")?;
        let t = self.non_negative("T")?;
        let ior_at = self.cursor.pos;
        let ior = self.number("index of refraction")?;
        if t > 0.0 && ior <= 0.0 {
            let tok = self.cursor.tokens[ior_at];
            return Err(self.error(&tok, format!("index of refraction must be positive for a transmissive material, found {ior}")));
        }
        let key = [color.x, color.y, color.z, kd, ks, shine, t, ior].map(f32::to_bits);
        let index = match self.material_ids.get(&key) {
            Some(&i) => i,
            None => {
                let i = self.contents.materials.len();
                self.contents.materials.push(material(format!("f line {}", f.line), color, kd, ks, shine, t, ior));
                self.material_ids.insert(key, i);
                i
            }
        };
        self.current_material = Some(index);
        Ok(())
    }

    fn sphere(&mut self, s: Token<'a>) -> Result<(), LoadError> {
        let center = self.vec3("centre")?;
        let radius = self.non_negative("radius")?;
        self.push_built(&s, Shape::sphere(center, radius))
    }

    fn cone(&mut self, c: Token<'a>) -> Result<(), LoadError> {
        let base = self.vec3("base")?;
        let base_radius = self.non_negative("base radius")?;
        let apex = self.vec3("apex")?;
        let apex_radius = self.non_negative("apex radius")?;
        self.push_built(&c, Shape::cone(base, base_radius, apex, apex_radius))
    }

    fn polygon(&mut self, p: Token<'a>) -> Result<(), LoadError> {
        let n = self.count("vertex count", 3)?;
        let mut vertices = Vec::with_capacity(n.min(self.cursor.tokens.len() / 3));
        for i in 0..n {
            vertices.push(self.vec3(&format!("vertex {}", i + 1))?);
        }
        self.push_polygon(&p, vertices)
    }

    fn patch(&mut self, pp: Token<'a>) -> Result<(), LoadError> {
        let n = self.count("vertex count", 3)?;
        let mut vertices = Vec::with_capacity(n.min(self.cursor.tokens.len() / 6));
        let mut normals = Vec::with_capacity(vertices.capacity());
        for i in 0..n {
            vertices.push(self.vec3(&format!("vertex {}", i + 1))?);
            normals.push(self.vec3(&format!("normal {}", i + 1))?);
        }
        if polygon_normal(&vertices).is_none() {
            self.warn(&pp, format!("degenerate patch ({n} vertices, no area) skipped"));
            return Ok(());
        }
        let units: Option<Vec<Vec3>> = normals.iter().map(|n| crate::unit(*n)).collect();
        let smooth = units.is_some();
        if !smooth {
            self.warn(&pp, "patch has a zero-length vertex normal; shaded flat");
        }
        let normals = units.unwrap_or_default();
        let mut shapes = Vec::with_capacity(n - 2);
        for i in 1..n - 1 {
            let tri = [vertices[0], vertices[i], vertices[i + 1]];
            let normals = smooth.then(|| [normals[0], normals[i], normals[i + 1]]);
            match Shape::triangle(tri, normals) {
                Ok(triangle) => shapes.push(triangle),
                // A fan over a convex patch with collinear neighbours has slivers of no area.
                Err(ShapeProblem::Degenerate(_)) => {}
                Err(ShapeProblem::Overflows) => return Err(self.overflow(&pp)),
            }
        }
        if shapes.is_empty() {
            // Only possible at the edge of the area test: the whole has an area, no fan triangle has.
            self.warn(&pp, format!("degenerate patch ({n} vertices, no triangle with an area) skipped"));
            return Ok(());
        }
        self.push(shapes);
        Ok(())
    }
}
