//! The course kit (`course/`) as Gradescope runs it. `run_autograder` grades a
//! student's folder in a temporary `/autograder`-shaped one, with the built
//! `glint` on `PATH`, on the GPU (lavapipe in CI; no adapter is a failure).
//! The student's images of every stage are Glint's own, but for the shadows
//! stage, where the student handed in the local-shading image again.
//! `setup.sh` runs with stub commands (curl, apt-get, add-apt-repository,
//! cargo, glint, Glint's `.ci/setup`) on a `PATH` that holds nothing else
//! of the machine's, as tests/setup.rs runs `.ci/setup`.

mod suite;

use std::fs;
use std::os::unix::fs::{symlink, PermissionsExt};
use std::path::{Path, PathBuf};
use std::process::{Command, Output};

use suite::{arg, glint, stderr, stdout};

const KIT: &str = concat!(env!("CARGO_MANIFEST_DIR"), "/../../course");

/// The kit's files, copied into `source/` as Gradescope unpacks the zip.
fn copy_kit(to: &Path) {
    for file in ["course.toml", "scenes/lecture.toml", "setup.sh", "run_autograder"] {
        let target = to.join(file);
        fs::create_dir_all(target.parent().unwrap()).unwrap();
        fs::copy(Path::new(KIT).join(file), &target).unwrap();
    }
}

/// The stages as the manifest names them, each with its image and the
/// options of `glint render` that make that image.
const STAGES: [(&str, &str, &[&str]); 5] = [
    ("1 visibility", "visibility.png", &["--view", "albedo"]),
    ("2 local shading", "local.png", &["--max-depth", "1", "--no-shadows"]),
    ("3 shadows", "shadows.png", &["--max-depth", "1"]),
    ("4 reflection", "reflection.png", &["--no-refraction"]),
    ("5 refraction", "refraction.png", &[]),
];

fn json(path: &Path) -> serde_json::Value {
    serde_json::from_str(&fs::read_to_string(path).unwrap_or_else(|e| panic!("{}: {e}", path.display()))).unwrap()
}

#[test]
fn run_autograder_grades_a_submission_stage_by_stage() {
    let dir = tempfile::tempdir().unwrap();
    let autograder = dir.path();
    copy_kit(&autograder.join("source"));
    let submission = autograder.join("submission");
    fs::create_dir_all(&submission).unwrap();
    let scene = autograder.join("source/scenes/lecture.toml");
    for (_, image, options) in STAGES {
        let out = submission.join(image);
        let mut args = vec!["render", arg(&scene), "-o", arg(&out), "-q"];
        args.extend(options);
        let o = glint(&args);
        assert!(o.status.success(), "{image}: {}", stderr(&o));
    }
    // No shadow rays yet: the local-shading image again.
    fs::copy(submission.join("local.png"), submission.join("shadows.png")).unwrap();

    let glint_dir = Path::new(env!("CARGO_BIN_EXE_glint")).parent().unwrap();
    let o = Command::new("bash")
        .arg(autograder.join("source/run_autograder"))
        .current_dir(autograder)
        .env("GLINT_AUTOGRADER", autograder)
        .env("PATH", format!("{}:{}", glint_dir.display(), std::env::var("PATH").unwrap_or_default()))
        .output()
        .unwrap();
    let out = stdout(&o);
    assert_eq!(o.status.code(), Some(0), "{out}{}", stderr(&o));
    let lines: Vec<&str> = out.lines().collect();
    assert_eq!(lines.len(), 6, "{out}");
    assert!(lines[2].starts_with("FAIL    submission/3 shadows: flip "), "{out}");
    assert_eq!(lines[5], "submission: 4 passed, 1 failed; 8/10 points", "{out}");

    // Gradescope's results: a test per stage, the wrong one failed with what
    // it lacks, in bold, and its images.
    let results = json(&autograder.join("results/results.json"));
    assert_eq!(results["score"], 8.0);
    assert_eq!(results["output"], "Whitted ray tracer: 4 passed, 1 failed; 8/10 points");
    let tests = results["tests"].as_array().unwrap();
    let names: Vec<&str> = tests.iter().map(|t| t["name"].as_str().unwrap()).collect();
    assert_eq!(names, STAGES.map(|(name, _, _)| name));
    for (test, (name, _, _)) in tests.iter().zip(STAGES) {
        let failed = name == "3 shadows";
        assert_eq!((&test["status"], &test["max_score"]), (&(if failed { "failed" } else { "passed" }).into(), &2.0.into()), "{name}");
        assert_eq!(test["score"], if failed { 0.0 } else { 2.0 }, "{name}");
        assert_eq!(test.get("output_format"), failed.then_some(&"md".into()), "{name}");
    }
    let output = tests[2]["output"].as_str().unwrap();
    let diagnosis = output.split("\n\n").nth(1).unwrap();
    assert!(diagnosis.starts_with("closest to Glint's render without shadow rays (flip ") && diagnosis.ends_with("): **check your shadow rays**"), "{output}");
    assert!(output.contains("\n- settings: view shaded, max depth 1, 1 spp, 160x120\n"), "{output}");
    // The three pictures, inline (glint-golden's gradescope.rs tests what they hold).
    let roles: Vec<&str> = output.split("![").skip(1).filter_map(|image| image.split_once("](data:image/png;base64,")).map(|(role, _)| role).collect();
    assert_eq!(roles, ["reference", "submission", "diff"], "{output}");
}

