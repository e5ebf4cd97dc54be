//! The bad-input corpus, `tests/bad_input/`: every file there is a malformed
//! scene, and `glint render FILE -o OUT` must refuse it the documented way.
//!
//! `tests/bad_input/expected.toml` records, for every top-level file, the exit
//! code, the `file:line[:column]` the error must name and a part of the
//! message. For each file the test checks that glint
//!
//! * exits with that code, which is neither 0 nor 101 (a Rust panic);
//! * prints exactly one line on stderr, starting with `glint:`, naming that
//!   place and holding that part of the message, and nothing on stdout;
//! * never panics;
//! * creates no file at all, and leaves an existing output file untouched.
//!
//! A corpus file without an expectation, or an expectation without its file,
//! fails the test. Files the corpus files reference live in
//! `tests/bad_input/companions/` and are not run on their own.
//!
//! Bad command lines (absurd `--spp`, `--max-depth`, `--width`) are a table at
//! the end: they are invocations, not files.

use std::io::Write;
use std::collections::BTreeMap;
use std::path::{Path, PathBuf};
use std::process::{Command, Output, Stdio};
use std::time::{Duration, Instant};

fn corpus_dir() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../../tests/bad_input")
        .canonicalize()
        .expect("tests/bad_input exists")
}

/// What `expected.toml` says about one file.
#[derive(Debug, Default)]
struct Expectation {
    code: Option<i32>,
    at: Option<String>,
    message: Option<String>,
}

/// Reads `expected.toml`. It uses a small part of TOML: comments, `["name"]`
/// headers and `key = "text"`, `key = 'text'` or `key = 3` lines; anything
/// else is an error, so that nothing in it is silently ignored.
fn read_expectations(path: &Path) -> BTreeMap<String, Expectation> {
    let text = std::fs::read_to_string(path).expect("expected.toml is readable");
    let mut all: BTreeMap<String, Expectation> = BTreeMap::new();
    let mut current: Option<String> = None;
    for (i, line) in text.lines().enumerate() {
        let at = format!("expected.toml:{}", i + 1);
        let line = line.trim();
        if line.is_empty() || line.starts_with('#') {
            continue;
        }
        if let Some(name) = line.strip_prefix("[\"").and_then(|l| l.strip_suffix("\"]")) {
            assert!(!all.contains_key(name), "{at}: `{name}` is described twice");
            all.insert(name.to_string(), Expectation::default());
            current = Some(name.to_string());
            continue;
        }
        let (key, value) = line.split_once('=').unwrap_or_else(|| panic!("{at}: not `key = value`: {line}"));
        let name = current.as_ref().unwrap_or_else(|| panic!("{at}: a key before any [\"file\"] header"));
        let entry = all.get_mut(name).expect("inserted with its header");
        let value = value.trim();
        // A "basic" string without escapes, or a 'literal' one.
        let text = || {
            let basic = value.strip_prefix('"').and_then(|v| v.strip_suffix('"'));
            if let Some(inner) = basic {
                assert!(!inner.contains(['"', '\\']), "{at}: no escapes in \"strings\" (use a 'literal' one): {value}");
                return Some(inner.to_string());
            }
            let literal = value.strip_prefix('\'').and_then(|v| v.strip_suffix('\''));
            let inner = literal.unwrap_or_else(|| panic!("{at}: expected a \"string\" or a 'literal string': {value}"));
            assert!(!inner.contains('\''), "{at}: a quote inside a 'literal string': {value}");
            Some(inner.to_string())
        };
        match key.trim() {
            "code" => entry.code = Some(value.parse().unwrap_or_else(|_| panic!("{at}: code must be a number"))),
            "at" => entry.at = text(),
            "message" => entry.message = text(),
            other => panic!("{at}: unknown key `{other}`"),
        }
    }
    all
}

