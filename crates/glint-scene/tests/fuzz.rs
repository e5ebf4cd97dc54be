//! Fuzzing of the scene loaders, as property tests that run with the rest of
//! the suite (cargo-fuzz needs a nightly toolchain; these need nothing).
//!
//! Each target builds near-valid files from a structured generator (TOML
//! tables, NFF statements, OBJ and MTL lines, with numbers that are often NaN,
//! infinite, huge, tiny or negative), then mutates them: tokens deleted,
//! duplicated, replaced by or interleaved with garbage, lines deleted, doubled
//! or swapped, random bytes inserted, the file cut at a random byte. Some cases
//! are plain random bytes or noise from the format's own alphabet. Every case
//! is written to a file and loaded through [`glint_scene::load`], as `glint
//! render` does, and must end in one of two ways:
//!
//! * an error naming a file of the case and a line inside it (and a column
//!   inside that line when it has one), in one line of text;
//! * a scene that the renderer can take as it is: finite geometry, a camera
//!   with a basis, image size and depth in range, materials and lights in
//!   range. The host half of rendering (BVH build, packing, per-frame
//!   uniforms) then runs on it and must not panic.
//!
//! A panic anywhere is a failure, shrunk by proptest to a small input.
//!
//! `cargo test -p glint-scene --test fuzz` runs a fixed-seed batch of each
//! target (quick, for CI). Longer runs, with random seeds:
//!
//! * `GLINT_FUZZ_SECONDS=300` runs each target for that long;
//! * `GLINT_FUZZ_CASES=200000` runs each target for that many cases;
//! * `GLINT_FUZZ_SEED=n` replays a run (a failure prints its seed).
//!
//! docs/fuzzing.md has the details and what the fuzzers found.

use std::fmt;
use std::path::{Path, PathBuf};
use std::sync::atomic::{AtomicU64, Ordering};
use std::time::{Duration, Instant};

use glam::Vec3;
use glint_scene::bvh::Bvh;
use glint_scene::gpu_types::{pack, scene_uniforms, primitive_bounds, GpuScene, BVH_STACK, LEAF, PRIM_POLYGON, PRIM_TRIANGLE, RIGHT_LEAF};
use glint_scene::scene::MAX_DEPTH_LIMIT;
use glint_scene::toml_scene::MAX_IMAGE_SIDE;
use glint_scene::{Attenuation, LightKind, LoadError, Projection, Scene, Shape};
use proptest::prelude::*;
use proptest::test_runner::{Config, RngSeed, TestCaseError, TestRunner};

// ---------------------------------------------------------------------------
// Running a target

/// Cases per target in the default (CI) run.
const DEFAULT_CASES: u32 = 2000;

fn env_u64(name: &str) -> Option<u64> {
    let value = std::env::var(name).ok()?;
    Some(value.trim().parse().unwrap_or_else(|_| panic!("{name}={value:?} is not a whole number")))
}

/// Runs `check` on inputs from `strategy`: a fixed-seed batch by default, or as
/// many cases or seconds as the environment asks for.
fn run_target<S>(name: &str, strategy: S, check: impl Fn(&S::Value, &Tally) -> Result<(), TestCaseError>)
where
    S: Strategy,
    S::Value: fmt::Debug,
{
    let seconds = env_u64("GLINT_FUZZ_SECONDS");
    let cases = env_u64("GLINT_FUZZ_CASES");
    let long = seconds.is_some() || cases.is_some();
    // CI runs the same cases every time; long runs new ones unless told a seed.
    let seed = env_u64("GLINT_FUZZ_SEED").unwrap_or_else(|| {
        if long {
            let now = std::time::SystemTime::now().duration_since(std::time::UNIX_EPOCH).unwrap_or_default();
            now.as_nanos() as u64
        } else {
            name.bytes().fold(0x676c_696e_74, |h, b| h.wrapping_mul(31).wrapping_add(u64::from(b)))
        }
    });
    let deadline = seconds.map(|s| Instant::now() + Duration::from_secs(s));
    let wanted = cases.unwrap_or(if long { u64::MAX } else { u64::from(DEFAULT_CASES) });
    let start = Instant::now();
    let tally = Tally::default();
    let mut done = 0u64;
    let mut batch = 0u64;
    while done < wanted && deadline.is_none_or(|d| Instant::now() < d) {
        let size = (wanted - done).min(5000) as u32;
        let rng_seed = RngSeed::Fixed(seed.wrapping_add(batch));
        let config = Config {
            cases: size,
            failure_persistence: None,
            max_shrink_iters: 20_000,
            max_global_rejects: 0,
            rng_seed,
            ..Config::default()
        };
        let mut runner = TestRunner::new(config);
        if let Err(e) = runner.run(&strategy, |input| check(&input, &tally)) {
            panic!("fuzz target {name} failed after {done} cases (GLINT_FUZZ_SEED={seed}): {e}");
        }
        done += u64::from(size);
        batch += 1;
    }
    let (scenes, errors) = (tally.scenes.load(Ordering::Relaxed), tally.errors.load(Ordering::Relaxed));
    eprintln!(
        "fuzz target {name}: {done} cases in {:.1} s, seed {seed}, no failure ({scenes} loads gave a scene, {errors} an error)",
        start.elapsed().as_secs_f64()
    );
    assert!(done > 0, "fuzz target {name} ran no case");
}

/// How the loads of a target ended, to show how deep the inputs reach.
#[derive(Default)]
struct Tally {
    scenes: AtomicU64,
    errors: AtomicU64,
}

// ---------------------------------------------------------------------------
// Inputs

/// The bytes of a file, shown as text with escapes when a case fails.
#[derive(Clone, PartialEq)]
struct Bytes(Vec<u8>);

impl fmt::Debug for Bytes {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "b\"{}\"", self.0.escape_ascii())
    }
}

/// A position in a file: taken modulo the number of tokens, lines or bytes
/// there are, and shrunk towards the start.
#[derive(Debug, Clone, Copy)]
struct Index(usize);

impl Index {
    fn index(self, len: usize) -> usize {
        self.0 % len
    }
}

fn index() -> impl Strategy<Value = Index> {
    any::<usize>().prop_map(Index)
}

/// One change to a file's bytes.
#[derive(Debug, Clone)]
enum Mutation {
    DeleteToken(Index),
    DuplicateToken(Index),
    ReplaceToken(Index, String),
    InsertToken(Index, String),
    DeleteLine(Index),
    DuplicateLine(Index),
    SwapLines(Index, Index),
    InsertBytes(Index, Vec<u8>),
    Truncate(Index),
}

/// Byte ranges of whitespace-separated tokens.
fn token_spans(bytes: &[u8]) -> Vec<(usize, usize)> {
    let mut spans = Vec::new();
    let mut start = None;
    for (i, b) in bytes.iter().enumerate() {
        match (b.is_ascii_whitespace(), start) {
            (true, Some(s)) => {
                spans.push((s, i));
                start = None;
            }
            (false, None) => start = Some(i),
            _ => {}
        }
    }
    if let Some(s) = start {
        spans.push((s, bytes.len()));
    }
    spans
}

/// Byte ranges of lines, each with its newline.
fn line_spans(bytes: &[u8]) -> Vec<(usize, usize)> {
    let mut spans = Vec::new();
    let mut start = 0;
    for (i, b) in bytes.iter().enumerate() {
        if *b == b'\n' {
            spans.push((start, i + 1));
            start = i + 1;
        }
    }
    if start < bytes.len() {
        spans.push((start, bytes.len()));
    }
    spans
}

