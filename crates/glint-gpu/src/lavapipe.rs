//! What Glint asks of lavapipe, Mesa's software Vulkan driver, before the first
//! device is made, and what it warns about once one is open.

use std::ffi::OsString;
use std::path::PathBuf;

/// The variable by which lavapipe's compiler (llvmpipe) picks its SIMD width.
pub const LAVAPIPE_WIDTH_ENV: &str = "LP_NATIVE_VECTOR_WIDTH";
/// The width Glint asks lavapipe for, in bits. The kernels are mostly
/// per-lane work (divergent loads, private stacks) that 8-wide vectors do not
/// speed up: with 4 lanes they trace as fast, to the same bits, and the driver
/// compiles them in half the time, which a first image waits for
/// (docs/performance.md, "Cold start").
pub const LAVAPIPE_WIDTH: &str = "128";
/// The variable naming the directory Mesa caches compiled shaders in.
pub const SHADER_CACHE_ENV: &str = "MESA_SHADER_CACHE_DIR";

/// Asks lavapipe for [`LAVAPIPE_WIDTH`]-bit vectors unless the environment
/// already chooses a width, and gives each width its own shader cache unless
/// the environment names one. Mesa 25.0 keys its cached kernels by CPU and
/// compiler flags but not by vector width (`lp_disk_cache_create`), so a
/// kernel cached by a process at one width crashes a process at another.
/// Drivers read both variables when the first device is made.
///
/// # Safety
/// Changes the process environment: call it before any other thread runs.
pub unsafe fn prepare_lavapipe() {
    let width = std::env::var_os(LAVAPIPE_WIDTH_ENV).unwrap_or_else(|| {
        // SAFETY: the caller guarantees no other thread reads the environment.
        unsafe { std::env::set_var(LAVAPIPE_WIDTH_ENV, LAVAPIPE_WIDTH) };
        LAVAPIPE_WIDTH.into()
    });
    if std::env::var_os(SHADER_CACHE_ENV).is_none() {
        let home = |name| std::env::var_os(name).filter(|v| !v.is_empty());
        if let Some(dir) = shader_cache_dir(&width, home("XDG_CACHE_HOME"), home("HOME")) {
            // SAFETY: as above.
            unsafe { std::env::set_var(SHADER_CACHE_ENV, dir) };
        }
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
