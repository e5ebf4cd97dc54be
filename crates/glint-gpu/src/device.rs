//! Adapter and device selection.

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
}

impl Gpu {
    /// Prefers a real GPU; `GLINT_ADAPTER` pins one by name.
    pub fn new() -> Result<Self, GpuError> {
        pollster::block_on(Self::new_async())
    }

    async fn new_async() -> Result<Self, GpuError> {
        let mut descriptor = wgpu::InstanceDescriptor::new_without_display_handle_from_env();
        descriptor.backends = backends();
        let instance = wgpu::Instance::new(descriptor);
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

    /// Opens `adapter` with WebGPU's default limits, so that what runs here
    /// runs on any WebGPU device (a kernel that binds too much fails here
    /// too), and subgroup operations where it has them (eye tiles).
    pub async fn open(adapter: wgpu::Adapter) -> Result<Self, GpuError> {
        Self::open_with(adapter, wgpu::Limits::default()).await
    }

    async fn open_with(adapter: wgpu::Adapter, limits: wgpu::Limits) -> Result<Self, GpuError> {
        let (device, queue) = adapter
            .request_device(&wgpu::DeviceDescriptor {
                label: Some("glint"),
                required_limits: limits,
                required_features: adapter.features() & wgpu::Features::SUBGROUP,
                ..Default::default()
            })
            .await
            .map_err(|e| GpuError::Device(e.to_string()))?;
        Ok(Self { adapter, device, queue })
    }

    /// When `error` is a scene's need beyond one of this device's limits
    /// (`GpuError::Limit`) and the adapter offers more of it, the adapter
    /// opened again with its own value of that limit; else `None`, and
    /// `error` stands.
    pub fn raised_for(&self, error: &GpuError) -> Option<Result<Gpu, GpuError>> {
        let GpuError::Limit { limit, .. } = error else { return None };
        let (mut limits, offered) = (self.device.limits(), self.adapter.limits());
        match *limit {
            "max_storage_buffer_binding_size" if offered.max_storage_buffer_binding_size > limits.max_storage_buffer_binding_size => {
                limits.max_storage_buffer_binding_size = offered.max_storage_buffer_binding_size;
                limits.max_buffer_size = limits.max_buffer_size.max(offered.max_buffer_size.min(u64::from(offered.max_storage_buffer_binding_size)));
            }
            "max_buffer_size" if offered.max_buffer_size > limits.max_buffer_size => limits.max_buffer_size = offered.max_buffer_size,
            "max_texture_dimension_2d" if offered.max_texture_dimension_2d > limits.max_texture_dimension_2d => {
                limits.max_texture_dimension_2d = offered.max_texture_dimension_2d;
            }
            _ => return None,
        }
        Some(pollster::block_on(Self::open_with(self.adapter.clone(), limits)))
    }

    pub fn info(&self) -> wgpu::AdapterInfo {
        self.adapter.get_info()
    }

    /// Every device-dependent choice, made from this device.
    pub fn profile(&self) -> crate::DeviceProfile {
        crate::DeviceProfile::of_device(&self.device)
    }

    /// A warning when the adapter's driver is known to give wrong pixels.
    pub fn driver_warning(&self) -> Option<String> {
        driver_warning(&self.info())
    }
}

/// A warning when the adapter `info` describes has a driver known to give
/// wrong pixels: a lavapipe older than Mesa 23, whose shaders silently stop
/// looping after 65,535 iterations.
pub fn driver_warning(info: &wgpu::AdapterInfo) -> Option<String> {
    crate::lavapipe::old_lavapipe_warning(info)
}
