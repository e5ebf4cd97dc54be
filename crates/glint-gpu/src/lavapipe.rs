//! What Glint asks of lavapipe, Mesa's software Vulkan driver, before the first
//! device is made, and what it warns about once one is open. The variables
//! are read by lavapipe alone (and Mesa's shader cache by Mesa's drivers); the
//! device profile (profile.rs) lets them count only when the adapter is lavapipe.
//! A front end describes its work (`Workload`); this file alone turns it into
//! the driver's environment, and it alone changes the process environment.

use std::ffi::OsString;
use std::path::{Path, PathBuf};
use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::Once;

use crate::workload::Workload;

/// The variable by which lavapipe's compiler (llvmpipe) picks its SIMD width.
pub const LAVAPIPE_WIDTH_ENV: &str = "LP_NATIVE_VECTOR_WIDTH";
/// The width Glint asks lavapipe for, in bits. The driver compiles optimised
/// kernels 4 wide in about half the time it takes 8 wide, which a first image
/// waits for; 8 wide, they trace faster, to the same bits, which pays only in
/// long renders ([`LONG_RENDER_MIN_SAMPLES`]; docs/decisions/006-four-wide-vectors.md).
pub const LAVAPIPE_WIDTH: &str = "128";
/// The variable naming the directory Mesa caches compiled shaders in.
pub const SHADER_CACHE_ENV: &str = "MESA_SHADER_CACHE_DIR";
/// The variable by which lavapipe's compiler (gallivm) takes its performance
/// flags; Mesa keys its shader cache by them.
pub const LAVAPIPE_PERF_ENV: &str = "GALLIVM_PERF";
/// The flag that skips LLVM's optimisation passes over a kernel: it compiles
/// in about half the time and runs about half as fast, to the same bits.
pub const QUICK_COMPILE_FLAG: &str = "nopt";
/// Up to this many samples (pixels × samples per pixel × images) a command
/// renders, the compile that a quick kernel saves outweighs the time it loses
/// in running (docs/decisions/030-quick-kernels.md).
pub const QUICK_COMPILE_MAX_SAMPLES: u64 = 400_000;
/// The width of quick kernels and of long renders' kernels on a CPU with
/// 256-bit vectors (AVX2), unless the environment chooses one. Without LLVM's
/// passes the compile grows little with the width, and optimised kernels trace
/// faster at it (docs/decisions/040-wide-vectors-for-quick-and-long-renders.md).
const WIDE_WIDTH: &str = "256";
/// From this many samples on, a render's optimised kernels are compiled at
/// [`wide_width`]: from there the longer compile is paid back
/// (docs/decisions/040-wide-vectors-for-quick-and-long-renders.md).
pub const LONG_RENDER_MIN_SAMPLES: u64 = 4_000_000;

/// `prepare_base` chose the width, and the shader cache by it, for the
/// environment chose neither: `choose_kernels` may choose again.
static WIDTH_CHOSEN: AtomicBool = AtomicBool::new(false);
static CACHE_CHOSEN: AtomicBool = AtomicBool::new(false);
static BASE: Once = Once::new();
static KERNELS: Once = Once::new();

/// Readies lavapipe for `workload` before the process's first device is
/// made ([`prepare_base`], then [`choose_kernels`] once). Lavapipe reads its
/// variables when the first device is made, so only the first workload chooses.
pub(crate) fn prepare(workload: &Workload) {
    prepare_base();
    KERNELS.call_once(|| {
        if let Some(environment) = Environment::alone() {
            choose_kernels(environment, workload.quick_kernels(), workload.samples_for_width());
        }
    });
}

/// The right to change the process environment: held only while this thread
/// is the process's one thread, when nothing can read the environment as it
/// changes. Elsewhere (a test harness's threads, a browser) Glint leaves the
/// environment as it is: lavapipe then picks its own width and kernels, to
/// the same bits.
#[derive(Clone, Copy)]
struct Environment(());