fn splice(bytes: &mut Vec<u8>, (start, end): (usize, usize), with: &[u8]) {
    bytes.splice(start..end, with.iter().copied());
}

impl Mutation {
    fn apply(&self, bytes: &mut Vec<u8>) {
        let tokens = token_spans(bytes);
        let lines = line_spans(bytes);
        let token = |i: &Index| (!tokens.is_empty()).then(|| tokens[i.index(tokens.len())]);
        let line = |i: &Index| (!lines.is_empty()).then(|| lines[i.index(lines.len())]);
        match self {
            Mutation::DeleteToken(i) => {
                if let Some(span) = token(i) {
                    splice(bytes, span, b"");
                }
            }
            Mutation::DuplicateToken(i) => {
                if let Some((s, e)) = token(i) {
                    let copy = [&bytes[s..e], b" "].concat();
                    splice(bytes, (s, s), &copy);
                }
            }
            Mutation::ReplaceToken(i, with) => {
                if let Some(span) = token(i) {
                    splice(bytes, span, with.as_bytes());
                }
            }
            Mutation::InsertToken(i, with) => {
                let at = token(i).map_or(0, |(s, _)| s);
                splice(bytes, (at, at), format!("{with} ").as_bytes());
            }
            Mutation::DeleteLine(i) => {
                if let Some(span) = line(i) {
                    splice(bytes, span, b"");
                }
            }
            Mutation::DuplicateLine(i) => {
                if let Some((s, e)) = line(i) {
                    let mut copy = bytes[s..e].to_vec();
                    if copy.last() != Some(&b'\n') {
                        copy.insert(0, b'\n');
                    }
                    splice(bytes, (e, e), &copy);
                }
            }
            Mutation::SwapLines(a, b) => {
                if let (Some(a), Some(b)) = (line(a), line(b)) {
                    let (first, second) = if a.0 <= b.0 { (a, b) } else { (b, a) };
                    if first.1 <= second.0 {
                        let (x, y) = (bytes[first.0..first.1].to_vec(), bytes[second.0..second.1].to_vec());
                        splice(bytes, second, &x);
                        splice(bytes, first, &y);
                    }
                }
            }
            Mutation::InsertBytes(i, with) => {
                let at = i.index(bytes.len() + 1);
                splice(bytes, (at, at), with);
            }
            Mutation::Truncate(i) => {
                let at = i.index(bytes.len() + 1);
                bytes.truncate(at);
            }
        }
    }
}

/// A replacement token: numbers of every kind, keywords and punctuation of the
/// three formats, and odd text.
fn garbage() -> BoxedStrategy<String> {
    prop_oneof![
        3 => number(Mode::Wild),
        2 => prop::sample::select(vec![
            "v", "f", "s", "p", "pp", "c", "l", "b", "vn", "vt", "o", "g", "usemtl", "mtllib", "newmtl", "Kd", "Ns", "d",
            "from", "at", "up", "angle", "hither", "resolution", "[[object]]", "[[light]]", "[image]", "[camera]",
            "[render]", "[[include]]", "[material.a]", "type", "=", "[", "]", "{", "}", ",", "\"", "'", "#", "/", "//",
            "1/2/3", "-1//-1", "\"sphere\"", "\"mesh\"", "true", "\"\"\"", "\\", "\u{0}", "\r", "é", "\u{202e}", "\u{feff}",
        ])
        .prop_map(String::from),
        1 => "\\PC{0,12}",
        1 => "[ -~]{0,6}",
    ]
    .boxed()
}

fn mutation() -> impl Strategy<Value = Mutation> {
    prop_oneof![
        2 => index().prop_map(Mutation::DeleteToken),
        1 => index().prop_map(Mutation::DuplicateToken),
        3 => (index(), garbage()).prop_map(|(i, g)| Mutation::ReplaceToken(i, g)),
        2 => (index(), garbage()).prop_map(|(i, g)| Mutation::InsertToken(i, g)),
        1 => index().prop_map(Mutation::DeleteLine),
        1 => index().prop_map(Mutation::DuplicateLine),
        1 => (index(), index()).prop_map(|(a, b)| Mutation::SwapLines(a, b)),
        1 => (index(), prop::collection::vec(any::<u8>(), 1..6)).prop_map(|(i, b)| Mutation::InsertBytes(i, b)),
        1 => index().prop_map(Mutation::Truncate),
    ]
}

/// A file from `text` with up to four mutations, or now and then pure noise.
fn mutated(text: BoxedStrategy<String>, alphabet: &'static str) -> BoxedStrategy<Bytes> {
    // A third untouched, a third with one change, a third with two to four.
    let mutations = prop_oneof![Just(Vec::new()), prop::collection::vec(mutation(), 1..2), prop::collection::vec(mutation(), 2..5)];
    let near_valid = (text, mutations).prop_map(|(text, mutations)| {
        let mut bytes = text.into_bytes();
        for m in &mutations {
            m.apply(&mut bytes);
        }
        Bytes(bytes)
    });
    prop_oneof![
        16 => near_valid,
        1 => prop::collection::vec(any::<u8>(), 0..400).prop_map(Bytes),
        1 => prop::collection::vec(prop::sample::select(alphabet.as_bytes().to_vec()), 0..400).prop_map(Bytes),
    ]
    .boxed()
}

/// How far from valid a generated file starts out (mutations come on top).
#[derive(Debug, Clone, Copy, PartialEq)]
enum Mode {
    /// Every value in range and every required key there: the file mostly
    /// loads, so mutations reach the checks after parsing.
    Sane,
    /// Numbers often NaN, infinite, huge, tiny, negative or not numbers; keys
    /// missing or where they do not belong.
    Wild,
}

fn decimal(range: std::ops::Range<f64>) -> BoxedStrategy<String> {
    range.prop_map(|v| format!("{v:.3}")).boxed()
}

/// A number as text.
fn number(mode: Mode) -> BoxedStrategy<String> {
    let sane = prop_oneof![3 => decimal(-10.0..10.0), 1 => (-5i64..10).prop_map(|v| v.to_string())];
    match mode {
        Mode::Sane => sane.boxed(),
        Mode::Wild => prop_oneof![
            6 => sane,
            3 => prop::sample::select(vec![
                "0", "-0", "1", "-1", "0.0", "nan", "NaN", "-nan", "inf", "-inf", "+inf", "infinity", "1e39", "-1e39",
                "3e38", "3.4e38", "-3.4e38", "1e30", "1e20", "1e-20", "1e-40", "1e-45", "1e308", "1e309", "100000",
                "16384", "16385", "65536", "4294967296", "18446744073709551616", "-2147483648", "9223372036854775807",
                "1e", "1.2.3", "--1", "+", ".", "0x10", "1_000", "x",
            ])
            .prop_map(String::from),
            1 => any::<f32>().prop_map(|v| v.to_string()),
            1 => any::<f64>().prop_map(|v| format!("{v:e}")),
            1 => any::<i64>().prop_map(|v| v.to_string()),
        ]
        .boxed(),
    }
}

/// A number that should be positive (a radius, a colour component).
fn positive(mode: Mode) -> BoxedStrategy<String> {
    match mode {
        Mode::Sane => decimal(0.05..5.0),
        Mode::Wild => number(mode),
    }
}

