//! What Glint asks of lavapipe, Mesa's software Vulkan driver, before the first
//! device is made, and what it warns about once one is open. The variables
//! are read by lavapipe alone (and Mesa's shader cache by Mesa's drivers); the
//! device profile (profile.rs) lets them count only when the adapter is lavapipe.

use std::ffi::OsString;
use std::path::{Path, PathBuf};
use std::sync::atomic::{AtomicBool, Ordering};

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

/// `prepare_driver_environment` chose the width, and the shader cache by it, for the
/// environment chose neither: `compile_for_samples` may choose again.
static WIDTH_CHOSEN: AtomicBool = AtomicBool::new(false);
static CACHE_CHOSEN: AtomicBool = AtomicBool::new(false);

/// Asks lavapipe for [`LAVAPIPE_WIDTH`]-bit vectors unless the environment
/// already chooses a width, and gives each width its own shader cache unless
/// the environment names one. Mesa 25.0 keys its cached kernels by CPU and
/// compiler flags but not by vector width (`lp_disk_cache_create`), so a
/// kernel cached by a process at one width crashes a process at another.
/// Drivers read both variables when the first device is made.
///
/// # Safety
/// Changes the process environment: call it before any other thread runs.
pub unsafe fn prepare_driver_environment() {
    let width = std::env::var_os(LAVAPIPE_WIDTH_ENV).unwrap_or_else(|| {
        // SAFETY: the caller guarantees no other thread reads the environment.
        unsafe { std::env::set_var(LAVAPIPE_WIDTH_ENV, LAVAPIPE_WIDTH) };
        WIDTH_CHOSEN.store(true, Ordering::Relaxed);
        LAVAPIPE_WIDTH.into()
    });
    if std::env::var_os(SHADER_CACHE_ENV).is_none() {
        // SAFETY: as above.
        unsafe { cache_by_width(&width) };
    }
}

/// Points Mesa's shader cache at the directory for `width`, when there is a
/// cache home to put it in.
///
/// # Safety
/// As [`prepare_driver_environment`].
unsafe fn cache_by_width(width: &OsString) {
    let home = |name| std::env::var_os(name).filter(|v| !v.is_empty());
    if let Some(dir) = shader_cache_dir(width, home("XDG_CACHE_HOME"), home("HOME")) {
        // SAFETY: the caller guarantees no other thread reads the environment.
        unsafe { std::env::set_var(SHADER_CACHE_ENV, dir) };
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

/// Chooses lavapipe's kernels for a command that renders `samples` samples in
/// all: without LLVM's optimisation passes for a small render of a scene not
/// rendered before ([`quick_compile_pays`]), unless the environment sets
/// `GALLIVM_PERF` (set empty, it keeps the optimised kernels); and at
/// [`width_for`] unless the environment chose a width, with the shader cache
/// of that width. Lavapipe reads the flags and the width when the first
/// device is made.
///
/// # Safety
/// Changes the process environment: call it after [`prepare_driver_environment`] and
/// before any other thread runs.
pub unsafe fn compile_for_samples(samples: u64, rendered_before: bool) {
    // SAFETY: the caller's guarantee.
    unsafe { choose_kernels(quick_compile_pays(samples, rendered_before), samples) }
}

/// Chooses lavapipe's kernels for the viewer, as [`compile_for_samples`] does
/// for a command: quick ones for a scene not viewed or rendered before. What
/// its user waits for is the first image, most of which a cold start spends
/// compiling the trace kernel: quick kernels show it sooner and trace the
/// frames after it slower, until the next session compiles optimised ones for
/// Mesa's cache (docs/decisions/047-quick-kernels-for-a-first-viewing.md).
///
/// # Safety
/// As [`compile_for_samples`].
pub unsafe fn compile_for_viewer(viewed_before: bool) {
    // The viewer's samples are open-ended: none chooses the long renders' width.
    // SAFETY: the caller's guarantee.
    unsafe { choose_kernels(!viewed_before, 0) }
}

/// Asks lavapipe for quick kernels or optimised ones (unless `GALLIVM_PERF`
/// chooses), at [`width_for`] `samples` unless the environment chose a width.
///
/// # Safety
/// As [`compile_for_samples`].
unsafe fn choose_kernels(quick: bool, samples: u64) {
    let quick = std::env::var_os(LAVAPIPE_PERF_ENV).is_none() && quick;
    if quick {
        // SAFETY: the caller guarantees no other thread reads the environment.
        unsafe { std::env::set_var(LAVAPIPE_PERF_ENV, QUICK_COMPILE_FLAG) };
    }
    if WIDTH_CHOSEN.load(Ordering::Relaxed) {
        let width = width_for(samples, quick);
        // SAFETY: as above.
        unsafe { std::env::set_var(LAVAPIPE_WIDTH_ENV, width) };
        if CACHE_CHOSEN.load(Ordering::Relaxed) {
            // SAFETY: as above.
            unsafe { cache_by_width(&width.into()) };
        }
    }
}

/// The SIMD width of a lavapipe adapter's kernels, in bits, from its name
/// ("llvmpipe (LLVM 15.0.6, 256 bits)").
pub(crate) fn vector_bits(info: &wgpu::AdapterInfo) -> Option<u32> {
    let name = info.name.strip_suffix(" bits)")?;
    name[name.rfind(' ')? + 1..].parse().ok()
}

/// Whether a command of `samples` samples is better served by quick kernels:
/// a small render of a scene not rendered before. A scene rendered before is
/// likely rendered again, and with optimised kernels Mesa's cache then holds
/// the kernels that run fastest; a quick kernel would be cached and rerun.
pub fn quick_compile_pays(samples: u64, rendered_before: bool) -> bool {
    !rendered_before && samples <= QUICK_COMPILE_MAX_SAMPLES
}

/// Whether the kernels this process compiles on lavapipe skip LLVM's
/// optimisation passes, as its `GALLIVM_PERF` asks.
pub(crate) fn kernels_compile_quickly() -> bool {
    std::env::var(LAVAPIPE_PERF_ENV).is_ok_and(|flags| flags.split([',', ' ']).any(|flag| flag == QUICK_COMPILE_FLAG))
}

/// Whether `MESA_SHADER_CACHE_DISABLE` turns Mesa's shader cache off, as
/// Mesa reads a boolean variable.
pub fn shader_cache_disabled() -> bool {
    std::env::var("MESA_SHADER_CACHE_DISABLE").is_ok_and(|v| matches!(v.to_ascii_lowercase().as_str(), "1" | "true" | "yes" | "y" | "on"))
}

/// The scenes rendered on this machine, one empty file each (named by a hash
/// of the scene's path) in a directory inside Mesa's shader cache: none when
/// the cache is disabled, since no kernel outlives its process then.
pub struct RenderedScenes {
    dir: Option<PathBuf>,
}

impl RenderedScenes {
    /// The record of the shader cache this process uses (call it after
    /// [`prepare_driver_environment`], which names the cache).
    pub fn of_shader_cache() -> Self {
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
    fn quick_kernels_only_for_small_renders_of_new_scenes() {
        assert!(quick_compile_pays(512 * 512, false));
        assert!(quick_compile_pays(QUICK_COMPILE_MAX_SAMPLES, false));
        assert!(!quick_compile_pays(QUICK_COMPILE_MAX_SAMPLES + 1, false));
        assert!(!quick_compile_pays(1024 * 1024, false));
        assert!(!quick_compile_pays(64 * 64, true));
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
}
