//! Cross-check against the original generators' output: every `NAME_sN.nff`
//! in `$GLINT_SPD_DIR` (Glint's CI points it at the 42 files made by SPD 3.14)
//! must equal what `glint-spd` generates for NAME at size N, number for number
//! within the six significant digits SPD prints. This is the only test that
//! reads outside the repository; without the variable it says so and passes.

use std::path::{Path, PathBuf};

fn reference_dir() -> Option<PathBuf> {
    let dir = PathBuf::from(std::env::var_os("GLINT_SPD_DIR")?);
    assert!(dir.is_dir(), "GLINT_SPD_DIR={} is not a directory", dir.display());
    Some(dir)
}

/// `balls_s4.nff` → ("balls", 4).
fn name_and_size(path: &Path) -> Option<(String, u32)> {
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
        let want_words: Vec<_> = want.split_whitespace().collect();
        let got_words: Vec<_> = got.split_whitespace().collect();
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

/// Compares every reference file of database `name`.
fn check_database(name: &str) {
    let Some(dir) = reference_dir() else {
        eprintln!("skipped: GLINT_SPD_DIR is not set (the reference files from SPD 3.14 exist only in Glint's CI)");
        return;
    };
    let mut files: Vec<_> = std::fs::read_dir(&dir)
        .expect("the reference directory is readable")
        .map(|e| e.expect("directory entry").path())
        .filter(|p| name_and_size(p).is_some_and(|(n, _)| n == name))
        .collect();
    files.sort();
    assert!(!files.is_empty(), "no {name}_sN.nff reference files in {}", dir.display());
    let db = glint_spd::database(name).expect("a known database");
    let mut failures = Vec::new();
    for path in &files {
        let (_, size) = name_and_size(path).expect("filtered on the name");
        let reference = std::fs::read_to_string(path).expect("reference file is text");
        let generated = db.generate(Some(size)).unwrap_or_else(|e| panic!("{}: {e}", path.display()));
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

#[test]
fn all_42_reference_files_are_checked() {
    let Some(dir) = reference_dir() else {
        eprintln!("skipped: GLINT_SPD_DIR is not set (the reference files from SPD 3.14 exist only in Glint's CI)");
        return;
    };
    let checked = std::fs::read_dir(&dir)
        .expect("the reference directory is readable")
        .filter_map(|e| name_and_size(&e.expect("directory entry").path()))
        .filter(|(name, _)| glint_spd::database(name).is_ok())
        .count();
    assert_eq!(checked, 42, "expected SPD's 42 reference files in {}", dir.display());
}

macro_rules! databases {
    ($($name:ident),*) => { $(#[test] fn $name() { check_database(stringify!($name)); })* };
}

databases!(balls, gears, mount, rings, teapot, tetra, tree, jacks, shells, lattice, sombrero, nurbtst);