fn numbers(mode: Mode, n: usize) -> BoxedStrategy<String> {
    prop::collection::vec(number(mode), n).prop_map(|v| v.join(" ")).boxed()
}

fn positives(mode: Mode, n: usize) -> BoxedStrategy<String> {
    prop::collection::vec(positive(mode), n).prop_map(|v| v.join(" ")).boxed()
}

/// `value` with probability `p`, which may be 1 (proptest's own `weighted`
/// wants it below 1).
fn maybe<T: fmt::Debug + Clone + 'static>(p: f64, value: BoxedStrategy<T>) -> BoxedStrategy<Option<T>> {
    if p >= 1.0 { value.prop_map(Some).boxed() } else { prop::option::weighted(p, value).boxed() }
}

/// A generator of a file's text.
type Generator = fn(Mode) -> BoxedStrategy<String>;

/// Either mode's version of a generator.
fn both_modes(generator: Generator) -> BoxedStrategy<String> {
    prop_oneof![generator(Mode::Sane), generator(Mode::Wild)].boxed()
}

/// The presence of an optional field: Sane keeps it or leaves it out, Wild
/// also drops required ones.
fn presence(mode: Mode, required: bool) -> f64 {
    match (mode, required) {
        (Mode::Sane, true) => 1.0,
        (Mode::Wild, true) => 0.95,
        (_, false) => 0.5,
    }
}

// ---------------------------------------------------------------------------
// NFF

fn nff_view(mode: Mode) -> BoxedStrategy<String> {
    let field = move |name: &'static str, value: BoxedStrategy<String>| {
        maybe(presence(mode, name != "hither"), value).prop_map(move |v| v.map(|v| format!("{name} {v}")))
    };
    let resolution = match mode {
        Mode::Sane => (1u32..40, 2u32..40).prop_map(|(w, h)| format!("{w} {h}")).boxed(),
        Mode::Wild => prop_oneof![numbers(mode, 2), (0i64..40, 0i64..40).prop_map(|(w, h)| format!("{w} {h}"))].boxed(),
    };
    let angle = match mode {
        Mode::Sane => decimal(5.0..170.0),
        Mode::Wild => number(mode),
    };
    (
        field("from", prop_oneof![Just("0 0 5".to_string()), numbers(mode, 3)].boxed()),
        field("at", prop_oneof![Just("0 0 0".to_string()), numbers(mode, 3)].boxed()),
        field("up", prop_oneof![Just("0 1 0".to_string()), numbers(mode, 3)].boxed()),
        field("angle", angle),
        field("hither", positive(mode)),
        field("resolution", resolution),
        any::<bool>(),
        prop::sample::select(vec![" ", "\n"]),
    )
        .prop_map(|(a, b, c, d, e, f, reverse, sep)| {
            let mut fields: Vec<String> = [a, b, c, d, e, f].into_iter().flatten().collect();
            if reverse {
                fields.reverse();
            }
            format!("v{sep}{}", fields.join(sep))
        })
        .boxed()
}

fn nff_statement(mode: Mode) -> BoxedStrategy<String> {
    let counted = move |keyword: &'static str, per_vertex: BoxedStrategy<String>| {
        let corners = if mode == Mode::Sane { 3..8 } else { 0..8 };
        (prop::collection::vec(per_vertex, corners), maybe(if mode == Mode::Sane { 1.0 } else { 0.8 }, Just(()).boxed()), 0usize..8)
            .prop_map(move |(vertices, honest, claimed)| {
                let n = if honest.is_some() { vertices.len() } else { claimed };
                format!("{keyword} {n}\n{}", vertices.join("\n"))
            })
    };
    // Vertices of a polygon in a plane z = const, as SPD files mostly have.
    let planar = (number(mode), number(mode), number(mode)).prop_map(|(x, y, _)| format!("{x} {y} 1"));
    let patch_vertex = (numbers(mode, 3), numbers(mode, 3)).prop_map(|(v, n)| format!("{v} {n}"));
    prop_oneof![
        1 => positives(mode, 3).prop_map(|c| format!("b {c}")),
        2 => (numbers(mode, 3), prop::option::of(positives(mode, 3)))
            .prop_map(|(p, c)| format!("l {p} {}", c.unwrap_or_default())),
        2 => (positives(mode, 3), positives(mode, 4), positive(mode)).prop_map(|(c, k, ior)| format!("f {c} {k} {ior}")),
        2 => (numbers(mode, 3), positive(mode), numbers(mode, 3), positive(mode))
            .prop_map(|(b, br, a, ar)| format!("c\n{b} {br}\n{a} {ar}")),
        4 => (numbers(mode, 3), positive(mode)).prop_map(|(c, r)| format!("s {c} {r}")),
        2 => counted("p", planar.boxed()),
        1 => counted("p", numbers(mode, 3)),
        2 => counted("pp", patch_vertex.boxed()),
        1 => "[ -~]{0,20}".prop_map(|c| format!("# {c}")),
    ]
    .boxed()
}

fn nff_text(mode: Mode) -> BoxedStrategy<String> {
    (maybe(presence(mode, true), nff_view(mode)), prop::collection::vec(nff_statement(mode), 0..10), 0usize..10)
        .prop_map(|(view, statements, view_at)| {
            let mut lines = statements;
            if let Some(v) = view {
                let at = view_at.min(lines.len());
                lines.insert(at, v);
            }
            lines.join("\n") + "\n"
        })
        .boxed()
}

// ---------------------------------------------------------------------------
// TOML

/// A TOML number; Wild also gives values of other types.
fn toml_number(mode: Mode) -> BoxedStrategy<String> {
    let spelt = |n: String| match n.as_str() {
        // The TOML spelling, so that they reach the loader.
        "NaN" | "-nan" => "nan".to_string(),
        "infinity" => "inf".to_string(),
        _ => n,
    };
    match mode {
        Mode::Sane => number(mode),
        Mode::Wild => prop_oneof![
            12 => number(mode).prop_map(spelt),
            1 => Just("\"1\"".to_string()),
            1 => Just("[1, 2, 3]".to_string()),
            1 => Just("true".to_string()),
        ]
        .boxed(),
    }
}

fn toml_positive(mode: Mode) -> BoxedStrategy<String> {
    match mode {
        Mode::Sane => positive(mode),
        Mode::Wild => toml_number(mode),
    }
}

fn toml_unit(mode: Mode) -> BoxedStrategy<String> {
    match mode {
        Mode::Sane => decimal(0.0..1.0),
        Mode::Wild => toml_number(mode),
    }
}

fn toml_array(values: BoxedStrategy<String>, lengths: std::ops::Range<usize>) -> BoxedStrategy<String> {
    prop::collection::vec(values, lengths).prop_map(|v| format!("[{}]", v.join(", "))).boxed()
}

/// Three values; Wild also gives other lengths and bare numbers.
fn toml_triple(mode: Mode, value: fn(Mode) -> BoxedStrategy<String>) -> BoxedStrategy<String> {
    match mode {
        Mode::Sane => toml_array(value(mode), 3..4),
        Mode::Wild => prop_oneof![12 => toml_array(value(mode), 3..4), 1 => toml_array(value(mode), 0..6), 1 => value(mode)].boxed(),
    }
}

fn toml_point(mode: Mode) -> BoxedStrategy<String> {
    toml_triple(mode, toml_number)
}

fn toml_colour(mode: Mode) -> BoxedStrategy<String> {
    prop_oneof![4 => toml_triple(mode, toml_unit), 1 => toml_unit(mode)].boxed()
}

