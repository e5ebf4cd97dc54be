//! Saving from the page: the browser downloads the bytes as a file.

use wasm_bindgen::JsCast;

/// Offers `bytes` as a download called `name`.
pub(crate) fn offer(name: &str, mime: &str, bytes: &[u8]) -> Result<(), String> {
    let failed = |e: wasm_bindgen::JsValue| format!("cannot download {name}: {e:?}");
    let parts = js_sys::Array::of1(&js_sys::Uint8Array::from(bytes));
    let options = web_sys::BlobPropertyBag::new();
    options.set_type(mime);
    let blob = web_sys::Blob::new_with_u8_array_sequence_and_options(&parts, &options).map_err(failed)?;
    let url = web_sys::Url::create_object_url_with_blob(&blob).map_err(failed)?;
    let document = web_sys::window().and_then(|w| w.document()).ok_or("the page has no document")?;
    let link: web_sys::HtmlAnchorElement = document.create_element("a").map_err(failed)?.unchecked_into();
    link.set_href(&url);
    link.set_download(name);
    link.click();
    web_sys::Url::revoke_object_url(&url).map_err(failed)
}