impl Environment {
    fn alone() -> Option<Environment> {
        // Only this thread could start another, and it does not while it holds this.
        #[cfg(target_os = "linux")]
        let alone = std::fs::read_dir("/proc/self/task").is_ok_and(|tasks| tasks.count() == 1);
        // Windows guards its environment with a lock.
        #[cfg(windows)]
        let alone = true;
        #[cfg(not(any(target_os = "linux", windows)))]
        let alone = false;
        alone.then_some(Environment(()))
    }

    fn set(self, name: &str, value: impl AsRef<std::ffi::OsStr>) {
        // SAFETY: `alone` found no other thread that could read the environment.
        unsafe { std::env::set_var(name, value) };
    }
}

/// Asks lavapipe for [`LAVAPIPE_WIDTH`]-bit vectors unless the environment
/// already chooses a width, and gives each width its own shader cache unless
/// the environment names one. Mesa 25.0 keys its cached kernels by CPU and
/// compiler flags but not by vector width (`lp_disk_cache_create`), so a
/// kernel cached by a process at one width crashes a process at another.
/// Drivers read both variables when the first device is made; the record of
/// rendered scenes lives in the cache named here.
pub(crate) fn prepare_base() {
    BASE.call_once(|| {
        let Some(environment) = Environment::alone() else { return };
        let width = std::env::var_os(LAVAPIPE_WIDTH_ENV).unwrap_or_else(|| {
            environment.set(LAVAPIPE_WIDTH_ENV, LAVAPIPE_WIDTH);
            WIDTH_CHOSEN.store(true, Ordering::Relaxed);
            LAVAPIPE_WIDTH.into()
        });
        if std::env::var_os(SHADER_CACHE_ENV).is_none() {
            cache_by_width(environment, &width);
        }
    });
}

/// Points Mesa's shader cache at the directory for `width`, when there is a
/// cache home to put it in.
fn cache_by_width(environment: Environment, width: &OsString) {
    let home = |name| std::env::var_os(name).filter(|v| !v.is_empty());
    if let Some(dir) = shader_cache_dir(width, home("XDG_CACHE_HOME"), home("HOME")) {
        environment.set(SHADER_CACHE_ENV, dir);
        CACHE_CHOSEN.store(true, Ordering::Relaxed);
    }
}

/// [`WIDE_WIDTH`] where this CPU runs 256-bit vectors natively (AVX2), else
/// [`LAVAPIPE_WIDTH`].
fn wide_width() -> &'static str {
    #[cfg(target_arch = "x86_64")]
    let wide = std::arch::is_x86_feature_detected!("avx2");
    #[cfg(not(target_arch = "x86_64"))]
    let wide = false;
    if wide { WIDE_WIDTH } else { LAVAPIPE_WIDTH }
}

/// The width Glint chooses for a command of `samples` samples whose kernels
/// are quick or not: [`wide_width`] for quick kernels and long renders, else
/// [`LAVAPIPE_WIDTH`].
pub fn width_for(samples: u64, quick: bool) -> &'static str {
    if quick || samples >= LONG_RENDER_MIN_SAMPLES { wide_width() } else { LAVAPIPE_WIDTH }
}

/// Asks lavapipe for quick kernels or optimised ones (unless `GALLIVM_PERF`
/// chooses: set empty, it keeps the optimised kernels), at [`width_for`]
/// `samples` unless the environment chose a width, with the shader cache of
/// that width. A viewer's first image waits mostly for the trace kernel's
/// compile: quick kernels show it sooner and trace the frames after it
/// slower, until the next session compiles optimised ones for Mesa's cache
/// (docs/decisions/047-quick-kernels-for-a-first-viewing.md).
fn choose_kernels(environment: Environment, quick: bool, samples: u64) {
    let quick = std::env::var_os(LAVAPIPE_PERF_ENV).is_none() && quick;
    if quick {
        environment.set(LAVAPIPE_PERF_ENV, QUICK_COMPILE_FLAG);
    }
    if WIDTH_CHOSEN.load(Ordering::Relaxed) {
        let width = width_for(samples, quick);
        environment.set(LAVAPIPE_WIDTH_ENV, width);
        if CACHE_CHOSEN.load(Ordering::Relaxed) {
            cache_by_width(environment, &width.into());
        }
    }
}