/// A string from `valid`; Wild also picks from `invalid`, or a number.
fn toml_choice(mode: Mode, valid: &[&'static str], invalid: &[&'static str]) -> BoxedStrategy<String> {
    let quoted = |choices: Vec<&'static str>| prop::sample::select(choices).prop_map(|s| format!("\"{s}\""));
    match mode {
        Mode::Sane => quoted(valid.to_vec()).boxed(),
        Mode::Wild => prop_oneof![8 => quoted([valid, invalid].concat()), 1 => toml_number(mode)].boxed(),
    }
}

fn toml_bool(mode: Mode) -> BoxedStrategy<String> {
    match mode {
        Mode::Sane => any::<bool>().prop_map(|b| b.to_string()).boxed(),
        Mode::Wild => prop_oneof![4 => any::<bool>().prop_map(|b| b.to_string()), 1 => toml_number(mode)].boxed(),
    }
}

/// A key, whether it must be there, and its value.
type Field = (&'static str, bool, BoxedStrategy<String>);

/// A table: `header`, then its fields, each there or not as `mode` has it.
/// Wild also adds a field from `foreign` (keys of other tables) now and then.
fn toml_table(mode: Mode, header: String, fields: Vec<Field>) -> BoxedStrategy<String> {
    let mut lines: Vec<BoxedStrategy<Option<String>>> = fields
        .into_iter()
        .map(|(key, required, value)| {
            maybe(presence(mode, required), value).prop_map(move |v| v.map(|v| format!("{key} = {v}"))).boxed()
        })
        .collect();
    if mode == Mode::Wild {
        let foreign = prop::sample::select(vec!["radius", "center", "path", "fov", "color", "type", "width", "spp", "matrix"]);
        lines.push(prop::option::weighted(0.05, (foreign, toml_number(mode))).prop_map(|f| f.map(|(k, v)| format!("{k} = {v}"))).boxed());
    }
    lines
        .prop_map(move |lines| {
            let body: Vec<String> = lines.into_iter().flatten().collect();
            format!("{header}\n{}\n", body.join("\n"))
        })
        .boxed()
}

fn toml_size(mode: Mode) -> BoxedStrategy<String> {
    match mode {
        Mode::Sane => (1u32..64).prop_map(|v| v.to_string()).boxed(),
        Mode::Wild => prop_oneof![4 => (1i64..64).prop_map(|v| v.to_string()), 1 => toml_number(mode)].boxed(),
    }
}

fn toml_camera(mode: Mode) -> BoxedStrategy<String> {
    let fov = match mode {
        Mode::Sane => decimal(1.0..170.0),
        Mode::Wild => toml_number(mode),
    };
    let eye = prop_oneof![Just("[0, 0, 5]".to_string()), toml_point(mode)].boxed();
    let perspective = toml_table(
        mode,
        "[camera]".into(),
        vec![
            ("type", false, Just("\"perspective\"".to_string()).boxed()),
            ("eye", true, eye.clone()),
            ("look_at", true, prop_oneof![Just("[0, 0, 0]".to_string()), toml_point(mode)].boxed()),
            ("up", false, toml_point(mode)),
            ("fov", true, fov),
        ],
    );
    let orthographic = toml_table(
        mode,
        "[camera]".into(),
        vec![
            ("type", true, toml_choice(mode, &["orthographic"], &["fisheye"])),
            ("eye", true, eye),
            ("look_at", true, Just("[0, 0, 0]".to_string()).boxed()),
            ("height", true, toml_positive(mode)),
        ],
    );
    prop_oneof![3 => perspective, 1 => orthographic].boxed()
}

fn toml_light(mode: Mode) -> BoxedStrategy<String> {
    let common = move || -> Vec<Field> {
        vec![
            ("color", false, toml_colour(mode)),
            ("intensity", false, toml_positive(mode)),
            ("enabled", false, toml_bool(mode)),
        ]
    };
    let point = {
        let mut fields = vec![("type", true, toml_choice(mode, &["point"], &["spot"])), ("position", true, toml_point(mode))];
        fields.extend(common());
        fields.push(("attenuation", false, toml_choice(mode, &["none", "inverse_square"], &["polynomial"])));
        toml_table(mode, "[[light]]".into(), fields)
    };
    let polynomial = {
        let mut fields = vec![
            ("type", true, Just("\"point\"".to_string()).boxed()),
            ("position", true, toml_point(mode)),
            ("attenuation", true, toml_choice(mode, &["polynomial"], &["linear", "none"])),
            ("coefficients", true, toml_triple(mode, toml_positive)),
        ];
        fields.extend(common());
        toml_table(mode, "[[light]]".into(), fields)
    };
    let directional = {
        let mut fields = vec![("type", true, Just("\"directional\"".to_string()).boxed()), ("direction", true, toml_point(mode))];
        fields.extend(common());
        toml_table(mode, "[[light]]".into(), fields)
    };
    prop_oneof![point, polynomial, directional].boxed()
}

fn toml_material(mode: Mode, name: &'static str) -> BoxedStrategy<String> {
    let shininess = match mode {
        Mode::Sane => decimal(0.0..200.0),
        Mode::Wild => toml_number(mode),
    };
    let ior = match mode {
        Mode::Sane => decimal(1.0..2.5),
        Mode::Wild => toml_number(mode),
    };
    toml_table(
        mode,
        format!("[material.{name}]"),
        vec![
            ("color", true, toml_colour(mode)),
            ("ka", false, toml_unit(mode)),
            ("kd", false, toml_unit(mode)),
            ("ks", false, toml_unit(mode)),
            ("shininess", false, shininess),
            ("specular_color", false, toml_colour(mode)),
            ("model", false, toml_choice(mode, &["phong", "blinn"], &["ward"])),
            ("metallic", false, toml_colour(mode)),
            ("reflect", false, toml_colour(mode)),
            ("transmit", false, toml_colour(mode)),
            ("ior", false, ior),
            ("fresnel", false, toml_bool(mode)),
        ],
    )
}

fn toml_object(mode: Mode) -> BoxedStrategy<String> {
    let table = move |kind: BoxedStrategy<String>, mut fields: Vec<Field>| {
        fields.insert(0, ("type", true, kind));
        fields.push(("material", false, toml_choice(mode, &["a"], &["b", "c"])));
        toml_table(mode, "[[object]]".into(), fields)
    };
    let kind = move |kind: &'static str| toml_choice(mode, &[kind], &["torus", "sphere", "mesh"]);
    let planar = (toml_number(mode), toml_number(mode)).prop_map(|(x, y)| format!("[{x}, {y}, 1]"));
    let sphere = table(kind("sphere"), vec![("center", true, toml_point(mode)), ("radius", true, toml_positive(mode))]);
    let triangle = table(
        kind("triangle"),
        vec![
            ("vertices", true, toml_array(toml_point(mode), 3..4)),
            ("normals", false, toml_array(toml_point(mode), 3..4)),
        ],
    );
    let corners = if mode == Mode::Sane { 3..8 } else { 0..8 };
    let polygon = table(kind("polygon"), vec![("vertices", true, toml_array(planar.boxed(), corners))]);
    // A cylinder's apex radius defaults to its base radius; a cone needs one.
    let cone = |kind_name: &'static str, apex_radius_required: bool| {
        table(
            kind(kind_name),
            vec![
                ("base", true, toml_point(mode)),
                ("base_radius", true, toml_positive(mode)),
                ("apex", true, toml_point(mode)),
                ("apex_radius", apex_radius_required, toml_positive(mode)),
            ],
        )
    };
    let scale = prop_oneof![toml_positive(mode), toml_triple(mode, toml_positive)].boxed();
    let rows = match mode {
        Mode::Sane => (toml_number(mode), toml_number(mode), toml_number(mode))
            .prop_map(|(x, y, z)| format!("[[1, 0, 0, {x}], [0, 2, 0, {y}], [0, 0, 1, {z}], [0, 0, 0, 1]]"))
            .boxed(),
        Mode::Wild => toml_array(toml_array(toml_number(mode), 3..5), 3..5),
    };
    let path = toml_choice(mode, &["cube.obj", "flat.obj"], &["missing.obj", "part.nff", ".", "cube.mtl"]);
    let mesh = table(
        kind("mesh"),
        vec![
            ("path", true, path.clone()),
            ("translate", false, toml_point(mode)),
            ("rotate", false, toml_point(mode)),
            ("scale", false, scale),
        ],
    );
    let mesh_matrix = table(kind("mesh"), vec![("path", true, path), ("matrix", true, rows)]);
    // Few subdivisions: 10 would make 20 million triangles a case.
    let subdivisions = match mode {
        Mode::Sane => (0u32..3).prop_map(|v| v.to_string()).boxed(),
        Mode::Wild => prop::sample::select(vec!["0", "1", "-1", "11", "1.5", "4294967296", "\"2\"", "nan"]).prop_map(String::from).boxed(),
    };
    let icosphere = table(
        kind("icosphere"),
        vec![
            ("center", true, toml_point(mode)),
            ("radius", true, toml_positive(mode)),
            ("subdivisions", true, subdivisions),
            ("displacement", false, if mode == Mode::Sane { decimal(0.0..0.5) } else { toml_number(mode) }),
        ],
    );
    prop_oneof![
        3 => sphere,
        2 => triangle,
        2 => polygon,
        1 => cone("cone", true),
        1 => cone("cylinder", false),
        2 => mesh,
        1 => mesh_matrix,
        1 => icosphere,
    ]
    .boxed()
}

