//! `.ci/setup` run against made-up machines: stub `apt-get`, `apt-cache`,
//! `dpkg-query`, `rustup`, `cargo` and `uname` (tests/setup_stubs/) on a
//! `PATH` that holds nothing else of the real machine's, and the machine's
//! files under `GLINT_SETUP_ROOT`. Each test says what the script installs
//! there, for rendering alone and for the whole test suite, and that a second
//! run does nothing.

use std::fs;
use std::os::unix::fs::{symlink, PermissionsExt};
use std::path::{Path, PathBuf};
use std::process::Command;

const ROOT: &str = env!("CARGO_MANIFEST_DIR");

/// The real commands the script and the stubs use; nothing else of the
/// machine's is on their `PATH`.
const TOOLS: &[&str] = &["bash", "env", "id", "dirname", "sed", "awk", "grep", "ls", "head", "tee", "cat", "mv", "chmod", "cut"];

const WASM_BINDGEN: &str = "wasm-bindgen-cli --version";

struct Machine {
    dir: tempfile::TempDir,
}

/// What one run of the script did.
struct Run {
    code: i32,
    stderr: String,
    log: Vec<String>,
}

impl Run {
    fn installed(&self, what: &str) -> bool {
        self.log.iter().any(|line| line.contains(what))
    }

    fn says(&self, what: &str) -> bool {
        self.stderr.contains(what)
    }
}

impl Machine {
    /// A Linux machine with this os-release and these packages that apt can
    /// install (`suite package version`).
    fn linux(os_release: &str, available: &str) -> Self {
        let machine = Self::empty();
        machine.write("root/etc/os-release", os_release);
        machine.write(
            "root/etc/apt/sources.list.d/debian.sources",
            "Types: deb\nURIs: http://mirror.example/debian\nSuites: stable\nComponents: main\nSigned-By: /usr/share/keyrings/debian-archive-keyring.gpg\n",
        );
        machine.write("available", available);
        for stub in ["apt-get", "apt-cache", "dpkg-query"] {
            machine.link_stub(stub);
        }
        machine
    }