/// Runs glint, killing it if it takes longer than a scene error should.
fn glint(args: &[&str]) -> Output {
    let mut child = Command::new(env!("CARGO_BIN_EXE_glint"))
        .args(args)
        .stdin(Stdio::null())
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .expect("glint runs");
    let deadline = Instant::now() + Duration::from_secs(60);
    while child.try_wait().expect("glint can be waited for").is_none() {
        if Instant::now() > deadline {
            let _ = child.kill();
            panic!("glint {args:?} ran for more than 60 s: it should have refused the input at once");
        }
        std::thread::sleep(Duration::from_millis(5));
    }
    child.wait_with_output().expect("glint's output can be read")
}

fn entries(dir: &Path) -> Vec<String> {
    let mut names: Vec<String> =
        std::fs::read_dir(dir).unwrap().map(|e| e.unwrap().file_name().to_string_lossy().into_owned()).collect();
    names.sort();
    names
}

/// Renders `file` into an empty directory (or one holding only a file the
/// output would replace), and returns everything that went wrong.
fn check_case(file: &Path, name: &str, expected: &Expectation, existing_output: bool) -> Vec<String> {
    let mut problems = Vec::new();
    let (Some(code), Some(at), Some(message)) = (expected.code, &expected.at, &expected.message) else {
        return vec![format!("{name}: expected.toml must give `code`, `at` and `message`")];
    };
    let (place_file, line) = match at.rsplit_once(':') {
        Some((head, last)) if head.contains(':') => head.rsplit_once(':').map_or((head, last), |(f, l)| (f, l)),
        Some((file, line)) => (file, line),
        None => (at.as_str(), ""),
    };
    if line.is_empty() || !line.chars().all(|c| c.is_ascii_digit()) {
        problems.push(format!("{name}: `at = \"{at}\"` must be file:line or file:line:column"));
    }
    if place_file != name && !place_file.starts_with("companions/") {
        problems.push(format!("{name}: `at` names {place_file}, neither the file itself nor a companion"));
    }
    if code == 0 || code == 101 {
        problems.push(format!("{name}: expected code {code} is not a refusal"));
    }

    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("out.png");
    if existing_output {
        std::fs::write(&out, b"precious").unwrap();
    }
    let o = glint(&["render", file.to_str().unwrap(), "-o", out.to_str().unwrap()]);
    let stderr = String::from_utf8_lossy(&o.stderr).into_owned();
    let stdout = String::from_utf8_lossy(&o.stdout).into_owned();
    let mut problem = |what: String| problems.push(format!("{name}: {what}\n    stderr: {stderr:?}"));
    if o.status.code() != Some(code) {
        problem(format!("exit code {:?}, expected {code}", o.status.code()));
    }
    if stderr.contains("panicked") || o.status.code() == Some(101) {
        problem("glint panicked".into());
    }
    let lines: Vec<&str> = stderr.lines().collect();
    if lines.len() != 1 || !stderr.ends_with('\n') {
        problem(format!("{} lines on stderr, expected exactly one", lines.len()));
    }
    if !stderr.starts_with("glint: ") {
        problem("stderr does not start with `glint: `".into());
    }
    // The printed path is the full path of the named file: "/…/NAME:LINE[:COL]: ".
    if !stderr.contains(&format!("/{at}: ")) {
        problem(format!("the message does not name `{at}`"));
    }
    if !stderr.contains(message.as_str()) {
        problem(format!("the message does not say `{message}`"));
    }
    if !stdout.is_empty() {
        problem(format!("stdout is not empty: {stdout:?}"));
    }
    let left = entries(dir.path());
    if existing_output {
        if left != ["out.png"] {
            problem(format!("files after the failed render: {left:?}"));
        }
        if std::fs::read(&out).unwrap() != b"precious" {
            problem("the existing output file was changed".into());
        }
    } else if !left.is_empty() {
        problem(format!("files were created: {left:?}"));
    }
    problems
}