fn toml_text(mode: Mode) -> BoxedStrategy<String> {
    let image = toml_table(
        mode,
        "[image]".into(),
        vec![("width", true, toml_size(mode)), ("height", true, toml_size(mode)), ("background", false, toml_colour(mode))],
    );
    let ambient = toml_table(mode, "[ambient]".into(), vec![("color", false, toml_colour(mode)), ("intensity", false, toml_positive(mode))]);
    let max_depth = match mode {
        Mode::Sane => (1u32..=16).prop_map(|v| v.to_string()).boxed(),
        Mode::Wild => toml_number(mode),
    };
    let render = toml_table(
        mode,
        "[render]".into(),
        vec![
            ("max_depth", false, max_depth),
            ("cutoff", false, toml_unit(mode)),
            ("shadows", false, toml_bool(mode)),
            ("shadow_mode", false, toml_choice(mode, &["opaque", "tinted"], &["soft"])),
            ("reflections", false, toml_bool(mode)),
            ("refractions", false, toml_bool(mode)),
        ],
    );
    let (near, far) = match mode {
        Mode::Sane => (decimal(0.0..5.0), decimal(5.5..50.0)),
        Mode::Wild => (toml_number(mode), toml_number(mode)),
    };
    let depth_cue = toml_table(
        mode,
        "[depth_cue]".into(),
        vec![
            ("color", true, toml_colour(mode)),
            ("near", true, near),
            ("far", true, far),
            ("near_scale", false, toml_unit(mode)),
            ("far_scale", true, toml_unit(mode)),
        ],
    );
    let include = toml_table(mode, "[[include]]".into(), vec![("path", true, toml_choice(mode, &["part.nff"], &["bad.nff", "missing.nff", "cube.obj"]))]);
    (
        image,
        toml_camera(mode),
        prop::option::of(ambient),
        prop::option::of(render),
        prop::option::weighted(0.2, depth_cue),
        prop::collection::vec(toml_light(mode), 0..3),
        toml_material(mode, "a"),
        prop::option::of(toml_material(mode, "b")),
        prop::collection::vec(toml_object(mode), 0..5),
        prop::collection::vec(include, 0..2),
    )
        .prop_map(|(image, camera, ambient, render, depth_cue, lights, a, b, objects, includes)| {
            let mut tables = vec![image, camera];
            tables.extend(ambient);
            tables.extend(render);
            tables.extend(depth_cue);
            tables.extend(lights);
            tables.push(a);
            tables.extend(b);
            tables.extend(objects);
            tables.extend(includes);
            tables.join("\n")
        })
        .boxed()
}

// ---------------------------------------------------------------------------
// OBJ and MTL

/// A face or line vertex: `v`, `v/vt`, `v//vn` or `v/vt/vn`. Sane indices name
/// the four positions, one texture coordinate and one normal every file starts with.
fn obj_reference(mode: Mode) -> BoxedStrategy<String> {
    let (v, other): (BoxedStrategy<i64>, BoxedStrategy<i64>) = match mode {
        Mode::Sane => (prop_oneof![1i64..=4, -4i64..=-1].boxed(), Just(1i64).boxed()),
        Mode::Wild => {
            let wild = || prop_oneof![8 => 1i64..9, 2 => -9i64..0, 1 => Just(0i64), 1 => any::<i64>()].boxed();
            (wild(), wild())
        }
    };
    (v, prop::option::of(other.clone()), prop::option::of(other))
        .prop_map(|(v, vt, vn)| match (vt, vn) {
            (None, None) => v.to_string(),
            (Some(t), None) => format!("{v}/{t}"),
            (None, Some(n)) => format!("{v}//{n}"),
            (Some(t), Some(n)) => format!("{v}/{t}/{n}"),
        })
        .boxed()
}

fn obj_text(mode: Mode) -> BoxedStrategy<String> {
    let position = match mode {
        Mode::Sane => prop_oneof![4 => numbers(mode, 3), 1 => (numbers(mode, 3), positive(mode)).prop_map(|(v, w)| format!("{v} {w}"))].boxed(),
        Mode::Wild => prop_oneof![8 => numbers(mode, 3), 1 => numbers(mode, 4), 1 => numbers(mode, 6), 1 => (0usize..8).prop_flat_map(move |n| numbers(mode, n))].boxed(),
    };
    let vertices = match mode {
        Mode::Sane => 3..7,
        Mode::Wild => 0..7,
    };
    let line = prop_oneof![
        6 => position.prop_map(|v| format!("v {v}")),
        1 => numbers(mode, 2).prop_map(|v| format!("vt {v}")),
        2 => numbers(mode, 3).prop_map(|v| format!("vn {v}")),
        8 => prop::collection::vec(obj_reference(mode), vertices).prop_map(|r| format!("f {}", r.join(" "))),
        1 => prop::collection::vec(obj_reference(mode), 2..4).prop_map(|r| format!("l {}", r.join(" "))),
        1 => prop::sample::select(vec!["o part", "g group", "usemtl a", "usemtl b", "s off", "o"]).prop_map(String::from),
        1 => "[ -~]{0,20}".prop_map(|c| format!("# {c}")),
    ];
    (
        prop::sample::select(if mode == Mode::Sane { vec!["mtllib m.mtl\n", ""] } else { vec!["mtllib m.mtl\n", "mtllib missing.mtl\n", "mtllib\n", ""] }),
        prop::collection::vec(line, 0..14),
    )
        .prop_map(move |(mtllib, lines)| {
            // Sane files have a face to frame for sure.
            let face = if mode == Mode::Sane { "f 1 2 3\n" } else { "" };
            format!("{mtllib}v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nvt 0 0\nvn 0 0 1\n{face}{}\n", lines.join("\n"))
        })
        .boxed()
}