    /// A machine with no os-release, no apt and no dpkg.
    fn empty() -> Self {
        let machine = Machine { dir: tempfile::tempdir().unwrap() };
        for dir in ["bin", "tools", "root/dev"] {
            fs::create_dir_all(machine.path(dir)).unwrap();
        }
        for file in ["installed", "available", "log", "targets"] {
            machine.write(file, "");
        }
        machine.write("targets", "x86_64-unknown-linux-gnu\n");
        for stub in ["rustup", "cargo", "uname", "sudo"] {
            machine.link_stub(stub);
        }
        for tool in TOOLS {
            let real = ["/usr/bin", "/bin"].iter().map(|d| Path::new(d).join(tool)).find(|p| p.exists()).unwrap();
            symlink(real, machine.path("tools").join(tool)).unwrap();
        }
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

    fn link_stub(&self, name: &str) {
        symlink(Path::new(ROOT).join("tests/setup_stubs").join(name), self.path("bin").join(name)).unwrap();
    }

    /// A package dpkg knows, and the commands it put on `PATH`.
    fn with_package(self, package: &str, version: &str, commands: &[&str]) -> Self {
        let mut installed = fs::read_to_string(self.path("installed")).unwrap();
        installed += &format!("{package} {version}\n");
        self.write("installed", &installed);
        for command in commands {
            self.command(command, &format!("echo v{version}"));
        }
        self
    }

    /// A command on `PATH` that runs this shell line.
    fn command(&self, name: &str, line: &str) {
        let path = self.path("bin").join(name);
        fs::write(&path, format!("#!/bin/bash\n{line}\n")).unwrap();
        fs::set_permissions(&path, fs::Permissions::from_mode(0o755)).unwrap();
    }

    /// Everything the test suite needs, already there.
    fn complete(self) -> Self {
        let machine = self
            .with_package("g++", "4:12.2.0-3", &["g++", "c++"])
            .with_package("mesa-vulkan-drivers", "25.0.7-2~bpo12+1", &[])
            .with_package("libvulkan1", "1.4.309.0-1~bpo12+1", &[])
            .with_package("xvfb", "2:21.1.7-3", &["xvfb-run"])
            .with_package("xauth", "1:1.1.2-1", &[])
            .with_package("chromium", "156.0.8078.73-1~deb12u1", &["chromium"])
            .with_package("slurm-wlm", "22.05.8-4+deb12u3", &["slurmctld", "slurmd", "sbatch"])
            .with_package("munge", "0.5.15-2", &["munged"])
            .with_package("nodejs", "18.20.4+dfsg-1~deb12u1", &["node"])
            .with_package("npm", "9.2.0~ds1-1", &["npm"]);
        machine.write("targets", "x86_64-unknown-linux-gnu\nwasm32-unknown-unknown\n");
        machine.command("wasm-bindgen", &format!("echo wasm-bindgen {}", wasm_bindgen_version()));
        machine
    }

    fn setup(&self, args: &[&str]) -> Run {
        fs::write(self.path("log"), "").unwrap();
        let out = Command::new("/bin/bash")
            .arg(Path::new(ROOT).join(".ci/setup"))
            .args(args)
            .env_clear()
            .env("PATH", format!("{}:{}", self.path("bin").display(), self.path("tools").display()))
            .env("STUB", self.dir.path())
            .env("GLINT_SETUP_ROOT", self.path("root"))
            .output()
            .unwrap();
        let log = fs::read_to_string(self.path("log")).unwrap().lines().map(String::from).collect();
        Run { code: out.status.code().unwrap_or(-1), stderr: String::from_utf8_lossy(&out.stderr).into_owned(), log }
    }
}

fn wasm_bindgen_version() -> String {
    let lock = fs::read_to_string(Path::new(ROOT).join("Cargo.lock")).unwrap();
    let at = lock.find("name = \"wasm-bindgen\"\n").unwrap();
    lock[at..].lines().nth(1).unwrap().trim_start_matches("version = ").trim_matches('"').to_string()
}

fn os_release(id: &str, codename: &str, name: &str) -> String {
    format!("PRETTY_NAME=\"{name}\"\nID={id}\nVERSION_CODENAME={codename}\n")
}

/// Debian 12 as its archive has it, with bookworm-backports' Mesa.
fn bookworm() -> Machine {
    Machine::linux(
        &os_release("debian", "bookworm", "Debian GNU/Linux 12 (bookworm)"),
        "main mesa-vulkan-drivers 22.3.6-1+deb12u1\n\
         main libvulkan1 1.3.239.0-1\n\
         bookworm-backports mesa-vulkan-drivers 25.0.7-2~bpo12+1\n\
         bookworm-backports libvulkan1 1.4.309.0-1~bpo12+1\n\
         main xvfb 2:21.1.7-3\n\
         main xauth 1:1.1.2-1\n\
         main chromium 156.0.8078.73-1~deb12u1\n\
         main nodejs 18.20.4+dfsg-1~deb12u1\n\
         main npm 9.2.0~ds1-1\n\
         main slurm-wlm 22.05.8-4+deb12u3\n\
         main munge 0.5.15-2\n\
         main g++ 4:12.2.0-3\n",
    )
}

/// The machine the README's first user had: a fresh Debian 12 with
/// NodeSource's Node.js, whose nodejs conflicts with Debian's npm.
fn bookworm_with_nodesource() -> Machine {
    bookworm().with_package("nodejs", "20.20.2-1nodesource1+repack1", &["node", "npm"])
}

#[test]
fn a_render_on_fresh_debian_12_installs_lavapipe_from_backports_and_a_cxx_compiler_alone() {
    let machine = bookworm_with_nodesource();
    let run = machine.setup(&[]);
    assert_eq!(run.code, 0, "{}", run.stderr);
    assert_eq!(run.log, ["apt-get update", "apt-get install -t bookworm-backports mesa-vulkan-drivers libvulkan1", "apt-get install g++"]);
    let backports = fs::read_to_string(machine.path("root/etc/apt/sources.list.d/glint-backports.sources")).unwrap();
    assert!(backports.contains("URIs: http://mirror.example/debian") && backports.contains("Suites: bookworm-backports"), "{backports}");
    assert_eq!(machine.setup(&[]).log, Vec::<String>::new(), "a second run does nothing");
}

#[test]
fn the_tests_on_fresh_debian_12_keep_nodesource_node_and_install_the_rest() {
    let machine = bookworm_with_nodesource();
    let run = machine.setup(&["--tests"]);
    assert_eq!(run.code, 0, "{}", run.stderr);
    for what in [
        "-t bookworm-backports mesa-vulkan-drivers libvulkan1",
        "apt-get install xvfb xauth",
        "apt-get install chromium",
        "apt-get install slurm-wlm munge",
        "rustup target add wasm32-unknown-unknown",
        WASM_BINDGEN,
    ] {
        assert!(run.installed(what), "{what} not installed: {:?}", run.log);
    }
    assert!(!run.installed("npm") && !run.installed("nodejs"), "NodeSource's node counts: {:?}", run.log);
    let again = machine.setup(&["--tests"]);
    assert_eq!((again.code, again.log), (0, vec![]), "a second run does nothing: {}", again.stderr);
}

#[test]
fn google_chrome_counts_as_chromium() {
    let machine = bookworm().complete();
    fs::remove_file(machine.path("bin/chromium")).unwrap();
    machine.command("google-chrome", "echo Google Chrome 156");
    let run = machine.setup(&["--tests"]);
    assert_eq!((run.code, run.log), (0, vec![]), "{}", run.stderr);
}

#[test]
fn a_complete_machine_gets_nothing() {
    for args in [&[][..], &["--tests"]] {
        let run = bookworm().complete().setup(args);
        assert_eq!((run.code, run.log, run.stderr), (0, vec![], String::new()), "{args:?}");
    }
}

#[test]
fn a_machine_with_a_gpu_driver_needs_nothing_to_render() {
    let machine = bookworm().with_package("libvulkan1", "1.3.239.0-1", &[]).with_package("g++", "4:12.2.0-3", &["g++", "c++"]);
    machine.write("root/dev/dri/renderD128", "");
    machine.write("root/usr/share/vulkan/icd.d/radeon_icd.x86_64.json", "{}");
    let run = machine.setup(&[]);
    assert_eq!((run.code, run.log), (0, vec![]), "{}", run.stderr);
}

#[test]
fn debian_13_takes_mesa_and_node_from_its_own_suite() {
    let machine = Machine::linux(
        &os_release("debian", "trixie", "Debian GNU/Linux 13 (trixie)"),
        "main mesa-vulkan-drivers 25.0.7-2\n\
         main libvulkan1 1.4.309.0-1\n\
         main xvfb 2:21.1.16-1.3\n\
         main xauth 1:1.1.2-1.1\n\
         main chromium 156.0.8078.73-1~deb13u1\n\
         main nodejs 20.19.2+dfsg-1\n\
         main npm 9.2.0~ds1-3\n\
         main slurm-wlm 24.11.5-4\n\
         main munge 0.5.16-1\n\
         main g++ 4:14.2.0-1\n",
    );
    let run = machine.setup(&["--tests"]);
    assert_eq!(run.code, 0, "{}", run.stderr);
    assert!(run.installed("apt-get install mesa-vulkan-drivers libvulkan1"), "{:?}", run.log);
    assert!(run.installed("apt-get install nodejs npm"), "{:?}", run.log);
    assert!(!machine.path("root/etc/apt/sources.list.d/glint-backports.sources").exists());
    assert_eq!(machine.setup(&["--tests"]).log, Vec::<String>::new());
}

/// Ubuntu's releases with the Mesa, Node.js and Chromium packages their
/// archives offer: a Mesa older than 25, no Chromium but a snap, and on
/// 22.04 a Node.js 12.
fn ubuntu(version: &str, codename: &str, mesa: &str, nodejs: &str) -> Machine {
    Machine::linux(
        &os_release("ubuntu", codename, &format!("Ubuntu {version} LTS")),
        &format!(
            "main mesa-vulkan-drivers {mesa}\n\
             main libvulkan1 1.3.275.0-1build1\n\
             main xvfb 2:21.1.12-1ubuntu1\n\
             main xauth 1:1.1.2-1build1\n\
             main chromium-browser 1:85.0.4183.83-0ubuntu2\n\
             main nodejs {nodejs}\n\
             main npm 9.2.0~ds1-2\n\
             main slurm-wlm 23.11.4-1.2u1\n\
             main munge 0.5.15-4build1\n\
             main g++ 4:13.2.0-7ubuntu1\n"
        ),
    )
}

#[test]
fn ubuntu_is_told_what_its_archive_cannot_give() {
    for (version, codename, mesa, nodejs, node_too_old) in [
        ("22.04", "jammy", "23.2.1-1ubuntu3.1~22.04.3", "12.22.9~dfsg-1ubuntu3.6", true),
        ("24.04", "noble", "24.2.8-1ubuntu1~24.04.1", "18.19.1+dfsg-6ubuntu5", false),
    ] {
        let machine = ubuntu(version, codename, mesa, nodejs);
        let run = machine.setup(&["--tests"]);
        assert_eq!(run.code, 1, "{version}: {}", run.stderr);
        assert!(run.installed("apt-get install mesa-vulkan-drivers libvulkan1"), "{version}: {:?}", run.log);
        assert!(run.says("lavapipe: not installed:") && run.says("older than 25") && run.says("ppa:kisak/kisak-mesa"), "{version}: {}", run.stderr);
        assert!(run.says("Chromium: not installed: Ubuntu packages Chromium as a snap only"), "{version}: {}", run.stderr);
        assert!(!run.installed("chromium"), "{version}: {:?}", run.log);
        assert_eq!(run.says("Node.js: not installed:") && run.says("older than 18"), node_too_old, "{version}: {}", run.stderr);
        assert_eq!(run.installed("apt-get install nodejs npm"), !node_too_old, "{version}: {:?}", run.log);
        assert!(run.installed("apt-get install xvfb xauth") && run.installed("apt-get install slurm-wlm munge"), "{version}: {:?}", run.log);
        assert!(run.says("not ready:"), "{version}: {}", run.stderr);
    }
}

#[test]
fn macos_renders_on_metal_and_is_told_what_the_tests_need() {
    let machine = Machine::empty();
    machine.write("uname", "Darwin\n");
    // Rust on macOS links with the Command Line Tools, which bring clang++.
    machine.command("clang++", "echo Apple clang");
    let render = machine.setup(&[]);
    assert_eq!((render.code, render.log.clone()), (0, vec![]), "{}", render.stderr);
    assert!(render.says("macOS: Glint renders on Metal; nothing to install"), "{}", render.stderr);
    let tests = machine.setup(&["--tests"]);
    assert_eq!(tests.code, 1, "{}", tests.stderr);
    for piece in ["Xvfb", "Chromium", "Node.js", "Slurm with munge"] {
        assert!(tests.says(&format!("{piece}: not installed: this machine has no apt-get; by hand: ")), "{piece}: {}", tests.stderr);
    }
    assert!(tests.installed("rustup target add wasm32-unknown-unknown") && tests.installed(WASM_BINDGEN), "{:?}", tests.log);
}

#[test]
fn a_piece_apt_cannot_install_is_named_and_the_others_go_on() {
    // NodeSource's nodejs without its npm: apt would have to install Debian's
    // npm, which conflicts with it.
    let machine = bookworm().with_package("nodejs", "20.20.2-1nodesource1+repack1", &["node"]);
    let run = machine.setup(&["--tests"]);
    assert_eq!(run.code, 1, "{}", run.stderr);
    assert!(run.says("Node.js npm: not installed: NodeSource's nodejs should carry npm"), "{}", run.stderr);
    assert!(!run.installed("npm"), "{:?}", run.log);
    assert!(run.installed("apt-get install chromium") && run.installed("slurm-wlm munge") && run.installed(WASM_BINDGEN), "{:?}", run.log);

    // A package the archive does not have: simulated first, so apt is left as it was.
    let machine = bookworm();
    let available = fs::read_to_string(machine.path("available")).unwrap().replace("main chromium ", "other chromium ");
    machine.write("available", &available);
    let run = machine.setup(&["--tests"]);
    assert_eq!(run.code, 1, "{}", run.stderr);
    assert!(run.says("Chromium: not installed: apt cannot install chromium: Unable to locate package chromium; by hand: "), "{}", run.stderr);
    assert!(!run.installed("chromium") && run.installed("apt-get install slurm-wlm munge"), "{:?}", run.log);
    assert!(run.says("not ready: Chromium"), "{}", run.stderr);
}

#[test]
fn a_bad_argument_is_a_usage_error() {
    let run = bookworm().setup(&["--test"]);
    assert_eq!((run.code, run.log.clone()), (2, vec![]));
    assert!(run.says("usage: bash .ci/setup [--tests]"), "{}", run.stderr);
}
