//! Adapter and device selection.

use crate::profile::{DeviceProfile, ProfileName};
use crate::workload::Workload;
use crate::GpuError;

/// Environment variable that pins the adapter: the first adapter whose name
/// contains its value (case-insensitive) is used, e.g. `GLINT_ADAPTER=llvmpipe`.
pub const ADAPTER_ENV: &str = "GLINT_ADAPTER";

/// What to install when no adapter is found.
pub const NO_ADAPTER_HINT: &str = "install a Vulkan driver; \
without a GPU, lavapipe provides one (Debian/Ubuntu: apt-get install mesa-vulkan-drivers libvulkan1, \
Mesa 25 or newer; on Debian 12 from bookworm-backports — `bash .ci/setup` does this)";

/// The backends Glint looks for adapters on: those `WGPU_BACKEND` names, else
/// the primary ones (Vulkan, Metal, DX12). Starting GL too would cost every
/// process a second driver's start-up (a third of `glint info` on lavapipe)
/// for an adapter ranked below them.
pub fn backends() -> wgpu::Backends {
    wgpu::Backends::from_env().unwrap_or(wgpu::Backends::PRIMARY)
}

/// Sorts adapters best first: a real GPU before a virtual or software one,
/// Vulkan before other backends.
pub fn adapter_rank(adapter: &wgpu::Adapter) -> (u8, bool) {
    let info = adapter.get_info();
    let kind = match info.device_type {
        wgpu::DeviceType::DiscreteGpu => 0,
        wgpu::DeviceType::IntegratedGpu => 1,
        wgpu::DeviceType::VirtualGpu => 2,
        wgpu::DeviceType::Other => 3,
        wgpu::DeviceType::Cpu => 4,
    };
    (kind, info.backend != wgpu::Backend::Vulkan)
}

/// An open device, with WebGPU's default limits unless a scene needs more.
pub struct Gpu {
    pub adapter: wgpu::Adapter,
    pub device: wgpu::Device,
    pub queue: wgpu::Queue,
    profile: DeviceProfile,
}

impl Gpu {
    /// Prefers a real GPU; `GLINT_ADAPTER` pins one by name. For work no
    /// front end describes (see [`Gpu::for_workload`]).
    pub fn new() -> Result<Self, GpuError> {
        Self::for_workload(&Workload::UNDESCRIBED)
    }

    /// [`Gpu::new`], with the driver readied for `workload` if this is the
    /// process's first device ([`Workload::prepare_driver`]).
    pub fn for_workload(workload: &Workload) -> Result<Self, GpuError> {
        workload.prepare_driver()?;
        pollster::block_on(Self::new_async(std::env::var(ADAPTER_ENV).ok()))
    }

    /// The first adapter whose name contains `name` (case-insensitive),
    /// whatever `GLINT_ADAPTER` says: for tests of one adapter's profile.
    pub fn named(name: &str) -> Result<Self, GpuError> {
        Workload::UNDESCRIBED.prepare_driver()?;
        pollster::block_on(Self::new_async(Some(name.to_string())))
    }

    async fn new_async(wanted: Option<String>) -> Result<Self, GpuError> {
        let mut descriptor = wgpu::InstanceDescriptor::new_without_display_handle_from_env();
        descriptor.backends = backends();
        let instance = wgpu::Instance::new(descriptor);
        let adapter = Self::pick_adapter(&instance, wanted).await?;
        Self::open(adapter).await
    }

    async fn pick_adapter(instance: &wgpu::Instance, wanted: Option<String>) -> Result<wgpu::Adapter, GpuError> {
        let mut adapters = instance.enumerate_adapters(wgpu::Backends::all()).await;
        // Only adapters that can run compute shaders qualify.
        adapters.retain(|a| a.get_downlevel_capabilities().flags.contains(wgpu::DownlevelFlags::COMPUTE_SHADERS));
        if let Some(wanted) = wanted {
            let wanted_lc = wanted.to_lowercase();
            let names: Vec<String> = adapters.iter().map(|a| a.get_info().name).collect();
            return adapters
                .into_iter()
                .find(|a| a.get_info().name.to_lowercase().contains(&wanted_lc))
                .ok_or_else(|| {
                    if names.is_empty() {
                        GpuError::NoAdapter(format!("no GPU adapter found: {NO_ADAPTER_HINT}"))
                    } else {
                        GpuError::NoAdapter(format!(
                            "{ADAPTER_ENV}={wanted} matches no adapter; found: {}",
                            names.join(", ")
                        ))
                    }
                });
        }
        adapters.sort_by_key(adapter_rank);
        adapters.into_iter().next().ok_or_else(|| GpuError::NoAdapter(format!("no GPU adapter found: {NO_ADAPTER_HINT}")))
    }