fn mtl_text(mode: Mode) -> BoxedStrategy<String> {
    let colour = match mode {
        Mode::Sane => prop_oneof![4 => positives(mode, 3), 1 => positive(mode)].boxed(),
        Mode::Wild => prop_oneof![6 => numbers(mode, 3), 2 => numbers(mode, 1), 1 => (0usize..5).prop_flat_map(move |n| numbers(mode, n))].boxed(),
    };
    let scalar = match mode {
        Mode::Sane => positive(mode),
        Mode::Wild => prop_oneof![6 => numbers(mode, 1), 1 => (0usize..3).prop_flat_map(move |n| numbers(mode, n))].boxed(),
    };
    let illum = match mode {
        Mode::Sane => (0u32..11).prop_map(|v| v.to_string()).boxed(),
        Mode::Wild => prop_oneof![(-2i64..12).prop_map(|v| v.to_string()), number(mode)].boxed(),
    };
    let line = prop_oneof![
        1 => prop::sample::select(vec!["newmtl a", "newmtl b"]).prop_map(String::from),
        6 => (prop::sample::select(vec!["Ka", "Kd", "Ks", "Ke", "Tf"]), colour).prop_map(|(k, v)| format!("{k} {v}")),
        4 => (prop::sample::select(vec!["Ns", "Ni", "d", "Tr"]), scalar).prop_map(|(k, v)| format!("{k} {v}")),
        2 => illum.prop_map(|v| format!("illum {v}")),
        1 => prop::sample::select(if mode == Mode::Sane {
            vec!["map_Kd tex.png", "# a comment", "Pr 0.5"]
        } else {
            vec!["map_Kd tex.png", "map_Kd", "bump", "d -halo 0.5", "Kd spectral x.rfl", "newmtl"]
        })
        .prop_map(String::from),
    ];
    prop::collection::vec(line, 0..10).prop_map(|lines| format!("newmtl a\n{}\n", lines.join("\n"))).boxed()
}

// ---------------------------------------------------------------------------
// The oracle

/// A file of the case: its path and bytes, for checking the places errors name.
struct CaseFile {
    path: PathBuf,
    bytes: Vec<u8>,
}

fn write_case(dir: &Path, name: &str, bytes: &[u8]) -> CaseFile {
    let path = dir.join(name);
    std::fs::write(&path, bytes).expect("the case directory is writable");
    CaseFile { path, bytes: bytes.to_vec() }
}

/// An error must name a file of the case, a line inside it and, when it has
/// one, a column inside that line, and it must print as one line.
fn check_error(e: &LoadError, files: &[&CaseFile]) -> Result<(), TestCaseError> {
    let shown = e.to_string();
    prop_assert!(!shown.contains(['\n', '\r']), "the message is not one line: {shown:?}");
    prop_assert!(!e.message.trim().is_empty(), "no message: {shown:?}");
    let file = files.iter().find(|f| f.path == e.path);
    prop_assert!(file.is_some(), "the error names a file that is not part of the case: {shown}");
    let file = file.unwrap();
    let Some(location) = e.location else {
        return Err(TestCaseError::fail(format!("the error names no line: {shown}")));
    };
    prop_assert!(
        shown.starts_with(&format!("{}:{}", e.path.display(), location.line)),
        "the message does not start with file:line: {shown}"
    );
    let lines = line_spans(&file.bytes);
    prop_assert!(
        location.line >= 1 && location.line <= lines.len().max(1) + 1,
        "line {} outside the file's {} lines: {shown}",
        location.line,
        lines.len()
    );
    if let Some(column) = location.column {
        let text = lines.get(location.line - 1).map_or(&[][..], |&(s, e)| &file.bytes[s..e]);
        let chars = String::from_utf8_lossy(text).chars().count();
        prop_assert!(column >= 1 && column <= chars + 1, "column {column} outside a line of {chars} characters: {shown}");
    }
    Ok(())
}

fn finite_non_negative(v: Vec3) -> bool {
    v.is_finite() && v.min_element() >= 0.0
}

/// A loaded scene must be one the renderer can take as it is.
fn check_scene(scene: &Scene) -> Result<(), TestCaseError> {
    prop_assert!((1..=MAX_IMAGE_SIDE).contains(&scene.width) && (1..=MAX_IMAGE_SIDE).contains(&scene.height));
    let camera = &scene.camera;
    prop_assert!(camera.eye.is_finite() && camera.look_at.is_finite() && camera.up.is_finite(), "{camera:?}");
    let basis = camera.basis();
    prop_assert!(
        basis.is_some_and(|b| b.u.is_finite() && b.v.is_finite() && b.w.is_finite()),
        "the camera has no usable basis: {camera:?}"
    );
    match camera.projection {
        Projection::Perspective { fov_y_degrees } => prop_assert!(fov_y_degrees > 0.0 && fov_y_degrees < 180.0, "{camera:?}"),
        Projection::Orthographic { height } => prop_assert!(height > 0.0 && height.is_finite(), "{camera:?}"),
    }
    prop_assert!(finite_non_negative(scene.background) && finite_non_negative(scene.ambient), "{:?} {:?}", scene.background, scene.ambient);
    let r = &scene.render;
    prop_assert!((1..=MAX_DEPTH_LIMIT).contains(&r.max_depth) && (0.0..=1.0).contains(&r.cutoff), "{r:?}");
    if let Some(d) = &scene.depth_cue {
        prop_assert!(finite_non_negative(d.color) && d.near.is_finite() && d.far.is_finite() && d.far > d.near, "{d:?}");
        prop_assert!((0.0..=1.0).contains(&d.near_scale) && (0.0..=1.0).contains(&d.far_scale), "{d:?}");
    }
    for light in &scene.lights {
        match light.kind {
            LightKind::Point { position } => prop_assert!(position.is_finite(), "{light:?}"),
            LightKind::Directional { direction } => {
                prop_assert!(direction.is_finite() && (direction.length() - 1.0).abs() < 1e-4, "{light:?}")
            }
        }
        prop_assert!(finite_non_negative(light.radiance()), "the light's radiance is not finite: {light:?}");
        if let Attenuation::Polynomial { c1, c2, c3 } = light.attenuation {
            prop_assert!(finite_non_negative(Vec3::new(c1, c2, c3)) && c1 + c2 + c3 > 0.0, "{light:?}");
        }
    }
    prop_assert!(!scene.materials.is_empty(), "no materials");
    for m in &scene.materials {
        let scalars = [m.ambient, m.diffuse, m.specular, m.shininess];
        prop_assert!(scalars.iter().all(|v| v.is_finite() && *v >= 0.0), "{m:?}");
        prop_assert!(m.ior.is_finite() && m.ior > 0.0, "{m:?}");
        let colours = [Some(m.color), m.specular_color, m.metallic_f0, Some(m.reflect), Some(m.transmit)];
        prop_assert!(colours.iter().flatten().all(|c| finite_non_negative(*c)), "{m:?}");
    }
    for object in &scene.objects {
        prop_assert!(object.material < scene.materials.len(), "material {} of {}", object.material, scene.materials.len());
        prop_assert!(!object.shapes.is_empty(), "an object without shapes");
        for shape in &object.shapes {
            let (lo, hi) = shape.bounds();
            prop_assert!(lo.is_finite() && hi.is_finite(), "bounds are not finite: {shape:?}");
            match shape {
                Shape::Sphere { center, radius } => prop_assert!(center.is_finite() && *radius > 0.0, "{shape:?}"),
                Shape::Triangle { vertices, normals } => {
                    prop_assert!(vertices.iter().all(|v| v.is_finite()), "{shape:?}");
                    if let Some(ns) = normals {
                        prop_assert!(ns.iter().all(|n| n.is_finite() && (n.length() - 1.0).abs() < 1e-3), "{shape:?}");
                    }
                }
                Shape::Polygon { vertices } => {
                    prop_assert!(vertices.len() >= 3 && vertices.iter().all(|v| v.is_finite()), "{shape:?}")
                }
                Shape::Cone { base, base_radius, apex, apex_radius } => {
                    prop_assert!(base.is_finite() && apex.is_finite() && base != apex, "{shape:?}");
                    prop_assert!(*base_radius >= 0.0 && *apex_radius >= 0.0 && base_radius.max(*apex_radius) > 0.0, "{shape:?}");
                }
            }
        }
    }
    // The host half of rendering: none of it may panic on what a loader
    // accepted, and what it uploads keeps every index the kernels follow
    // inside its array.
    prop_assert!(scene.validate().is_ok(), "a loaded scene fails validation: {:?}", scene.validate());
    let bvh = Bvh::build(&primitive_bounds(scene));
    let gpu_bvh = bvh.gpu().map_err(|e| TestCaseError::fail(e.to_string()))?;
    let packed = pack(scene, &bvh.order, gpu_bvh);
    check_indices(&packed)?;
    let g = scene_uniforms(scene, scene.width, scene.height, packed.light_count, packed.bvh_root);
    let camera_values = [g.camera.u, g.camera.v, g.camera.w].concat();
    prop_assert!(
        camera_values.iter().chain([&g.camera.half_width, &g.camera.half_height]).all(|v| v.is_finite()),
        "the packed camera is not finite: {:?}",
        g.camera
    );
    Ok(())
}

