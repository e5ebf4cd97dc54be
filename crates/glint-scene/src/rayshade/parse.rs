//! The Rayshade reader proper: tokens that remember where they are, and a
//! parser that turns each statement into the camera, lights, surfaces and
//! objects of a scene.

use std::collections::HashMap;
use std::path::Path;

use glam::Vec3;

use super::{fov_y, material, Surface};
use crate::scene::{MAX_DEPTH_LIMIT, MAX_IMAGE_SIDE};
use crate::token_reader::{Cursor, Token, TokenReader};
use crate::{
    quoted, Attenuation, Camera, Light, LightKind, LoadError, Location, Material, Object, Projection, RenderSettings,
    Scene, ShadowMode, Shape,
};

/// Rayshade's defaults (its `defaults.h` and `RSSetup`).
const DEFAULT_EYEP: Vec3 = Vec3::new(0.0, -10.0, 0.0);
const DEFAULT_UP: Vec3 = Vec3::Z;
const DEFAULT_HFOV: f64 = 45.0;
const DEFAULT_SCREEN: u32 = 512;
const DEFAULT_MAXDEPTH: u32 = 5;
const DEFAULT_CUTOFF: f32 = 0.002;
/// Where Rayshade's default light, used when a scene defines none, comes from.
const DEFAULT_LIGHT_FROM: Vec3 = Vec3::new(1.0, -1.0, 1.0);

/// Rayshade keywords Glint does not read, so that a file using one gets an
/// error naming it rather than "unknown keyword".
const UNSUPPORTED: &[&str] = &[
    "aperture", "focaldist", "eyesep", "contrast", "adaptive", "filter", "report", "outfile", "frames", "starttime",
    "shutter", "framelength", "window", "crop", "shadowtransp", "print", "box", "disc", "torus", "blob", "heightfield",
    "grid", "list", "csg", "union", "intersect", "difference", "end", "object", "define", "name", "applysurf",
    "instance", "translate", "rotate", "scale", "transform", "texture", "atmosphere", "fog", "fogdeck", "mist",
];

/// Splits `source` into tokens, skipping `/* … */` and `//` comments.
fn tokenize<'a>(source: &'a str, path: &Path) -> Result<Vec<Token<'a>>, LoadError> {
    // Comments become spaces byte for byte, so offsets stay those of `source`.
    let mut code = source.as_bytes().to_vec();
    let mut i = 0;
    while i < code.len() {
        let end = match &code[i..] {
            [b'/', b'*', ..] => match source[i + 2..].find("*/") {
                Some(n) => i + 2 + n + 2,
                None => return Err(LoadError::new(path, Some(Location::of_offset(source, i)), "a `/*` comment is never closed")),
            },
            [b'/', b'/', ..] => source[i..].find('\n').map_or(code.len(), |n| i + n),
            _ => {
                i += 1;
                continue;
            }
        };
        for byte in &mut code[i..end] {
            if *byte != b'\n' {
                *byte = b' ';
            }
        }
        i = end;
    }
    let mut tokens = Vec::with_capacity(source.len() / 6);
    let (mut start, mut line) = (None, 1);
    for (i, byte) in code.iter().chain(std::iter::once(&b' ')).enumerate() {
        match (byte.is_ascii_whitespace(), start) {
            (true, Some(s)) => {
                tokens.push(Token { text: &source[s..i], offset: s, line });
                start = None;
            }
            (false, None) => start = Some(i),
            _ => {}
        }
        line += usize::from(*byte == b'\n');
    }
    Ok(tokens)
}

pub fn parse(source: &str, path: &Path) -> Result<Scene, LoadError> {
    let mut parser = Parser {
        cursor: Cursor::new(source, path, tokenize(source, path)?),
        eyep: None,
        lookp: None,
        up: None,
        fov: None,
        screen: None,
        background: None,
        max_depth: None,
        cutoff: None,
        ambient: None,
        lights: Vec::new(),
        surfaces: HashMap::new(),
        current_material: 0,
        materials: Vec::new(),
        objects: Vec::new(),
        warnings: Vec::new(),
    };
    parser.run()?;
    parser.scene()
}

