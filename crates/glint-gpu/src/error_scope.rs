//! Catching the validation errors of a piece of GPU work, to report them where
//! the work was asked for. Natively an error scope is pushed and popped at
//! once. A browser's device answers a pop only after the page's thread
//! returns to it, so there no scope is pushed: the errors reach the device's
//! uncaptured-error handler, which the viewer shows as its GPU error.

pub(crate) struct ErrorScope {
    #[cfg(not(target_arch = "wasm32"))]
    guard: wgpu::ErrorScopeGuard,
}

impl ErrorScope {
    pub fn push(device: &wgpu::Device) -> Self {
        #[cfg(target_arch = "wasm32")]
        let _ = device;
        Self {
            #[cfg(not(target_arch = "wasm32"))]
            guard: device.push_error_scope(wgpu::ErrorFilter::Validation),
        }
    }

    /// The first validation error since `push`.
    pub fn pop(self) -> Option<wgpu::Error> {
        #[cfg(not(target_arch = "wasm32"))]
        let error = pollster::block_on(self.guard.pop());
        #[cfg(target_arch = "wasm32")]
        let error = None;
        error
    }
}