fn check_outcome(outcome: Result<Scene, LoadError>, files: &[&CaseFile], tally: &Tally) -> Result<(), TestCaseError> {
    match outcome {
        Err(e) => {
            tally.errors.fetch_add(1, Ordering::Relaxed);
            check_error(&e, files)
        }
        Ok(scene) => {
            tally.scenes.fetch_add(1, Ordering::Relaxed);
            check_scene(&scene)
        }
    }
}

// ---------------------------------------------------------------------------
// The targets

const NFF_ALPHABET: &str = "vbflcsp 0123456789.-e\n#fromatupanglehitresolution";
const TOML_ALPHABET: &str = "[]{}=,.\"'# \n0123456789-+eabcdefghijklmnopqrstuvwxyz_";
const OBJ_ALPHABET: &str = "vtnfolgsu /0123456789.-e\n#mtlib";

#[test]
fn fuzz_nff() {
    let dir = tempfile::tempdir().unwrap();
    run_target("nff", mutated(both_modes(nff_text), NFF_ALPHABET), |input, tally| {
        let scene = write_case(dir.path(), "case.nff", &input.0);
        check_outcome(glint_scene::load(&scene.path), &[&scene], tally)
    });
}

/// Files a generated TOML scene may name, beside it.
fn toml_companions(dir: &Path) -> Vec<CaseFile> {
    vec![
        write_case(dir, "cube.obj", b"mtllib cube.mtl\nv 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nusemtl red\nf 1 2 3 4\nvn 0 0 1\nf 1//1 3//1 4//1\n"),
        write_case(dir, "cube.mtl", b"newmtl red\nKd 0.8 0.1 0.1\nKs 0.5 0.5 0.5\nNs 50\nillum 3\n"),
        // Only degenerate faces: a mesh that contributes nothing, with a warning.
        write_case(dir, "flat.obj", b"v 0 0 0\nv 1 1 1\nv 2 2 2\nf 1 2 3\n"),
        write_case(dir, "part.nff", b"l 1 2 3\nf 0 1 0 1 0 0 0 1\ns 0 0 0 1\np 3\n0 0 0\n1 0 0\n0 1 0\n"),
        write_case(dir, "bad.nff", b"s 0 0 0 1\ns 0 0\n"),
    ]
}

#[test]
fn fuzz_toml() {
    let dir = tempfile::tempdir().unwrap();
    let companions = toml_companions(dir.path());
    run_target("toml", mutated(both_modes(toml_text), TOML_ALPHABET), |input, tally| {
        let scene = write_case(dir.path(), "scene.toml", &input.0);
        let mut files: Vec<&CaseFile> = companions.iter().collect();
        files.push(&scene);
        check_outcome(glint_scene::load(&scene.path), &files, tally)
    });
}

#[test]
fn fuzz_obj() {
    let dir = tempfile::tempdir().unwrap();
    let strategy = (mutated(both_modes(obj_text), OBJ_ALPHABET), mutated(both_modes(mtl_text), "newmtlKadsNiTrf 0123456789.-e\n#"));
    run_target("obj", strategy, |(obj, mtl), tally| {
        let mtl = write_case(dir.path(), "m.mtl", &mtl.0);
        let mesh = write_case(dir.path(), "m.obj", &obj.0);
        check_outcome(glint_scene::load(&mesh.path), &[&mesh, &mtl], tally)?;
        // The same mesh placed twice in a TOML scene, transformed.
        let scene = write_case(
            dir.path(),
            "m.toml",
            b"[image]\nwidth = 8\nheight = 8\n[camera]\neye = [0, 0, 5]\nlook_at = [0, 0, 0]\nfov = 40\n\
              [[object]]\ntype = \"mesh\"\npath = \"m.obj\"\nscale = [2, 1e-3, 3]\nrotate = [10, 20, 30]\n\
              [[object]]\ntype = \"mesh\"\npath = \"m.obj\"\nmaterial = \"x\"\n[material.x]\ncolor = 1\n",
        );
        check_outcome(glint_scene::load(&scene.path), &[&mesh, &mtl, &scene], tally)
    });
}

/// Inputs the fuzzers found, shrunk, that failed before their fix: each is a
/// set of files, the first of which is loaded. Inputs that are malformed are
/// also in the bad-input corpus, `tests/bad_input/`.
const REGRESSIONS: &[&[(&str, &[u8])]] = &[
    // An NFF patch normal of (3e38, 0, 0): its f32 length overflowed to infinity
    // and the normal was "normalised" to zero, a smooth triangle with a zero normal.
    &[(
        "patch.nff",
        b"v from 0 0 5 at 0 0 0 up 0 1 0 angle 5.000 resolution 1 2\nf 0.050 0.050 0.050 0.050 0.050 0.050 0.050 0.050\n\
          # A\npp 4\n0.000 0.000 0.000 3e38 0.000 0.000\n0.000 0.000 0.000 0.000 0.000 5.427\n\
          0.000 0.000 -7.484 0.000 0.000 -5.896\n0.000 8.091 0.000 0.000 0.000 5.269\n",
    )],
    // A relative texture index before the first one: `tobj` multiplies it and
    // overflows (a panic in a debug build). Also tests/bad_input/obj_face_texcoord_before_first.obj.
    &[("vt.obj", b"v 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0 0\nf 1/-5 2/-5 3/-5\n")],
    // An MTL colour of one value (a grey) or two: `tobj` unwraps a short array
    // and panics. Also tests/bad_input/obj_mtl_color_two_values.obj.
    &[("grey.obj", b"mtllib grey.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nusemtl a\nf 1 2 3\n"), ("grey.mtl", b"newmtl a\nKd 0.5\n")],
    &[("pair.obj", b"mtllib pair.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nusemtl a\nf 1 2 3\n"), ("pair.mtl", b"newmtl a\nKs 1 0\n")],
];