struct Parser<'a> {
    cursor: Cursor<'a>,
    eyep: Option<(Vec3, Token<'a>)>,
    lookp: Option<(Vec3, Token<'a>)>,
    up: Option<(Vec3, Token<'a>)>,
    /// `fov H [V]` and where it was.
    fov: Option<(f64, Option<f64>, Token<'a>)>,
    screen: Option<(u32, u32, Token<'a>)>,
    background: Option<Vec3>,
    max_depth: Option<u32>,
    cutoff: Option<f32>,
    ambient: Option<Vec3>,
    lights: Vec<Light>,
    /// Material index by surface name.
    surfaces: HashMap<&'a str, usize>,
    /// The surface the primitive being read names.
    current_material: usize,
    materials: Vec<Material>,
    objects: Vec<Object>,
    warnings: Vec<LoadError>,
}

impl<'a> TokenReader<'a> for Parser<'a> {
    fn cursor(&self) -> &Cursor<'a> {
        &self.cursor
    }

    fn cursor_mut(&mut self) -> &mut Cursor<'a> {
        &mut self.cursor
    }

    fn warnings(&mut self) -> &mut Vec<LoadError> {
        &mut self.warnings
    }

    fn push(&mut self, shapes: Vec<Shape>) {
        self.objects.push(Object { material: self.current_material, shapes });
    }

    fn not_a_number(&self, token: &Token, what: &str) -> String {
        if token.text.starts_with('(') {
            return format!("{what}: Glint does not evaluate Rayshade's expressions in parentheses; write the number");
        }
        format!("expected a number ({what}) for {}, found {}", self.statement_name(), quoted(token.text))
    }
}

impl<'a> Parser<'a> {
    fn next_is_number(&self) -> bool {
        self.peek().is_some_and(|t| t.text.parse::<f64>().is_ok())
    }

    fn whole(&mut self, what: &str, range: std::ops::RangeInclusive<u32>) -> Result<u32, LoadError> {
        let t = self.expect(what)?;
        t.text.parse::<u32>().ok().filter(|n| range.contains(n)).ok_or_else(|| {
            self.error(&t, format!("{what}: {} is not a whole number in {}..={}", quoted(t.text), range.start(), range.end()))
        })
    }

    /// The numbers up to the next word.
    fn numbers(&mut self, what: &str) -> Result<Vec<f32>, LoadError> {
        let mut values = Vec::new();
        while self.next_is_number() {
            values.push(self.number(what)?);
        }
        Ok(values)
    }

    fn run(&mut self) -> Result<(), LoadError> {
        while let Some(t) = self.peek() {
            self.cursor.pos += 1;
            let previous = self.cursor.statement.replace(t);
            match t.text {
                "eyep" => self.eyep = Some((self.vec3("eyep")?, t)),
                "lookp" => self.lookp = Some((self.vec3("lookp")?, t)),
                "up" => self.up = Some((self.vec3("up")?, t)),
                "fov" => {
                    let h = f64::from(self.number("horizontal field of view")?);
                    let v = if self.next_is_number() { Some(f64::from(self.number("vertical field of view")?)) } else { None };
                    self.fov = Some((h, v, t));
                }
                "screen" => {
                    let w = self.whole("screen width", 1..=MAX_IMAGE_SIDE)?;
                    let h = self.whole("screen height", 1..=MAX_IMAGE_SIDE)?;
                    self.screen = Some((w, h, t));
                }
                "background" => self.background = Some(self.color("background")?),
                "sample" => self.sample(t)?,
                "maxdepth" => self.max_depth = Some(self.whole("maxdepth", 0..=MAX_DEPTH_LIMIT - 1)? + 1),
                "cutoff" => self.cutoff = Some(self.non_negative("cutoff")?),
                "light" => self.light(t)?,
                "surface" => self.surface(t)?,
                "sphere" => self.sphere(t)?,
                "cone" => self.cone(t)?,
                "cylinder" => self.cylinder(t)?,
                "polygon" => self.polygon(t)?,
                "triangle" => self.triangle(t)?,
                "plane" => self.plane(t)?,
                word if UNSUPPORTED.contains(&word) => {
                    return Err(self.error(&t, format!("Glint does not read Rayshade's `{word}`")));
                }
                word if word.parse::<f64>().is_ok() => {
                    self.cursor.statement = previous;
                    return Err(self.error(&t, format!("unexpected number {}: too many values for {}", quoted(word), self.statement_name())));
                }
                word => return Err(self.error(&t, format!("unknown keyword {}", quoted(word)))),
            }
        }
        Ok(())
    }

    /// `sample N [jitter|nojitter]`: Glint's samples are `--spp`'s business.
    fn sample(&mut self, t: Token<'a>) -> Result<(), LoadError> {
        let n = self.whole("samples", 1..=64)?;
        if self.peek().is_some_and(|p| p.text == "jitter" || p.text == "nojitter") {
            self.cursor.pos += 1;
        }
        if n > 1 {
            self.warn(&t, format!("sample {n}: Glint traces one sample per pixel, at its centre, unless `glint render --spp` asks for {}", n * n));
        }
        Ok(())
    }

    /// `light I point x y z`, `light I directional x y z` or `light I ambient`.
    fn light(&mut self, t: Token<'a>) -> Result<(), LoadError> {
        let at = self.cursor.pos;
        let intensity = self.numbers("light intensity")?;
        let color = match intensity[..] {
            [i] => Vec3::splat(i),
            [r, g, b] => Vec3::new(r, g, b),
            _ => {
                let t = self.cursor.tokens.get(at).copied().unwrap_or(t);
                return Err(self.error(&t, format!("light: the intensity is one number or three (r g b), found {}", intensity.len())));
            }
        };
        if color.min_element() < 0.0 {
            return Err(self.error(&self.cursor.tokens[at], "light: the intensity must not be negative"));
        }
        let kind = self.expect("a kind (point, directional or ambient)")?;
        let kind = match kind.text {
            "ambient" => {
                self.ambient = Some(color);
                return Ok(());
            }
            "point" => LightKind::Point { position: self.vec3("light position")? },
            "directional" => {
                let towards = self.vec3("light direction")?;
                let Some(towards) = crate::unit(towards) else {
                    return Err(self.error(&kind, "directional light: the direction is a zero vector"));
                };
                LightKind::Directional { direction: -towards }
            }
            "spot" | "area" | "extended" | "jittered" => {
                return Err(self.error(&kind, format!("Glint does not read Rayshade's {} lights (only point, directional and ambient)", kind.text)));
            }
            other => return Err(self.error(&kind, format!("light: unknown kind {} (point, directional or ambient)", quoted(other)))),
        };
        if self.peek().is_some_and(|p| p.text == "noshadow") {
            let p = self.expect("noshadow")?;
            self.warn(&p, "noshadow: Glint's lights always cast shadows; ignored");
        }
        self.lights.push(Light { kind, color, intensity: 1.0, attenuation: Attenuation::None, enabled: true });
        Ok(())
    }

    fn surface(&mut self, t: Token<'a>) -> Result<(), LoadError> {
        let name = self.expect("a name")?;
        if name.text.parse::<f64>().is_ok() {
            return Err(self.error(&name, format!("surface: expected a name, found the number {}", quoted(name.text))));
        }
        if self.surfaces.contains_key(name.text) {
            return Err(self.error(&name, format!("surface {} is defined twice", quoted(name.text))));
        }
        let mut surface = Surface::default();
        while let Some(c) = self.peek() {
            self.cursor.statement = Some(c);
            match c.text {
                "ambient" => surface.ambient = self.take(|p| p.color("ambient"))?,
                "diffuse" => surface.diffuse = self.take(|p| p.color("diffuse"))?,
                "specular" => surface.specular = self.take(|p| p.color("specular"))?,
                "body" => surface.body = self.take(|p| p.color("body"))?,
                "specpow" => surface.specpow = self.take(|p| p.non_negative("specpow"))?,
                "reflect" => surface.reflect = self.take(|p| p.non_negative("reflect"))?,
                "transp" => surface.transp = self.take(|p| p.non_negative("transp"))?,
                "index" => {
                    let at = self.cursor.pos + 1;
                    surface.index = self.take(|p| p.number("index"))?;
                    if surface.index <= 0.0 {
                        return Err(self.error(&self.cursor.tokens[at], format!("index must be positive, found {}", surface.index)));
                    }
                }
                "noshadow" => {
                    self.cursor.pos += 1;
                    self.warn(&c, "noshadow: Glint's surfaces always receive shadows; ignored");
                }
                "extinct" => {
                    self.take(|p| p.non_negative("extinct"))?;
                    self.warn(&c, "extinct: Glint does not attenuate light inside a medium; ignored");
                }
                "translu" => return Err(self.error(&c, "Glint does not read Rayshade's `translu` (diffuse transmission)")),
                _ => break,
            }
        }
        self.cursor.statement = Some(t);
        let (material, warning) = material(name.text, &surface).map_err(|e| self.error(&name, e))?;
        if let Some(warning) = warning {
            self.warn(&name, warning);
        }
        self.surfaces.insert(name.text, self.materials.len());
        self.materials.push(material);
        Ok(())
    }

    /// Reads the operands of the component keyword at the cursor.
    fn take<T>(&mut self, read: impl FnOnce(&mut Self) -> Result<T, LoadError>) -> Result<T, LoadError> {
        self.cursor.pos += 1;
        read(self)
    }

    /// The surface a primitive names; Glint needs one (Rayshade would fall
    /// back on a default surface that its guide does not give).
    fn surface_of(&mut self, keyword: &Token<'a>) -> Result<(), LoadError> {
        if self.next_is_number() || self.peek().is_none() {
            return Err(self.error(keyword, format!("`{}` names no surface: Glint needs a surface defined with `surface NAME`", keyword.text)));
        }
        let name = self.expect("a surface")?;
        self.current_material = *self.surfaces.get(name.text).ok_or_else(|| self.error(&name, format!("undefined surface {}", quoted(name.text))))?;
        Ok(())
    }

    fn sphere(&mut self, s: Token<'a>) -> Result<(), LoadError> {
        self.surface_of(&s)?;
        let radius = self.non_negative("radius")?;
        let center = self.vec3("centre")?;
        self.push_built(&s, Shape::sphere(center, radius))
    }

    fn cone(&mut self, c: Token<'a>) -> Result<(), LoadError> {
        self.surface_of(&c)?;
        let base_radius = self.non_negative("base radius")?;
        let base = self.vec3("base")?;
        let apex_radius = self.non_negative("apex radius")?;
        let apex = self.vec3("apex")?;
        self.push_built(&c, Shape::cone(base, base_radius, apex, apex_radius))
    }

    fn cylinder(&mut self, c: Token<'a>) -> Result<(), LoadError> {
        self.surface_of(&c)?;
        let radius = self.non_negative("radius")?;
        let base = self.vec3("base")?;
        let apex = self.vec3("apex")?;
        self.push_built(&c, Shape::cone(base, radius, apex, radius))
    }

    fn plane(&mut self, p: Token<'a>) -> Result<(), LoadError> {
        self.surface_of(&p)?;
        let point = self.vec3("point")?;
        let normal = self.vec3("normal")?;
        let Some(normal) = crate::unit(normal) else {
            return Err(self.error(&p, "plane: the normal is a zero vector"));
        };
        self.push_built(&p, Shape::plane(point, normal))
    }

    /// The vertices of a polygon or triangle: every number up to the next word.
    fn points(&mut self, keyword: &Token<'a>) -> Result<Vec<Vec3>, LoadError> {
        let values = self.numbers("vertex coordinate")?;
        if values.len() % 3 != 0 {
            return Err(self.error(keyword, format!("`{}` has {} numbers, not whole x y z triples", keyword.text, values.len())));
        }
        Ok(values.chunks(3).map(|c| Vec3::new(c[0], c[1], c[2])).collect())
    }

    fn polygon(&mut self, p: Token<'a>) -> Result<(), LoadError> {
        self.surface_of(&p)?;
        let vertices = self.points(&p)?;
        if vertices.len() < 3 {
            return Err(self.error(&p, format!("polygon needs at least three vertices, found {}", vertices.len())));
        }
        self.push_polygon(&p, vertices)
    }

    /// `triangle p1 p2 p3`, or a Phong triangle `p1 n1 p2 n2 p3 n3`.
    fn triangle(&mut self, t: Token<'a>) -> Result<(), LoadError> {
        self.surface_of(&t)?;
        let points = self.points(&t)?;
        let (vertices, normals) = match points[..] {
            [a, b, c] => ([a, b, c], None),
            [a, na, b, nb, c, nc] => ([a, b, c], Some([na, nb, nc])),
            _ => {
                return Err(self.error(&t, format!("triangle needs three vertices, or three vertices each with a normal, found {} points", points.len())));
            }
        };
        let normals = match normals.map(|n| n.map(crate::unit)) {
            Some([Some(a), Some(b), Some(c)]) => Some([a, b, c]),
            Some(_) => {
                self.warn(&t, "triangle has a zero-length vertex normal; shaded flat");
                None
            }
            None => None,
        };
        self.push_built(&t, Shape::triangle(vertices, normals))
    }

    fn scene(mut self) -> Result<Scene, LoadError> {
        let (width, height) = self.screen.map_or((DEFAULT_SCREEN, DEFAULT_SCREEN), |(w, h, _)| (w, h));
        let (h, v, fov_token) = match self.fov {
            Some((h, v, t)) => (h, v, Some(t)),
            None => (DEFAULT_HFOV, None, None),
        };
        let (fov, h_glint) = fov_y(h, v, width, height);
        let place = |parser: &Self, token: Option<Token>| token.map(|t| parser.location(&t));
        if !(fov > 0.0 && fov < 180.0 && h > 0.0 && h < 180.0) {
            // Without a `fov`, the screen's shape made the vertical angle.
            let location = place(&self, fov_token.or(self.screen.map(|s| s.2)));
            return Err(LoadError::new(self.cursor.path, location, format!("fov: the field of view must be between 0 and 180 degrees, found {h} (horizontal) and {fov} (vertical)")));
        }
        if (h_glint - h).abs() > 1.0e-3 {
            if let Some(t) = fov_token {
                self.warn(&t, format!("fov {h} {fov}: Glint's pixels are square, so on a {width} × {height} screen it keeps the vertical {fov}° and spans {h_glint:.4}° across, not {h}°"));
            }
        }
        let eye = self.eyep.map_or(DEFAULT_EYEP, |e| e.0);
        let look_at = self.lookp.map_or(Vec3::ZERO, |l| l.0);
        let up = self.up.map_or(DEFAULT_UP, |u| u.0);
        let camera = Camera { eye, look_at, up, projection: Projection::Perspective { fov_y_degrees: fov as f32 } };
        let camera_token = [self.eyep.map(|e| e.1), self.lookp.map(|l| l.1), self.up.map(|u| u.1)].into_iter().flatten().max_by_key(|t| t.offset);
        if crate::view_overflows(&camera) {
            let location = place(&self, camera_token);
            return Err(LoadError::new(self.cursor.path, location, "`eyep` and `lookp` are too far apart (the view direction overflows 32-bit floats)"));
        }
        if camera.basis().is_none() {
            let location = place(&self, camera_token);
            return Err(LoadError::new(self.cursor.path, location, "`up` is parallel to the view direction (or `eyep` equals `lookp`)"));
        }
        if self.lights.is_empty() {
            self.lights.push(Light {
                kind: LightKind::Directional { direction: -DEFAULT_LIGHT_FROM.normalize() },
                color: Vec3::ONE,
                intensity: 1.0,
                attenuation: Attenuation::None,
                enabled: true,
            });
        }
        if self.materials.is_empty() {
            let (default, _) = material("default", &Surface::default()).expect("the default surface is finite");
            self.materials.push(default);
        }
        Ok(Scene {
            width,
            height,
            background: self.background.unwrap_or(Vec3::ZERO),
            camera,
            ambient: self.ambient.unwrap_or(Vec3::ONE),
            lights: self.lights,
            materials: self.materials,
            objects: self.objects,
            depth_cue: None,
            render: RenderSettings {
                max_depth: self.max_depth.unwrap_or(DEFAULT_MAXDEPTH + 1),
                cutoff: self.cutoff.unwrap_or(DEFAULT_CUTOFF),
                // Rayshade lets light through transparent occluders by default.
                shadow_mode: ShadowMode::Tinted,
                ..RenderSettings::default()
            },
            animation: None,
            warnings: self.warnings,
        })
    }
}
