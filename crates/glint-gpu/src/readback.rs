//! Reading a buffer back from the device. A read is started, and its bytes
//! arrive through the map callback: natively the caller may wait for the queue
//! at once, but a browser's page has one thread that must never block, so the
//! viewer there takes the result in a later frame. Both are this one code path.

use std::sync::{Arc, Condvar, Mutex};

use crate::GpuError;

/// A read on its way; `take` gives its decoded result once the device has
/// delivered the bytes.
pub struct Readback<T> {
    /// The result, and a signal for a thread that waits for it.
    slot: Arc<(Mutex<Option<Result<T, GpuError>>>, Condvar)>,
}

impl<T: Send + 'static> Readback<T> {
    /// Maps `buffer` (copied into by work already submitted) and decodes its
    /// bytes with `decode` once they are there.
    pub(crate) fn start(buffer: wgpu::Buffer, decode: impl FnOnce(&[u8]) -> Result<T, GpuError> + Send + 'static) -> Self {
        let slot = Arc::new((Mutex::new(None), Condvar::new()));
        let (filled, mapped) = (Arc::clone(&slot), buffer.clone());
        buffer.map_async(wgpu::MapMode::Read, .., move |result| {
            let result = result.map_err(|e| GpuError::Runtime(e.to_string())).and_then(|()| {
                let decoded = decode(&mapped.get_mapped_range(..).map_err(|e| GpuError::Runtime(e.to_string()))?);
                mapped.unmap();
                decoded
            });
            *filled.0.lock().unwrap_or_else(|e| e.into_inner()) = Some(result);
            filled.1.notify_all();
        });
        Self { slot }
    }

    /// Whether the device has delivered the result.
    pub fn is_ready(&self) -> bool {
        self.slot.0.lock().unwrap_or_else(|e| e.into_inner()).is_some()
    }

    /// The result, once the device has delivered it; natively the device must
    /// be polled (`wgpu::Device::poll`) for that to happen.
    pub fn take(&self) -> Option<Result<T, GpuError>> {
        self.slot.0.lock().unwrap_or_else(|e| e.into_inner()).take()
    }

    /// Waits for the queue and gives the result. Never in a browser, whose
    /// device delivers only once the page's thread returns to it.
    pub fn wait(self, device: &wgpu::Device) -> Result<T, GpuError> {
        device.poll(wgpu::PollType::wait_indefinitely()).map_err(|e| GpuError::Runtime(e.to_string()))?;
        // Another thread's poll may be running the callback still.
        let (slot, filled) = &*self.slot;
        let mut result = filled.wait_while(slot.lock().unwrap_or_else(|e| e.into_inner()), |r| r.is_none()).unwrap_or_else(|e| e.into_inner());
        result.take().expect("filled")
    }
}