#[test]
fn regressions() {
    for (i, files) in REGRESSIONS.iter().enumerate() {
        let dir = tempfile::tempdir().unwrap();
        let written: Vec<CaseFile> = files.iter().map(|(name, bytes)| write_case(dir.path(), name, bytes)).collect();
        let refs: Vec<&CaseFile> = written.iter().collect();
        let outcome = glint_scene::load(&written[0].path);
        if let Err(e) = check_outcome(outcome, &refs, &Tally::default()) {
            panic!("regression {i} ({}): {e}", files[0].0);
        }
    }
}

// ---------------------------------------------------------------------------
// The harness itself

#[test]
fn mutations_do_what_they_say() {
    let apply = |m: Mutation, text: &str| {
        let mut bytes = text.as_bytes().to_vec();
        m.apply(&mut bytes);
        bytes
    };
    let i = Index;
    assert_eq!(apply(Mutation::DeleteToken(i(2)), "s 1 2\n"), b"s 1 \n");
    assert_eq!(apply(Mutation::DeleteToken(i(5)), "s 1 2\n"), b"s 1 \n", "positions wrap around");
    assert_eq!(apply(Mutation::DuplicateToken(i(0)), "s 1\n"), b"s s 1\n");
    assert_eq!(apply(Mutation::ReplaceToken(i(2), "nan".into()), "s 1 2\n"), b"s 1 nan\n");
    assert_eq!(apply(Mutation::InsertToken(i(1), "x".into()), "s 1\n"), b"s x 1\n");
    assert_eq!(apply(Mutation::DeleteLine(i(0)), "a\nb\n"), b"b\n");
    assert_eq!(apply(Mutation::DuplicateLine(i(1)), "a\nb"), b"a\nb\nb");
    assert_eq!(apply(Mutation::SwapLines(i(1), i(0)), "a\nbb\n"), b"bb\na\n");
    assert_eq!(apply(Mutation::InsertBytes(i(0), vec![0xff]), "ab"), b"\xffab");
    assert_eq!(apply(Mutation::Truncate(i(1)), "abc"), b"a");
    assert_eq!(apply(Mutation::Truncate(i(3)), "abc"), b"abc");
}

#[test]
fn the_oracle_rejects_what_it_should() {
    let dir = tempfile::tempdir().unwrap();
    let file = write_case(dir.path(), "x.nff", b"s 0 0 0 1\n");
    let at = |line, column| Some(glint_scene::Location { line, column });
    let ok = LoadError::new(&file.path, at(1, Some(3)), "fine");
    assert!(check_error(&ok, &[&file]).is_ok());
    for bad in [
        LoadError::new(&file.path, None, "no line"),
        LoadError::new(&file.path, at(3, None), "past the end"),
        LoadError::new(&file.path, at(1, Some(12)), "past the end of the line"),
        LoadError::new(Path::new("elsewhere.nff"), at(1, None), "another file"),
        LoadError::new(&file.path, at(1, None), ""),
    ] {
        assert!(check_error(&bad, &[&file]).is_err(), "{bad}");
    }
}

/// Sane files, before mutation, must mostly load: otherwise the fuzzers would
/// spend their time in the parsers' first error and never reach the checks
/// after parsing, the BVH or the packing.
#[test]
fn sane_files_mostly_load() {
    use proptest::strategy::ValueTree;
    let dir = tempfile::tempdir().unwrap();
    toml_companions(dir.path());
    write_case(dir.path(), "m.mtl", b"newmtl a\nKd 1 0 0\n");
    let mut runner = TestRunner::deterministic();
    let targets: [(&str, Generator, &str); 4] =
        [("nff", nff_text, "case.nff"), ("toml", toml_text, "scene.toml"), ("obj", obj_text, "case.obj"), ("mtl", mtl_text, "m.mtl")];
    for (name, make, file) in targets {
        let mut errors = Vec::new();
        for _ in 0..200 {
            let text = make(Mode::Sane).new_tree(&mut runner).unwrap().current();
            let case = write_case(dir.path(), file, text.as_bytes());
            let loaded = if name == "mtl" {
                let obj = write_case(dir.path(), "case.obj", b"mtllib m.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nusemtl a\nf 1 2 3\n");
                glint_scene::load(&obj.path)
            } else {
                glint_scene::load(&case.path)
            };
            if let Err(e) = loaded {
                errors.push(e.to_string());
            }
        }
        assert!(errors.len() <= 20, "{name}: {} of 200 sane files fail to load, e.g. {:?}", errors.len(), &errors[..3.min(errors.len())]);
    }
}

/// Walks every BVH record reachable from the root, as any traversal might
/// (the kernel's stack holds each level's far child: never deeper than
/// `BVH_STACK`), and checks each index the kernels read: child records, leaf
/// primitive ranges, materials, polygon vertices and vertex normals.
fn check_indices(scene: &GpuScene) -> Result<(), TestCaseError> {
    let mut pending = vec![(scene.bvh_root, 0usize)];
    while let Some((reference, depth)) = pending.pop() {
        prop_assert!(depth <= BVH_STACK as usize, "a path {depth} deep overflows the traversal stack");
        let record = (reference & !LEAF) as usize;
        prop_assert!(record < scene.nodes.len(), "record {record} of {}", scene.nodes.len());
        let node = scene.nodes[record];
        if reference & LEAF != 0 {
            let (first, count) = (node.quantized[0] as usize, node.quantized[1] as usize);
            prop_assert!(first + count <= scene.prims.len(), "leaf {first}+{count} of {} primitives", scene.prims.len());
            for p in &scene.prims[first..first + count] {
                let (kind, material) = (p.kind_material & 0xff, (p.kind_material >> 8) as usize);
                prop_assert!(material < scene.materials.len(), "material {material} of {}", scene.materials.len());
                let points = p.first as usize + p.count as usize;
                if kind == PRIM_POLYGON {
                    prop_assert!(p.count >= 3 && points <= scene.points.len(), "polygon {}+{} of {} points", p.first, p.count, scene.points.len());
                }
                if kind == PRIM_TRIANGLE && p.count == 3 {
                    prop_assert!(points <= scene.points.len(), "normals {}+3 of {} points", p.first, scene.points.len());
                }
            }
        } else {
            let first = node.children & !(LEAF | RIGHT_LEAF);
            for (child, leaf_flag) in [(first, LEAF), (first + 1, RIGHT_LEAF)] {
                let is_leaf = node.children & leaf_flag != 0;
                pending.push((child | if is_leaf { LEAF } else { 0 }, depth + 1));
            }
        }
    }
    prop_assert!(!scene.materials.is_empty() && !scene.lights.is_empty() && !scene.points.is_empty(), "an empty binding");
    Ok(())
}