    /// Opens `adapter` as [`device_descriptor`] asks, with WebGPU's default limits.
    pub async fn open(adapter: wgpu::Adapter) -> Result<Self, GpuError> {
        Self::open_with(adapter, wgpu::Limits::default()).await
    }

    async fn open_with(adapter: wgpu::Adapter, limits: wgpu::Limits) -> Result<Self, GpuError> {
        let descriptor = wgpu::DeviceDescriptor { required_limits: limits, ..device_descriptor(&adapter, SceneLimits::Default) };
        let (device, queue) = adapter.request_device(&descriptor).await.map_err(|e| GpuError::Device(e.to_string()))?;
        let profile = DeviceProfile::of_device(&device)?;
        Ok(Self { adapter, device, queue, profile })
    }

    /// When `error` is a scene's need beyond one of this device's limits
    /// (`GpuError::Limit`) and the adapter offers more of it, the adapter
    /// opened again with its own value of that limit; else `None`, and
    /// `error` stands.
    pub fn raised_for(&self, error: &GpuError) -> Option<Result<Gpu, GpuError>> {
        let GpuError::Limit { limit, .. } = error else { return None };
        let mut limits = self.device.limits();
        raise(&mut limits, &self.adapter.limits(), limit).then(|| pollster::block_on(Self::open_with(self.adapter.clone(), limits)))
    }

    pub fn info(&self) -> wgpu::AdapterInfo {
        self.adapter.get_info()
    }

    /// Every device-dependent choice, made from this device (or forced by
    /// `GLINT_PROFILE`).
    pub fn profile(&self) -> DeviceProfile {
        self.profile
    }

    /// How far Mesa's shader cache makes a first compile's times those of a
    /// fresh machine, for reports of them; `None` on other drivers.
    pub fn cold_start_note(&self) -> Option<&'static str> {
        crate::lavapipe::cold_start_note(&self.info())
    }

    /// A warning when the adapter's driver is known to give wrong pixels.
    pub fn driver_warning(&self) -> Option<String> {
        driver_warning(&self.info())
    }
}

/// How far a device's limits reach for a scene's size.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum SceneLimits {
    /// WebGPU's defaults; a scene that needs more opens the device again
    /// (`Gpu::raised_for`).
    Default,
    /// The adapter's own, for a device that cannot be opened again: the
    /// viewer's, which eframe owns.
    Adapter,
}

/// The limits a scene's size may need beyond WebGPU's defaults.
const SCENE_SIZED_LIMITS: [&str; 3] = ["max_storage_buffer_binding_size", "max_buffer_size", "max_texture_dimension_2d"];

/// What Glint asks of a device of `adapter`: subgroup operations where its
/// profile walks eye tiles, and WebGPU's default limits, so that what runs
/// here runs on any WebGPU device (a kernel that binds too much fails here
/// too); `scene_limits` says how far the limits a scene's size needs reach.
pub fn device_descriptor(adapter: &wgpu::Adapter, scene_limits: SceneLimits) -> wgpu::DeviceDescriptor<'static> {
    let quick_kernels = crate::lavapipe::kernels_compile_quickly();
    // A `GLINT_PROFILE` that names no profile fails when the renderer is made.
    let forced = ProfileName::forced().ok().flatten();
    let profile = DeviceProfile::forced(forced, &adapter.get_info(), adapter.features(), quick_kernels);
    let (required_features, required_limits) = requirements(&profile, &adapter.limits(), scene_limits);
    wgpu::DeviceDescriptor { label: Some("glint"), required_features, required_limits, ..Default::default() }
}

/// [`device_descriptor`]'s features and limits for an adapter of `profile`
/// which offers the limits `offered`.
fn requirements(profile: &DeviceProfile, offered: &wgpu::Limits, scene_limits: SceneLimits) -> (wgpu::Features, wgpu::Limits) {
    let eye_tiles = profile.eye_tiles;
    let mut limits = wgpu::Limits::default();
    if scene_limits == SceneLimits::Adapter {
        for limit in SCENE_SIZED_LIMITS {
            raise(&mut limits, offered, limit);
        }
    }
    (if eye_tiles { wgpu::Features::SUBGROUP } else { wgpu::Features::empty() }, limits)
}

