//! Cross-check against the original generators' output: every `NAME_sN.nff`
//! in `$GLINT_SPD_DIR` (Glint's CI points it at the 42 files made by SPD 3.14)
//! and every `NAME_sN.ray` in `$GLINT_SPD_RAYSHADE_DIR` (the 28 files SPD 3.14
//! writes with `-r 8`) must equal what `glint-spd` generates for NAME at size
//! N, word for word and space for space, numbers within the six significant
//! digits SPD prints. These are the only tests that read outside the
//! repository; without the variables they say so and pass.

use std::path::{Path, PathBuf};

use glint_spd::Format;

/// The variable naming the reference files of `format`.
fn variable(format: Format) -> &'static str {
    match format {
        Format::Nff => "GLINT_SPD_DIR",
        Format::Rayshade => "GLINT_SPD_RAYSHADE_DIR",
    }
}

fn extension(format: Format) -> &'static str {
    match format {
        Format::Nff => "nff",
        Format::Rayshade => "ray",
    }
}

fn reference_dir(format: Format) -> Option<PathBuf> {
    let name = variable(format);
    let Some(dir) = std::env::var_os(name) else {
        eprintln!("skipped: {name} is not set (the reference files from SPD 3.14 exist only in Glint's CI)");
        return None;
    };
    let dir = PathBuf::from(dir);
    assert!(dir.is_dir(), "{name}={} is not a directory", dir.display());
    Some(dir)
}

/// `balls_s4.nff` → ("balls", 4), for files of `format`.
fn name_and_size(path: &Path, format: Format) -> Option<(String, u32)> {
    if path.extension()? != extension(format) {
        return None;
    }
    let stem = path.file_stem()?.to_str()?;
    let (name, size) = stem.rsplit_once("_s")?;
    Some((name.to_string(), size.parse().ok()?))
}

/// Two numbers as printed with `%g` agree when they round to the same six
/// significant digits, give or take one unit in the last place (a libm that
/// differs in the last bit can flip a rounding), or are both negligible next
/// to the scene (|x| < 1e-9: `-2.55836e-17` is a zero that rounding left).
fn numbers_agree(a: f64, b: f64) -> bool {
    if a == b || (a.abs() < 1e-9 && b.abs() < 1e-9) {
        return true;
    }
    let scale = a.abs().max(b.abs());
    (a - b).abs() <= scale * 1.0e-5
}

/// The first place where `generated` and `reference` differ, as a message.
fn first_difference(generated: &str, reference: &str) -> Option<String> {
    let mut generated_lines = generated.lines();
    for (number, want) in reference.lines().enumerate() {
        let line = number + 1;
        let Some(got) = generated_lines.next() else {
            return Some(format!("line {line}: generated text ends; reference has `{want}`"));
        };
        // Split at single spaces, so that doubled and trailing spaces count.
        let want_words: Vec<_> = want.split(' ').collect();
        let got_words: Vec<_> = got.split(' ').collect();
        let same = want_words.len() == got_words.len()
            && want_words.iter().zip(&got_words).all(|(w, g)| match (w.parse::<f64>(), g.parse::<f64>()) {
                (Ok(w), Ok(g)) => numbers_agree(w, g),
                _ => w == g,
            });
        if !same {
            return Some(format!("line {line}: generated `{got}`, reference `{want}`"));
        }
    }
    generated_lines.next().map(|extra| format!("generated text has more lines than the reference, from `{extra}`"))
}

/// Compares every reference file of database `name` in `format`.
fn check_database(name: &str, format: Format) {
    let Some(dir) = reference_dir(format) else {
        return;
    };
    let mut files: Vec<_> = std::fs::read_dir(&dir)
        .expect("the reference directory is readable")
        .map(|e| e.expect("directory entry").path())
        .filter(|p| name_and_size(p, format).is_some_and(|(n, _)| n == name))
        .collect();
    files.sort();
    assert!(!files.is_empty(), "no {name}_sN.{} reference files in {}", extension(format), dir.display());
    let db = glint_spd::database(name).expect("a known database");
    let mut failures = Vec::new();
    for path in &files {
        let (_, size) = name_and_size(path, format).expect("filtered on the name");
        let reference = std::fs::read_to_string(path).expect("reference file is text");
        let generated = db.generate_as(Some(size), format).unwrap_or_else(|e| panic!("{}: {e}", path.display()));
        if generated == reference {
            eprintln!("{}: byte-identical", path.display());
        } else if let Some(difference) = first_difference(&generated, &reference) {
            failures.push(format!("{}: {difference}", path.display()));
        } else {
            eprintln!("{}: equal within six significant digits, not byte for byte", path.display());
        }
    }
    assert!(failures.is_empty(), "{} files differ:\n{}", failures.len(), failures.join("\n"));
}

/// How many reference files of `format` name a database Glint generates.
fn reference_count(dir: &Path, format: Format) -> usize {
    std::fs::read_dir(dir)
        .expect("the reference directory is readable")
        .filter_map(|e| name_and_size(&e.expect("directory entry").path(), format))
        .filter(|(name, _)| glint_spd::database(name).is_ok())
        .count()
}

#[test]
fn all_42_reference_files_are_checked() {
    if let Some(dir) = reference_dir(Format::Nff) {
        assert_eq!(reference_count(&dir, Format::Nff), 42, "expected SPD's 42 reference files in {}", dir.display());
    }
}

#[test]
fn all_28_rayshade_reference_files_are_checked() {
    if let Some(dir) = reference_dir(Format::Rayshade) {
        let count = reference_count(&dir, Format::Rayshade);
        assert_eq!(count, 28, "expected SPD's 28 Rayshade reference files in {}", dir.display());
    }
}

macro_rules! databases {
    ($format:expr; $($name:ident),*) => { $(#[test] fn $name() { check_database(stringify!($name), $format); })* };
}

databases!(Format::Nff; balls, gears, mount, rings, teapot, tetra, tree, jacks, shells, lattice, sombrero, nurbtst);

/// The seven classic databases, as Rayshade text.
mod rayshade {
    use super::{check_database, Format};

    databases!(Format::Rayshade; balls, gears, mount, rings, teapot, tetra, tree);
}
