//! Example NFF scenes that the project generates itself, in the spirit of Eric
//! Haines' Standard Procedural Databases: `scenes/sphereflake.nff` (SPD's
//! "balls") and `scenes/cone_tree.nff` (a branching tree of cones and spheres,
//! like SPD's "tree").
//!
//! The committed files must be exactly what the generators below write;
//! `GLINT_BLESS=1 cargo test --release --test example_scenes` rewrites them
//! (the same convention as the golden images, which also cover these scenes).
//!
//! The output must not depend on the platform: every number goes through
//! [`num`] (a fixed number of decimals, which Rust's formatter rounds exactly),
//! and the generators use only +, −, ×, ÷ and √ (correctly rounded in IEEE 754)
//! with their own sine and cosine, never the platform's libm.

use std::f64::consts::{FRAC_PI_2, PI};
use std::fmt::Write as _;
use std::path::{Path, PathBuf};

/// Committed example files must stay small.
const MAX_FILE_BYTES: usize = 100_000;

// ---------------------------------------------------------------------------
// Deterministic arithmetic and output.

/// sin and cos of `x` by reduction to [−π/4, π/4] and Taylor series, so that
/// they give the same bits everywhere (libm's may differ in the last place).
fn sin_cos(x: f64) -> (f64, f64) {
    let quadrant = (x / FRAC_PI_2).round();
    let r = x - quadrant * FRAC_PI_2;
    let r2 = r * r;
    // Terms up to r^17 / 17!: the error is far below f64 precision for |r| ≤ π/4.
    let (mut s, mut c) = (0.0, 0.0);
    let (mut ts, mut tc) = (r, 1.0);
    for k in 0..9 {
        s += ts;
        c += tc;
        let k = f64::from(k);
        ts *= -r2 / ((2.0 * k + 2.0) * (2.0 * k + 3.0));
        tc *= -r2 / ((2.0 * k + 1.0) * (2.0 * k + 2.0));
    }
    match (quadrant as i64).rem_euclid(4) {
        0 => (s, c),
        1 => (c, -s),
        2 => (-s, -c),
        _ => (-c, s),
    }
}

/// arcsin of `x`, by Newton's method on sin(y) = x (only needed for constants).
fn asin(x: f64) -> f64 {
    let mut y = x;
    for _ in 0..60 {
        let (s, c) = sin_cos(y);
        y -= (s - x) / c;
    }
    y
}

/// A number as written to the files: at most `DECIMALS` decimals, trailing
/// zeros dropped, no negative zero.
fn num(v: f64) -> String {
    const DECIMALS: usize = 4;
    assert!(v.is_finite(), "non-finite number {v}");
    let s = format!("{v:.DECIMALS$}");
    let s = s.trim_end_matches('0').trim_end_matches('.');
    if s == "-0" { "0".to_string() } else { s.to_string() }
}

#[derive(Debug, Clone, Copy, PartialEq)]
struct V(f64, f64, f64);

impl V {
    fn add(self, o: V) -> V {
        V(self.0 + o.0, self.1 + o.1, self.2 + o.2)
    }
    fn scale(self, k: f64) -> V {
        V(self.0 * k, self.1 * k, self.2 * k)
    }
    fn dot(self, o: V) -> f64 {
        self.0 * o.0 + self.1 * o.1 + self.2 * o.2
    }
    fn cross(self, o: V) -> V {
        V(self.1 * o.2 - self.2 * o.1, self.2 * o.0 - self.0 * o.2, self.0 * o.1 - self.1 * o.0)
    }
    fn normalize(self) -> V {
        self.scale(1.0 / self.dot(self).sqrt())
    }
}

impl std::fmt::Display for V {
    fn fmt(&self, f: &mut std::fmt::Formatter) -> std::fmt::Result {
        write!(f, "{} {} {}", num(self.0), num(self.1), num(self.2))
    }
}

/// A rotation matrix (rows).
#[derive(Debug, Clone, Copy)]
struct M([V; 3]);

impl M {
    const IDENTITY: M = M([V(1.0, 0.0, 0.0), V(0.0, 1.0, 0.0), V(0.0, 0.0, 1.0)]);

    /// Rotation by `angle` (radians, right-handed) about the unit `axis`.
    fn axis_angle(axis: V, angle: f64) -> M {
        let (sin, cos) = sin_cos(angle);
        M::rodrigues(axis, sin, cos)
    }

    /// Rotation about the unit `axis` by the angle with this sine and cosine.
    fn rodrigues(axis: V, s: f64, c: f64) -> M {
        let V(x, y, z) = axis;
        let t = 1.0 - c;
        M([
            V(c + x * x * t, x * y * t - z * s, x * z * t + y * s),
            V(y * x * t + z * s, c + y * y * t, y * z * t - x * s),
            V(z * x * t - y * s, z * y * t + x * s, c + z * z * t),
        ])
    }