/// The SIMD width of a lavapipe adapter's kernels, in bits, from its name
/// ("llvmpipe (LLVM 15.0.6, 256 bits)").
pub(crate) fn vector_bits(info: &wgpu::AdapterInfo) -> Option<u32> {
    let name = info.name.strip_suffix(" bits)")?;
    name[name.rfind(' ')? + 1..].parse().ok()
}

/// Whether the kernels this process compiles on lavapipe skip LLVM's
/// optimisation passes, as its `GALLIVM_PERF` asks.
pub(crate) fn kernels_compile_quickly() -> bool {
    std::env::var(LAVAPIPE_PERF_ENV).is_ok_and(|flags| flags.split([',', ' ']).any(|flag| flag == QUICK_COMPILE_FLAG))
}

/// Whether `MESA_SHADER_CACHE_DISABLE` turns Mesa's shader cache off, as
/// Mesa reads a boolean variable.
fn shader_cache_disabled() -> bool {
    std::env::var("MESA_SHADER_CACHE_DISABLE").is_ok_and(|v| matches!(v.to_ascii_lowercase().as_str(), "1" | "true" | "yes" | "y" | "on"))
}

/// For reports of first compiles' times on a Mesa driver: whether Mesa's
/// shader cache lets them stand for a fresh machine's.
pub(crate) fn cold_start_note(info: &wgpu::AdapterInfo) -> Option<&'static str> {
    mesa_version(&info.driver_info).map(|_| match shader_cache_disabled() {
        true => "Mesa's shader cache disabled",
        false => "Mesa's shader cache enabled: set MESA_SHADER_CACHE_DISABLE=true for a fresh machine's times",
    })
}

/// The scenes rendered on this machine, one empty file each (named by a hash
/// of the scene's path) in a directory inside Mesa's shader cache: none when
/// the cache is disabled, since no kernel outlives its process then.
pub struct RenderedScenes {
    dir: Option<PathBuf>,
}

impl RenderedScenes {
    /// The record of the scenes rendered on this machine, kept where this
    /// process's kernels are cached.
    pub fn on_this_machine() -> Self {
        prepare_base();
        let cache = std::env::var_os(SHADER_CACHE_ENV).filter(|dir| !dir.is_empty() && !shader_cache_disabled());
        Self { dir: cache.map(|dir| PathBuf::from(dir).join("glint-rendered-scenes")) }
    }

    pub fn contains(&self, scene: &Path) -> bool {
        self.marker(scene).is_some_and(|marker| marker.exists())
    }

    /// Records `scene` as rendered. Best effort: a cache that cannot be
    /// written costs the next render quick kernels, nothing else.
    pub fn insert(&self, scene: &Path) {
        if let (Some(dir), Some(marker)) = (&self.dir, self.marker(scene)) {
            let _ = std::fs::create_dir_all(dir).and_then(|()| std::fs::write(marker, []));
        }
    }

    fn marker(&self, scene: &Path) -> Option<PathBuf> {
        use std::hash::{Hash, Hasher};
        let mut hasher = std::hash::DefaultHasher::new();
        std::fs::canonicalize(scene).unwrap_or_else(|_| scene.to_path_buf()).hash(&mut hasher);
        Some(self.dir.as_ref()?.join(format!("{:016x}", hasher.finish())))
    }
}

/// `<cache home>/glint/lavapipe-<width>`, the cache home found as Mesa finds
/// it (`$XDG_CACHE_HOME`, else `$HOME/.cache`); `None` leaves Mesa's default.
pub fn shader_cache_dir(width: &OsString, xdg_cache_home: Option<OsString>, home: Option<OsString>) -> Option<PathBuf> {
    let cache_home = xdg_cache_home.map(PathBuf::from).or_else(|| home.map(|h| PathBuf::from(h).join(".cache")))?;
    let width: String = width.to_string_lossy().chars().filter(char::is_ascii_alphanumeric).collect();
    Some(cache_home.join("glint").join(format!("lavapipe-{width}")))
}

