//! Fuzzing of the scene loaders, as property tests that run with the rest of
//! the suite (cargo-fuzz needs a nightly toolchain; these need nothing).
//!
//! Each target builds near-valid files from a structured generator (TOML
//! tables, NFF and Rayshade statements, OBJ and MTL lines, with numbers that are often NaN,
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

mod generate;
mod mutate;
mod oracle;

use std::fmt;
use std::path::Path;
use std::sync::atomic::{AtomicU64, Ordering};
use std::time::{Duration, Instant};

use glam::Vec3;
use glint_scene::{LoadError, Shape};
use proptest::prelude::*;
use proptest::test_runner::{Config, RngSeed, TestCaseError, TestRunner};

use generate::{both_modes, Generator, mtl_text, nff_text, obj_text, ray_text, toml_object, toml_text, Mode};
use mutate::{mutated, Index, Mutation};
use oracle::{check_error, check_outcome, check_scene, write_case, CaseFile};

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
// The targets

const NFF_ALPHABET: &str = "vbflcsp 0123456789.-e\n#fromatupanglehitresolution";
const RAY_ALPHABET: &str = "eyplokfvscrnbgdtiamhu 0123456789.-e\n/*";
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

#[test]
fn fuzz_rayshade() {
    let dir = tempfile::tempdir().unwrap();
    run_target("rayshade", mutated(both_modes(ray_text), RAY_ALPHABET), |input, tally| {
        let scene = write_case(dir.path(), "case.ray", &input.0);
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
    // A Rayshade plane with a zero normal loaded, and failed validation.
    &[("plane.ray", b"surface s0\nplane s0 0 0 0 0 0 0\n")],
    // A Rayshade screen so tall that the default fov of 45 is 720 degrees
    // vertically: an error that named no line.
    &[("tall.ray", b"screen 1 16\n")],
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

/// The oracle refuses what the shape policy keeps out of a scene, by the
/// shape's own check, and bounds turned inside out.
#[test]
fn the_oracle_rejects_shapes_no_loader_keeps() {
    let dir = tempfile::tempdir().unwrap();
    let file = write_case(dir.path(), "s.toml", b"[image]\nwidth = 8\nheight = 8\n[camera]\neye = [0, 0, 0]\nlook_at = [0, 0, -1]\nfov = 40\n[[object]]\ntype = \"sphere\"\ncenter = [0, 0, -5]\nradius = 1\n");
    let scene = glint_scene::load(&file.path).unwrap();
    assert!(check_scene(&scene).is_ok());
    for radius in [0.0, -1.0] {
        let shape = Shape::Sphere { center: Vec3::ZERO, radius };
        let mut bad = scene.clone();
        bad.objects[0].shapes = vec![shape.clone()];
        assert!(check_scene(&bad).is_err(), "{shape:?}");
    }
}

/// The TOML generator makes every object type the loader reads: a kind added
/// to the loader but not here would go unfuzzed.
#[test]
fn the_toml_generator_makes_every_object_type() {
    use proptest::strategy::ValueTree;
    let mut runner = TestRunner::deterministic();
    let mut made = std::collections::BTreeSet::new();
    for _ in 0..300 {
        let text = toml_object(Mode::Sane).new_tree(&mut runner).unwrap().current();
        made.extend(text.lines().filter_map(|line| line.strip_prefix("type = \"")?.strip_suffix('"')).map(String::from));
    }
    for kind in glint_scene::toml_scene::object_types() {
        assert!(made.contains(kind), "no `{kind}` among {made:?}");
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
    let targets: [(&str, Generator, &str); 5] = [
        ("nff", nff_text, "case.nff"),
        ("ray", ray_text, "case.ray"),
        ("toml", toml_text, "scene.toml"),
        ("obj", obj_text, "case.obj"),
        ("mtl", mtl_text, "m.mtl"),
    ];
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