/// A made-up machine for setup.sh: stub commands that log what they are
/// asked to do, Glint's source as a stub `.ci/setup` and a `Cargo.toml`, and
/// the machine's files under `root/`.
struct Machine {
    dir: tempfile::TempDir,
}

/// The real commands setup.sh and the stubs use; nothing else of the
/// machine's is on their `PATH`.
const TOOLS: &[&str] = &["bash", "sh", "env", "sed", "grep", "head", "mkdir", "cat", "chmod", "cp"];

impl Machine {
    fn new(os_id: &str) -> Self {
        let machine = Machine { dir: tempfile::tempdir().unwrap() };
        for dir in ["bin", "tools", "home", "root/etc/apt/sources.list.d"] {
            fs::create_dir_all(machine.path(dir)).unwrap();
        }
        machine.write("root/etc/os-release", &format!("ID={os_id}\n"));
        machine.write("log", "");
        for tool in TOOLS {
            let real = ["/usr/bin", "/bin"].iter().map(|d| Path::new(d).join(tool)).find(|p| p.exists()).unwrap();
            symlink(real, machine.path("tools").join(tool)).unwrap();
        }
        copy_kit(&machine.path("autograder/source"));
        machine.write("autograder/source/glint/Cargo.toml", "[workspace.package]\nversion = \"0.4.2\"\n");
        machine.script("autograder/source/glint/.ci/setup", r#"echo ".ci/setup${*:+ $*}" >> "$STUB/log""#);
        machine.script("bin/curl", r#"echo "curl $*" >> "$STUB/log"; cat "$STUB/rustup-init.sh""#);
        machine.write("rustup-init.sh", "echo \"rustup-init $*\" >> \"$STUB/log\"\nmkdir -p \"$HOME/.cargo/bin\"\ncp \"$STUB/cargo\" \"$HOME/.cargo/bin/cargo\"\n");
        // cargo install puts a glint of the source's version on PATH.
        machine.script("cargo", r#"echo "cargo $*" >> "$STUB/log"; cp "$STUB/glint" "$STUB/bin/glint""#);
        machine.script("glint", r#"case "$1" in --version) echo "glint 0.4.2" ;; *) echo "glint $*" >> "$STUB/log" ;; esac"#);
        machine.script("bin/apt-get", r#"echo "apt-get $*" >> "$STUB/log""#);
        machine.script(
            "bin/add-apt-repository",
            r#"echo "add-apt-repository $*" >> "$STUB/log"
echo "deb https://ppa.launchpadcontent.net/kisak/kisak-mesa/ubuntu/ jammy main" > "$GLINT_SETUP_ROOT/etc/apt/sources.list.d/kisak-ubuntu-kisak-mesa-jammy.list""#,
        );
        machine
    }

    fn path(&self, name: &str) -> PathBuf {
        self.dir.path().join(name)
    }

    fn write(&self, name: &str, text: &str) {
        let path = self.path(name);
        fs::create_dir_all(path.parent().unwrap()).unwrap();
        fs::write(path, text).unwrap();
    }

    /// An executable bash script running `line`.
    fn script(&self, name: &str, line: &str) {
        self.write(name, &format!("#!/bin/bash\n{line}\n"));
        fs::set_permissions(self.path(name), fs::Permissions::from_mode(0o755)).unwrap();
    }

    /// Runs setup.sh; returns its output and the stubs' log.
    fn setup(&self) -> (Output, Vec<String>) {
        fs::write(self.path("log"), "").unwrap();
        let out = Command::new("/bin/bash")
            .arg(self.path("autograder/source/setup.sh"))
            .env_clear()
            .env("PATH", format!("{}:{}", self.path("bin").display(), self.path("tools").display()))
            .env("HOME", self.path("home"))
            .env("STUB", self.dir.path())
            .env("GLINT_AUTOGRADER", self.path("autograder"))
            .env("GLINT_SETUP_ROOT", self.path("root"))
            .output()
            .unwrap();
        let log = fs::read_to_string(self.path("log")).unwrap().lines().map(String::from).collect();
        (out, log)
    }

    fn cargo_install(&self) -> String {
        format!("cargo install --locked --path {}/crates/glint-cli --root /usr/local", self.path("autograder/source/glint").display())
    }
}

#[test]
fn setup_installs_rust_mesa_from_kisak_and_glint_on_ubuntu_and_nothing_twice() {
    let machine = Machine::new("ubuntu");
    let (out, log) = machine.setup();
    assert!(out.status.success(), "{}", stderr(&out));
    assert_eq!(
        log,
        [
            "curl --proto =https --tlsv1.2 -sSf https://sh.rustup.rs".to_string(),
            "rustup-init -y --profile minimal".into(),
            "add-apt-repository -y ppa:kisak/kisak-mesa".into(),
            ".ci/setup".into(),
            machine.cargo_install(),
            "glint info".into(),
        ]
    );
    // Rust, the PPA and glint are there: only the checks run again.
    let (out, log) = machine.setup();
    assert!(out.status.success(), "{}", stderr(&out));
    assert_eq!(log, [".ci/setup", "glint info"]);
    assert!(stderr(&out).contains("setup.sh: glint 0.4.2 is installed"), "{}", stderr(&out));
}

#[test]
fn setup_on_debian_with_rust_adds_no_ppa() {
    let machine = Machine::new("debian");
    fs::copy(machine.path("cargo"), machine.path("bin/cargo")).unwrap();
    let (out, log) = machine.setup();
    assert!(out.status.success(), "{}", stderr(&out));
    assert_eq!(log, [".ci/setup".to_string(), machine.cargo_install(), "glint info".into()]);
}

#[test]
fn setup_stops_where_lavapipe_cannot_be_installed() {
    let machine = Machine::new("debian");
    fs::copy(machine.path("cargo"), machine.path("bin/cargo")).unwrap();
    machine.script("autograder/source/glint/.ci/setup", r#"echo ".ci/setup" >> "$STUB/log"; echo "glint setup: not ready: lavapipe" >&2; exit 1"#);
    let (out, log) = machine.setup();
    assert_eq!(out.status.code(), Some(1));
    assert!(stderr(&out).contains("glint setup: not ready: lavapipe"), "{}", stderr(&out));
    assert_eq!(log, [".ci/setup"], "no glint is built without a driver");
}