    /// The shortest rotation taking +Z onto the unit vector `to`.
    fn from_z(to: V) -> M {
        let z = V(0.0, 0.0, 1.0);
        let axis = z.cross(to);
        let sin = axis.dot(axis).sqrt();
        let cos = z.dot(to);
        if sin < 1e-12 {
            return if cos > 0.0 { M::IDENTITY } else { M::axis_angle(V(1.0, 0.0, 0.0), PI) };
        }
        M::rodrigues(axis.scale(1.0 / sin), sin, cos)
    }

    fn apply(&self, v: V) -> V {
        V(self.0[0].dot(v), self.0[1].dot(v), self.0[2].dot(v))
    }
}

/// An NFF file being written.
struct Nff(String);

impl Nff {
    fn new(header: &[&str]) -> Nff {
        let mut text = String::new();
        for line in header {
            writeln!(text, "# {line}").unwrap();
        }
        Nff(text)
    }
    fn view(&mut self, from: V, at: V, up: V, angle: f64, width: u32, height: u32) {
        let t = &mut self.0;
        writeln!(t, "v\nfrom {from}\nat {at}\nup {up}\nangle {}\nhither 0.01\nresolution {width} {height}", num(angle)).unwrap();
    }
    fn background(&mut self, c: V) {
        writeln!(self.0, "b {c}").unwrap();
    }
    fn light(&mut self, p: V) {
        writeln!(self.0, "l {p}").unwrap();
    }
    /// `f r g b Kd Ks Shine T ior` (Glint: Ks is also the mirror reflectance).
    fn fill(&mut self, color: V, kd: f64, ks: f64, shine: f64, t: f64, ior: f64) {
        writeln!(self.0, "f {color} {} {} {} {} {}", num(kd), num(ks), num(shine), num(t), num(ior)).unwrap();
    }
    fn sphere(&mut self, c: V, r: f64) {
        writeln!(self.0, "s {c} {}", num(r)).unwrap();
    }
    fn cone(&mut self, base: V, base_r: f64, apex: V, apex_r: f64) {
        writeln!(self.0, "c\n{base} {}\n{apex} {}", num(base_r), num(apex_r)).unwrap();
    }
    fn polygon(&mut self, vertices: &[V]) {
        writeln!(self.0, "p {}", vertices.len()).unwrap();
        for v in vertices {
            writeln!(self.0, "{v}").unwrap();
        }
    }
}

// ---------------------------------------------------------------------------
// The sphereflake.

/// The nine directions of a sphere's children, in a frame whose +Z points away
/// from the sphere's own parent: three above at 54.7° elevation and six around
/// the equator, as SPD's balls.c builds them (three directions from a cube
/// corner, tipped over, repeated at 0°, 120° and 240° about Z).
fn flake_directions() -> [V; 9] {
    let d = 1.0 / 2f64.sqrt();
    let tip = M::axis_angle(V(1.0, -1.0, 0.0).normalize(), asin(2.0 / 6f64.sqrt()));
    let trio = [V(d, d, 0.0), V(d, 0.0, -d), V(0.0, d, -d)].map(|v| tip.apply(v));
    let mut dirs = [V(0.0, 0.0, 0.0); 9];
    for set in 0..3u32 {
        let turn = M::axis_angle(V(0.0, 0.0, 1.0), f64::from(set) * 2.0 * PI / 3.0);
        for (k, v) in trio.iter().enumerate() {
            dirs[set as usize * 3 + k] = turn.apply(*v).normalize();
        }
    }
    dirs
}

fn flake(nff: &mut Nff, dirs: &[V; 9], center: V, radius: f64, axis: V, depth: u32) {
    nff.sphere(center, radius);
    if depth == 0 {
        return;
    }
    let frame = M::from_z(axis);
    let child_radius = radius / 3.0;
    for d in dirs {
        let dir = frame.apply(*d).normalize();
        flake(nff, dirs, center.add(dir.scale(radius + child_radius)), child_radius, dir, depth - 1);
    }
}