#[test]
fn every_bad_input_is_refused_with_one_line_naming_the_place() {
    let dir = corpus_dir();
    let mut expectations = read_expectations(&dir.join("expected.toml"));
    let files: Vec<String> = entries(&dir)
        .into_iter()
        .filter(|name| name != "expected.toml" && dir.join(name).is_file())
        .collect();
    let mut problems = Vec::new();
    let mut by_format: BTreeMap<&str, usize> = BTreeMap::new();
    for (i, name) in files.iter().enumerate() {
        let Some(expected) = expectations.remove(name) else {
            problems.push(format!("{name}: no expectation in expected.toml"));
            continue;
        };
        *by_format.entry(name.split('_').next().unwrap_or("")).or_default() += 1;
        // Every seventh case also has an output file there already.
        problems.extend(check_case(&dir.join(name), name, &expected, i % 7 == 0));
    }
    for name in expectations.keys() {
        problems.push(format!("{name}: described in expected.toml, but there is no such file"));
    }
    assert!(problems.is_empty(), "{} problem(s):\n{}", problems.len(), problems.join("\n"));
    // Written past the test harness's capture, so every run shows the summary.
    let _ = writeln!(std::io::stderr(), "bad input: {} files refused: {by_format:?}", files.len());
    assert!(files.len() >= 50, "the corpus has only {} files", files.len());
    for format in ["toml", "nff", "obj", "ray"] {
        assert!(by_format.get(format).copied().unwrap_or(0) >= 10, "fewer than 10 {format} cases: {by_format:?}");
    }
}

#[test]
fn an_existing_output_survives_each_kind_of_bad_input() {
    let dir = corpus_dir();
    let expectations = read_expectations(&dir.join("expected.toml"));
    for name in ["toml_nan_radius.toml", "nff_resolution_100000x100000.nff", "obj_face_index_out_of_range.obj", "toml_mesh_bad_mtl.toml"] {
        let expected = &expectations[name];
        let problems = check_case(&dir.join(name), name, expected, true);
        assert!(problems.is_empty(), "{}", problems.join("\n"));
    }
}

/// Absurd values on the command line are refused by the argument parser, with
/// the usage code, before any file is read or written. A usage error is shown
/// as clap explains it (first line `glint: …`, then the allowed values or the
/// usage), not cut to one line.
#[test]
fn absurd_command_line_values_are_refused() {
    let scene = corpus_dir().join("../../scenes/showcase.toml");
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("out.png");
    let cases: &[(&[&str], &str)] = &[
        (&["--spp", "0"], "--spp"),
        (&["--spp", "100000"], "--spp"),
        (&["--spp=-1"], "--spp"),
        (&["--max-depth", "0"], "--max-depth"),
        (&["--max-depth", "1000"], "--max-depth"),
        (&["--width", "0"], "--width"),
        (&["--height", "0"], "--height"),
        (&["--width", "100000"], "--width"),
        (&["--height", "100000"], "--height"),
        (&["--width", "wide"], "--width"),
        (&["--exposure", "nan"], "--exposure"),
        (&["--exposure=-1"], "--exposure"),
        (&["--exposure", "-1"], "must be a positive number"),
        (&["--width", "-5"], "--width"),
        (&["--tone-map", "sepia"], "--tone-map"),
        (&["--aov", "depth=out.png"], "--aov"),
    ];
    for (extra, option) in cases {
        let mut args = vec!["render", scene.to_str().unwrap(), "-o", out.to_str().unwrap()];
        args.extend_from_slice(extra);
        let o = glint(&args);
        let stderr = String::from_utf8_lossy(&o.stderr);
        assert_eq!(o.status.code(), Some(2), "{extra:?}: {stderr}");
        assert!(stderr.contains(option), "{extra:?}: the message does not name {option}: {stderr}");
        let first = stderr.lines().next().unwrap_or_default();
        assert!(first.starts_with("glint: ") && first.contains(option), "{extra:?}: the first line does not name {option}: {stderr}");
        assert!(stderr.contains("try '--help'"), "{extra:?}: not clap's full message: {stderr}");
        assert!(!stderr.contains("panicked"), "{extra:?}: {stderr}");
        assert!(entries(dir.path()).is_empty(), "{extra:?} created {:?}", entries(dir.path()));
    }
}
