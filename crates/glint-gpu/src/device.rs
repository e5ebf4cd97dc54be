//! Adapter and device selection.

use crate::GpuError;

/// Environment variable that pins the adapter: the first adapter whose name
/// contains its value (case-insensitive) is used, e.g. `GLINT_ADAPTER=llvmpipe`.
pub const ADAPTER_ENV: &str = "GLINT_ADAPTER";

const NO_ADAPTER_HINT: &str = "no GPU adapter found: install a Vulkan driver; \
without a GPU, lavapipe provides one (Debian/Ubuntu: apt-get install mesa-vulkan-drivers libvulkan1, \
Mesa 25 or newer; on Debian 12 from bookworm-backports — `bash .ci/setup` does this)";

/// The variable by which lavapipe's compiler (llvmpipe) picks its SIMD width.
pub const LAVAPIPE_WIDTH_ENV: &str = "LP_NATIVE_VECTOR_WIDTH";
/// The width Glint's batch commands ask lavapipe for, in bits. The kernels
/// are mostly per-lane work (divergent loads, private stacks) that 8-wide
/// vectors do not speed up: with 4 lanes they trace as fast, to the same
/// bits, and the driver compiles them in half the time, which a first image
/// waits for (docs/performance.md, "Cold start"). Not for the viewer: Mesa
/// 25.0's lavapipe corrupts its heap drawing egui at this width.
pub const LAVAPIPE_WIDTH: &str = "128";

/// Asks lavapipe for [`LAVAPIPE_WIDTH`]-bit vectors unless the environment
/// already chooses a width; drivers read it when the first device is made.
///
/// # Safety
/// Changes the process environment: call it before any other thread runs.
pub unsafe fn prefer_lavapipe_width() {
    if std::env::var_os(LAVAPIPE_WIDTH_ENV).is_none() {
        // SAFETY: the caller guarantees no other thread reads the environment.
        unsafe { std::env::set_var(LAVAPIPE_WIDTH_ENV, LAVAPIPE_WIDTH) };
    }
}

/// An open device with the adapter's own limits.
pub struct Gpu {
    pub adapter: wgpu::Adapter,
    pub device: wgpu::Device,
    pub queue: wgpu::Queue,
}

impl Gpu {
    /// Prefers a real GPU; `GLINT_ADAPTER` pins one by name.
    pub fn new() -> Result<Self, GpuError> {
        pollster::block_on(Self::new_async())
    }

    async fn new_async() -> Result<Self, GpuError> {
        let instance = wgpu::Instance::new(wgpu::InstanceDescriptor::new_without_display_handle_from_env());
        let adapter = Self::pick_adapter(&instance).await?;
        Self::open(adapter).await
    }

    async fn pick_adapter(instance: &wgpu::Instance) -> Result<wgpu::Adapter, GpuError> {
        let mut adapters = instance.enumerate_adapters(wgpu::Backends::all()).await;
        // Only adapters that can run compute shaders qualify.
        adapters.retain(|a| a.get_downlevel_capabilities().flags.contains(wgpu::DownlevelFlags::COMPUTE_SHADERS));
        if let Ok(wanted) = std::env::var(ADAPTER_ENV) {
            let wanted_lc = wanted.to_lowercase();
            let names: Vec<String> = adapters.iter().map(|a| a.get_info().name).collect();
            return adapters
                .into_iter()
                .find(|a| a.get_info().name.to_lowercase().contains(&wanted_lc))
                .ok_or_else(|| {
                    if names.is_empty() {
                        GpuError::NoAdapter(NO_ADAPTER_HINT.into())
                    } else {
                        GpuError::NoAdapter(format!(
                            "{ADAPTER_ENV}={wanted} matches no adapter; found: {}",
                            names.join(", ")
                        ))
                    }
                });
        }
        let rank = |a: &wgpu::Adapter| match a.get_info().device_type {
            wgpu::DeviceType::DiscreteGpu => 0,
            wgpu::DeviceType::IntegratedGpu => 1,
            wgpu::DeviceType::VirtualGpu => 2,
            wgpu::DeviceType::Other => 3,
            wgpu::DeviceType::Cpu => 4,
        };
        adapters.sort_by_key(|a| (rank(a), a.get_info().backend != wgpu::Backend::Vulkan));
        adapters.into_iter().next().ok_or_else(|| GpuError::NoAdapter(NO_ADAPTER_HINT.into()))
    }

    /// Opens `adapter` asking for its own limits, not wgpu's conservative defaults.
    pub async fn open(adapter: wgpu::Adapter) -> Result<Self, GpuError> {
        let (device, queue) = adapter
            .request_device(&wgpu::DeviceDescriptor {
                label: Some("glint"),
                required_limits: adapter.limits(),
                ..Default::default()
            })
            .await
            .map_err(|e| GpuError::Device(e.to_string()))?;
        Ok(Self { adapter, device, queue })
    }

    pub fn info(&self) -> wgpu::AdapterInfo {
        self.adapter.get_info()
    }

    /// A warning when the adapter is a lavapipe older than Mesa 23, whose shaders
    /// silently stop looping after 65,535 iterations.
    pub fn driver_warning(&self) -> Option<String> {
        old_lavapipe_warning(&self.info())
    }
}

/// The Mesa version in a driver-info string such as "Mesa 25.0.7 (LLVM 19.1.7)".
pub fn mesa_version(driver_info: &str) -> Option<(u32, u32)> {
    let rest = &driver_info[driver_info.find("Mesa ")? + 5..];
    let mut parts = rest.split(|c: char| !c.is_ascii_digit()).filter(|s| !s.is_empty());
    Some((parts.next()?.parse().ok()?, parts.next()?.parse().ok()?))
}

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