/// Haines' sphereflake: a sphere with nine spheres a third its size on its
/// surface, each with nine of its own, `depth` levels down (1 + 9 + … + 9^depth
/// spheres), on a floor, under three lights; Z is up.
fn sphereflake(depth: u32) -> String {
    let mut nff = Nff::new(&[
        &format!("Sphereflake (after SPD's balls), depth {depth}: {} spheres on a floor.", (9u32.pow(depth + 1) - 1) / 8),
        "Generated by tests/example_scenes.rs; do not edit. Regenerate with",
        "GLINT_BLESS=1 cargo test --release --test example_scenes",
    ]);
    nff.view(V(2.1, 1.3, 1.7), V(0.0, 0.0, 0.0), V(0.0, 0.0, 1.0), 45.0, 400, 400);
    nff.background(V(0.078, 0.361, 0.753));
    nff.light(V(4.0, 3.0, 2.0));
    nff.light(V(1.0, -4.0, 4.0));
    nff.light(V(-3.0, 1.0, 5.0));
    // The floor: matte, a checkerboard of two colours.
    let tiles = 8;
    let size = 1.5;
    for (parity, color) in [(0, V(0.95, 0.8, 0.5)), (1, V(0.55, 0.3, 0.2))] {
        nff.fill(color, 0.8, 0.0, 0.0, 0.0, 1.0);
        for i in 0..tiles {
            for j in 0..tiles {
                if (i + j) % 2 != parity {
                    continue;
                }
                let x = f64::from(i - tiles / 2) * size;
                let y = f64::from(j - tiles / 2) * size;
                let z = -0.5;
                nff.polygon(&[V(x, y, z), V(x + size, y, z), V(x + size, y + size, z), V(x, y + size, z)]);
            }
        }
    }
    // The balls: shiny and half mirror (Ks = 0.5 is also k_m in Glint's NFF reading).
    nff.fill(V(1.0, 0.9, 0.7), 0.5, 0.5, 30.0, 0.0, 1.0);
    flake(&mut nff, &flake_directions(), V(0.0, 0.0, 0.0), 0.5, V(0.0, 0.0, 1.0), depth);
    nff.0
}

// ---------------------------------------------------------------------------
// The cone tree.

struct Tree {
    /// Branches per fork.
    fork: u32,
    /// How far each branch leans from its parent's direction (radians).
    spread: f64,
    /// Each level's length and radius, relative to its parent's.
    length_ratio: f64,
    radius_ratio: f64,
    /// What has been grown: (base, base radius, tip, tip radius) per branch,
    /// and (centre, radius) per joint and per leaf.
    cones: Vec<(V, f64, V, f64)>,
    joints: Vec<(V, f64)>,
    leaves: Vec<(V, f64)>,
}

/// A unit vector perpendicular to the unit `d`.
fn perpendicular(d: V) -> V {
    let other = if d.0.abs() < 0.9 { V(1.0, 0.0, 0.0) } else { V(0.0, 1.0, 0.0) };
    d.cross(other).normalize()
}

impl Tree {
    /// One branch from `base` along the unit `dir`: an open cone narrowing from
    /// `radius` to the children's radius, a sphere at the joint (which also
    /// closes the cone), then `level` more forks; a leaf at the end of each twig.
    fn branch(&mut self, base: V, dir: V, length: f64, radius: f64, level: u32, twist: f64) {
        let tip = base.add(dir.scale(length));
        let tip_radius = radius * self.radius_ratio;
        self.cones.push((base, radius, tip, tip_radius));
        if level == 0 {
            self.leaves.push((tip, length * 0.45));
            return;
        }
        self.joints.push((tip, tip_radius));
        // Children lean `spread` away from `dir`, spaced evenly around it; each
        // level turns the ring by the golden angle so the forks do not line up.
        let golden = PI * (3.0 - 5f64.sqrt());
        let side = perpendicular(dir);
        for k in 0..self.fork {
            let around = twist + f64::from(k) * 2.0 * PI / f64::from(self.fork);
            let axis = M::axis_angle(dir, around).apply(side);
            let child = M::axis_angle(axis, self.spread).apply(dir).normalize();
            self.branch(tip, child, length * self.length_ratio, tip_radius, level - 1, twist + golden);
        }
    }
}

