//! Reading the files a user opens in the page, by the file picker or by
//! dropping them on it. A browser reads a file only asynchronously: each
//! batch of files arrives in the inbox, which the app empties at a frame.

use std::cell::RefCell;
use std::rc::Rc;

use wasm_bindgen::closure::Closure;
use wasm_bindgen::JsCast;
use wasm_bindgen_futures::JsFuture;

use crate::opening::check_size;

/// The files opened together, by name, each read or why it was not.
pub(crate) type Batch = Vec<(String, Result<Vec<u8>, String>)>;

#[derive(Clone, Default)]
pub(crate) struct Inbox(Rc<RefCell<Vec<Batch>>>);

impl Inbox {
    /// The batches read since the last call.
    pub fn take(&self) -> Vec<Batch> {
        std::mem::take(&mut self.0.borrow_mut())
    }

    /// Reads files dropped on the page.
    pub fn read_dropped(&self, files: Vec<egui::DroppedFileHandle>, ctx: &egui::Context) {
        let (inbox, ctx) = (self.clone(), ctx.clone());
        wasm_bindgen_futures::spawn_local(async move {
            let mut batch = Vec::new();
            for file in files {
                let name = file.path().display().to_string();
                let size = file.web_file().map_or(0.0, |f| f.size());
                let bytes = match check_size(&name, size as u64) {
                    Ok(()) => file.bytes_async().await.map_err(|e| format!("{name}: cannot read the file: {e}")),
                    Err(e) => Err(e),
                };
                batch.push((name, bytes));
            }
            inbox.0.borrow_mut().push(batch);
            ctx.request_repaint();
        });
    }

    /// Opens the browser's file picker; the chosen files arrive in the inbox.
    pub fn pick(&self, ctx: &egui::Context) -> Result<(), String> {
        let document = web_sys::window().and_then(|w| w.document()).ok_or("the page has no document")?;
        let input: web_sys::HtmlInputElement =
            document.create_element("input").map_err(|e| format!("cannot open a file picker: {e:?}"))?.unchecked_into();
        input.set_type("file");
        input.set_multiple(true);
        input.set_accept(".toml,.nff,.ray,.obj,.mtl");
        let (inbox, ctx, chosen) = (self.clone(), ctx.clone(), input.clone());
        let on_change = Closure::once_into_js(move || {
            let files: Vec<web_sys::File> = chosen.files().map_or_else(Vec::new, |list| (0..list.length()).filter_map(|i| list.get(i)).collect());
            wasm_bindgen_futures::spawn_local(async move {
                let mut batch = Vec::new();
                for file in files {
                    let name = file.name();
                    let bytes = match check_size(&name, file.size() as u64) {
                        Ok(()) => JsFuture::from(file.array_buffer())
                            .await
                            .map(|buffer| js_sys::Uint8Array::new(&buffer).to_vec())
                            .map_err(|e| format!("{name}: cannot read the file: {e:?}")),
                        Err(e) => Err(e),
                    };
                    batch.push((name, bytes));
                }
                inbox.0.borrow_mut().push(batch);
                ctx.request_repaint();
            });
        });
        input.set_onchange(Some(on_change.unchecked_ref()));
        input.click();
        Ok(())
    }
}