/// Raises `limit` in `limits` to the adapter's `offered` value; false when
/// it is no limit of a scene's size or the adapter offers no more.
fn raise(limits: &mut wgpu::Limits, offered: &wgpu::Limits, limit: &str) -> bool {
    match limit {
        "max_storage_buffer_binding_size" if offered.max_storage_buffer_binding_size > limits.max_storage_buffer_binding_size => {
            limits.max_storage_buffer_binding_size = offered.max_storage_buffer_binding_size;
            limits.max_buffer_size = limits.max_buffer_size.max(offered.max_buffer_size.min(u64::from(offered.max_storage_buffer_binding_size)));
        }
        "max_buffer_size" if offered.max_buffer_size > limits.max_buffer_size => limits.max_buffer_size = offered.max_buffer_size,
        "max_texture_dimension_2d" if offered.max_texture_dimension_2d > limits.max_texture_dimension_2d => {
            limits.max_texture_dimension_2d = offered.max_texture_dimension_2d;
        }
        _ => return false,
    }
    true
}

/// A warning when the adapter `info` describes has a driver known to give
/// wrong pixels: a lavapipe older than Mesa 23, whose shaders silently stop
/// looping after 65,535 iterations.
pub fn driver_warning(info: &wgpu::AdapterInfo) -> Option<String> {
    crate::lavapipe::old_lavapipe_warning(info)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::profile::tests::{adapter, lavapipe};

    /// A device asks for subgroup operations exactly where its profile walks
    /// eye tiles, and for WebGPU's default limits unless it cannot be opened
    /// again; then for the adapter's own limits of a scene's size alone.
    #[test]
    fn a_device_is_asked_for_what_its_profile_uses() {
        let mut offered = wgpu::Limits::default();
        (offered.max_texture_dimension_2d, offered.max_storage_buffer_binding_size, offered.max_buffer_size) = (16384, 1 << 31, 1 << 32);
        offered.max_storage_buffers_per_shader_stage = 64;
        let ask = |info: &wgpu::AdapterInfo, quick_kernels| {
            requirements(&DeviceProfile::of(info, wgpu::Features::SUBGROUP, quick_kernels), &offered, SceneLimits::Default)
        };
        assert_eq!(ask(&lavapipe(128), false), (wgpu::Features::SUBGROUP, wgpu::Limits::default()), "eye tiles");
        assert_eq!(ask(&lavapipe(128), true).0, wgpu::Features::empty(), "quick kernels read textures, so walk no eye tiles");
        let gpu = adapter("NVIDIA GeForce RTX 4090", wgpu::DeviceType::DiscreteGpu, 32);
        assert_eq!(ask(&gpu, false), (wgpu::Features::empty(), wgpu::Limits::default()));
        let small_groups = adapter("a GPU of 8-lane SIMD groups", wgpu::DeviceType::IntegratedGpu, 8);
        assert_eq!(ask(&small_groups, false).0, wgpu::Features::SUBGROUP);
        let without = requirements(&DeviceProfile::of(&lavapipe(128), wgpu::Features::empty(), false), &offered, SceneLimits::Default);
        assert_eq!(without.0, wgpu::Features::empty(), "an adapter without subgroups is not asked for them");
        let plain = DeviceProfile::forced(Some(ProfileName::Plain), &lavapipe(128), wgpu::Features::SUBGROUP, false);
        assert_eq!(requirements(&plain, &offered, SceneLimits::Default).0, wgpu::Features::empty(), "the plain profile walks no eye tiles");

        let lavapipe_profile = DeviceProfile::of(&lavapipe(128), wgpu::Features::SUBGROUP, false);
        let (_, limits) = requirements(&lavapipe_profile, &offered, SceneLimits::Adapter);
        let sized = wgpu::Limits {
            max_texture_dimension_2d: 16384,
            max_storage_buffer_binding_size: 1 << 31,
            max_buffer_size: 1 << 32,
            ..wgpu::Limits::default()
        };
        assert_eq!(limits, sized);
    }
}