/// A tree of cones (branches), spheres (joints) and green spheres (leaves) on a
/// round lawn; Z is up.
fn cone_tree(levels: u32) -> String {
    let mut tree = Tree {
        fork: 3,
        spread: 0.6,
        length_ratio: 0.72,
        radius_ratio: 0.62,
        cones: Vec::new(),
        joints: Vec::new(),
        leaves: Vec::new(),
    };
    tree.branch(V(0.0, 0.0, 0.0), V(0.0, 0.0, 1.0), 1.6, 0.22, levels, 0.0);
    let Tree { cones, joints, leaves, .. } = tree;
    let mut nff = Nff::new(&[
        &format!(
            "Cone tree (after SPD's tree), {levels} forks deep: {} cones, {} joint spheres, {} leaves.",
            cones.len(),
            joints.len(),
            leaves.len()
        ),
        "Generated by tests/example_scenes.rs; do not edit. Regenerate with",
        "GLINT_BLESS=1 cargo test --release --test example_scenes",
    ]);
    nff.view(V(5.5, -7.0, 2.6), V(0.0, 0.0, 2.2), V(0.0, 0.0, 1.0), 40.0, 400, 400);
    nff.background(V(0.55, 0.7, 0.9));
    nff.light(V(-6.0, -8.0, 12.0));
    nff.light(V(8.0, -3.0, 6.0));
    // The lawn: a 24-sided disc.
    nff.fill(V(0.35, 0.55, 0.2), 0.9, 0.0, 0.0, 0.0, 1.0);
    let lawn: Vec<V> = (0..24)
        .map(|k| {
            let (s, c) = sin_cos(f64::from(k) * 2.0 * PI / 24.0);
            V(6.0 * c, 6.0 * s, 0.0)
        })
        .collect();
    nff.polygon(&lawn);
    nff.fill(V(0.45, 0.3, 0.18), 0.85, 0.1, 10.0, 0.0, 1.0);
    for (base, br, apex, ar) in &cones {
        nff.cone(*base, *br, *apex, *ar);
    }
    for (c, r) in &joints {
        nff.sphere(*c, *r);
    }
    nff.fill(V(0.25, 0.65, 0.15), 0.75, 0.25, 40.0, 0.0, 1.0);
    for (c, r) in &leaves {
        nff.sphere(*c, *r);
    }
    nff.0
}

// ---------------------------------------------------------------------------
// The tests.

fn scenes_dir() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("scenes")
}

/// Checks that `text` loads cleanly and equals the committed file `name`, or
/// rewrites the file under GLINT_BLESS=1.
fn check(name: &str, text: &str, primitives: std::ops::RangeInclusive<usize>) {
    let path = scenes_dir().join(name);
    let scene = glint_scene::nff::parse(text, &path, &glint_scene::nff::NffOptions::default()).unwrap_or_else(|e| panic!("{e}"));
    assert!(scene.warnings.is_empty(), "{name}: {:?}", scene.warnings);
    assert!(primitives.contains(&scene.primitive_count()), "{name}: {} primitives, expected {primitives:?}", scene.primitive_count());
    assert!(text.len() <= MAX_FILE_BYTES, "{name}: {} bytes, over {MAX_FILE_BYTES}", text.len());
    if std::env::var_os("GLINT_BLESS").is_some_and(|v| v == "1") {
        std::fs::write(&path, text).unwrap_or_else(|e| panic!("{}: {e}", path.display()));
        println!("wrote {}", path.display());
        return;
    }
    let committed = std::fs::read_to_string(&path)
        .unwrap_or_else(|e| panic!("{}: {e} (run GLINT_BLESS=1 cargo test --release --test example_scenes)", path.display()));
    if committed != text {
        let line = committed.lines().zip(text.lines()).position(|(a, b)| a != b).unwrap_or(committed.lines().count().min(text.lines().count()));
        panic!(
            "{} is not what the generator writes (first difference at line {}: {:?} vs generated {:?}); \
             run GLINT_BLESS=1 cargo test --release --test example_scenes",
            path.display(),
            line + 1,
            committed.lines().nth(line),
            text.lines().nth(line)
        );
    }
}

#[test]
fn sphereflake_is_up_to_date() {
    check("sphereflake.nff", &sphereflake(3), 800..=900);
}

#[test]
fn cone_tree_is_up_to_date() {
    check("cone_tree.nff", &cone_tree(5), 500..=2000);
}

#[test]
fn generators_are_deterministic_and_well_formed() {
    assert_eq!(sphereflake(2), sphereflake(2));
    assert_eq!(num(-0.00001), "0");
    assert_eq!(num(1.5), "1.5");
    assert_eq!(num(2.0), "2");
    assert_eq!(num(-0.12345), "-0.1235");
    for k in -8..=8 {
        let x = f64::from(k) * 0.7;
        let (s, c) = sin_cos(x);
        assert!((s - x.sin()).abs() < 1e-15 && (c - x.cos()).abs() < 1e-15, "sin_cos({x})");
    }
    assert!((asin(0.5) - PI / 6.0).abs() < 1e-15);
    // The flake's children: three above the equator, six on it, all unit length.
    let dirs = flake_directions();
    assert_eq!(dirs.iter().filter(|d| d.2 > 0.5).count(), 3);
    assert_eq!(dirs.iter().filter(|d| d.2.abs() < 1e-12).count(), 6);
    assert!(dirs.iter().all(|d| (d.dot(*d) - 1.0).abs() < 1e-12));
}