/// The Mesa version in a driver-info string such as "Mesa 25.0.7 (LLVM 19.1.7)".
pub fn mesa_version(driver_info: &str) -> Option<(u32, u32)> {
    let rest = &driver_info[driver_info.find("Mesa ")? + 5..];
    let mut parts = rest.split(|c: char| !c.is_ascii_digit()).filter(|s| !s.is_empty());
    Some((parts.next()?.parse().ok()?, parts.next()?.parse().ok()?))
}

/// A warning when the adapter is a lavapipe older than Mesa 23, whose shaders
/// silently stop looping after 65,535 iterations.
pub fn old_lavapipe_warning(info: &wgpu::AdapterInfo) -> Option<String> {
    if !info.name.contains("llvmpipe") {
        return None;
    }
    match mesa_version(&info.driver_info) {
        Some((major, minor)) if major < 23 => Some(format!(
            "warning: lavapipe from Mesa {major}.{minor} silently ends shader loops after 65,535 iterations, \
giving wrong pixels; install Mesa 25 or newer (`bash .ci/setup`)"
        )),
        _ => None,
    }
}

impl Workload {
    /// Whether lavapipe should compile this work's kernels without LLVM's
    /// optimisation passes: a first viewing, or a small render of a scene not
    /// rendered before (docs/decisions/030-quick-kernels.md, 047). A scene
    /// rendered before is likely rendered again, and with optimised kernels
    /// Mesa's cache then holds the kernels that run fastest.
    pub(crate) fn quick_kernels(&self) -> bool {
        !self.rendered_before && (self.interactive || self.samples.is_some_and(|s| s <= QUICK_COMPILE_MAX_SAMPLES))
    }

    /// The samples that choose lavapipe's SIMD width (`lavapipe::width_for`):
    /// a viewer's open-ended frames never choose the long renders' width.
    pub(crate) fn samples_for_width(&self) -> u64 {
        if self.interactive { 0 } else { self.samples.unwrap_or(u64::MAX) }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn each_width_caches_in_its_own_directory_under_the_cache_home() {
        let dir = |width: &str, xdg: Option<&str>, home: Option<&str>| shader_cache_dir(&width.into(), xdg.map(Into::into), home.map(Into::into));
        assert_eq!(dir("128", Some("/c"), Some("/h")), Some(PathBuf::from("/c/glint/lavapipe-128")));
        assert_eq!(dir("256", None, Some("/h")), Some(PathBuf::from("/h/.cache/glint/lavapipe-256")));
        assert_eq!(dir("../x", None, Some("/h")), Some(PathBuf::from("/h/.cache/glint/lavapipe-x")));
        assert_eq!(dir("128", None, None), None);
    }

    #[test]
    fn tests_ask_for_the_width_glint_asks_for() {
        let config = std::fs::read_to_string(concat!(env!("CARGO_MANIFEST_DIR"), "/../../.cargo/config.toml")).unwrap();
        let line = format!("{LAVAPIPE_WIDTH_ENV} = \"{LAVAPIPE_WIDTH}\"");
        assert!(config.lines().any(|l| l == line), ".cargo/config.toml lacks `{line}`");
        let cache = format!("target/lavapipe-{LAVAPIPE_WIDTH}");
        assert!(config.contains(&cache), ".cargo/config.toml lacks the cache {cache}");
    }

    #[test]
    fn the_environment_changes_only_while_the_process_has_one_thread() {
        let (started, stop) = (std::sync::Barrier::new(2), std::sync::Barrier::new(2));
        std::thread::scope(|scope| {
            scope.spawn(|| {
                started.wait();
                stop.wait();
            });
            started.wait();
            assert!(Environment::alone().is_none(), "another thread could read the environment");
            stop.wait();
        });
    }

    #[test]
    fn wide_kernels_for_quick_kernels_and_long_renders() {
        assert_eq!(width_for(512 * 512, true), wide_width());
        assert_eq!(width_for(512 * 512, false), LAVAPIPE_WIDTH);
        assert_eq!(width_for(LONG_RENDER_MIN_SAMPLES - 1, false), LAVAPIPE_WIDTH);
        assert_eq!(width_for(LONG_RENDER_MIN_SAMPLES, false), wide_width());
    }

    #[test]
    fn remembers_rendered_scenes_by_path() {
        let dir = tempfile::tempdir().unwrap();
        let scenes = RenderedScenes { dir: Some(dir.path().join("rendered")) };
        let (a, b) = (dir.path().join("a.toml"), dir.path().join("b.toml"));
        assert!(!scenes.contains(&a));
        scenes.insert(&a);
        assert!(scenes.contains(&a) && !scenes.contains(&b));
        let none = RenderedScenes { dir: None };
        none.insert(&a);
        assert!(!none.contains(&a), "without a shader cache nothing is remembered");
    }

    #[test]
    fn reads_the_vector_width_from_the_adapter_name() {
        let info = |name: &str| wgpu::AdapterInfo { name: name.into(), ..wgpu::AdapterInfo::new(wgpu::DeviceType::Cpu, wgpu::Backend::Vulkan) };
        assert_eq!(vector_bits(&info("llvmpipe (LLVM 15.0.6, 256 bits)")), Some(256));
        assert_eq!(vector_bits(&info("llvmpipe (LLVM 19.1.7, 128 bits)")), Some(128));
        assert_eq!(vector_bits(&info("NVIDIA GeForce RTX 4090")), None);
    }

    #[test]
    fn reads_mesa_versions() {
        assert_eq!(mesa_version("Mesa 25.0.7 (LLVM 19.1.7)"), Some((25, 0)));
        assert_eq!(mesa_version("Mesa 22.3.6 (LLVM 15.0.6)"), Some((22, 3)));
        assert_eq!(mesa_version("NVIDIA 550.1"), None);
    }

    #[test]
    fn warns_only_for_old_lavapipe() {
        let mut info = wgpu::AdapterInfo::new(wgpu::DeviceType::Cpu, wgpu::Backend::Vulkan);
        info.name = "llvmpipe (LLVM 15.0.6, 256 bits)".into();
        info.driver_info = "Mesa 22.3.6 (LLVM 15.0.6)".into();
        assert!(old_lavapipe_warning(&info).is_some());
        info.driver_info = "Mesa 25.0.7 (LLVM 19.1.7)".into();
        assert!(old_lavapipe_warning(&info).is_none());
    }

    #[test]
    fn quick_kernels_only_for_first_viewings_and_small_renders_of_new_scenes() {
        assert!(Workload::render(512 * 512, 512 * 512, false).quick_kernels());
        assert!(Workload::render(1, QUICK_COMPILE_MAX_SAMPLES, false).quick_kernels());
        assert!(!Workload::render(1, QUICK_COMPILE_MAX_SAMPLES + 1, false).quick_kernels());
        assert!(!Workload::render(64 * 64, 64 * 64, true).quick_kernels());
        assert!(Workload::interactive(false).quick_kernels() && !Workload::interactive(true).quick_kernels());
        assert!(!Workload::REPEATED_FRAMES.quick_kernels() && !Workload::UNDESCRIBED.quick_kernels());
    }

    #[test]
    fn the_long_renders_width_for_long_renders_and_repeated_frames_alone() {
        let width = |w: Workload| width_for(w.samples_for_width(), w.quick_kernels());
        assert_eq!(width(Workload::render(1, LONG_RENDER_MIN_SAMPLES, true)), width_for(u64::MAX, false));
        assert_eq!(width(Workload::REPEATED_FRAMES), width_for(LONG_RENDER_MIN_SAMPLES, false), "a benchmark times a long render's kernels");
        assert_eq!(width(Workload::render(1, LONG_RENDER_MIN_SAMPLES - 1, true)), LAVAPIPE_WIDTH);
        assert_eq!(width(Workload::interactive(true)), LAVAPIPE_WIDTH, "a viewer's frames are open-ended");
        assert_eq!(width(Workload::UNDESCRIBED), LAVAPIPE_WIDTH);
    }
}
