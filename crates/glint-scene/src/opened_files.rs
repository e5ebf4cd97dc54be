//! Files handed to Glint as bytes rather than found on disk. A browser page
//! has no file system: the files a user opens there are kept here by name,
//! and the loaders read them, and the files they name (an OBJ's MTL, a TOML
//! scene's meshes), as they read files on disk.

use std::collections::HashMap;
use std::path::{Path, PathBuf};
use std::sync::{Arc, Mutex};

static FILES: Mutex<Option<HashMap<PathBuf, Arc<[u8]>>>> = Mutex::new(None);

/// Keeps `bytes` as the file `path`, in place of any earlier file of that name.
pub fn provide(path: impl Into<PathBuf>, bytes: impl Into<Arc<[u8]>>) {
    FILES.lock().unwrap_or_else(|e| e.into_inner()).get_or_insert_default().insert(path.into(), bytes.into());
}

/// The bytes of the file at `path`: those handed over, else the file on disk
/// (a browser page has none).
pub(crate) fn read(path: &Path) -> std::io::Result<Vec<u8>> {
    let provided = FILES.lock().unwrap_or_else(|e| e.into_inner()).as_ref().and_then(|files| files.get(path).cloned());
    match provided {
        Some(bytes) => Ok(bytes.to_vec()),
        #[cfg(target_arch = "wasm32")]
        None => Err(std::io::Error::new(std::io::ErrorKind::NotFound, "not among the files opened; open it together with the scene")),
        #[cfg(not(target_arch = "wasm32"))]
        None => std::fs::read(path),
    }
}

#[cfg(test)]
mod tests {
    use std::path::Path;

    #[test]
    fn an_obj_handed_over_finds_its_mtl_and_a_missing_one_is_named() {
        let obj = "mtllib handed-over.mtl\nusemtl red\nv 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n";
        super::provide("handed-over.obj", obj.as_bytes());
        let without = crate::load(Path::new("handed-over.obj")).unwrap();
        let warning = without.warnings.iter().map(ToString::to_string).collect::<Vec<_>>().join("\n");
        assert!(warning.starts_with("handed-over.obj:1:") && warning.contains("cannot read material library `handed-over.mtl`"), "{warning}");
        super::provide("handed-over.mtl", &b"newmtl red\nKd 1 0 0\n"[..]);
        let scene = crate::load(Path::new("handed-over.obj")).unwrap();
        assert_eq!(scene.materials.iter().filter(|m| m.name == "red").count(), 1, "{:?}", scene.materials);
    }

    #[test]
    fn empty_and_binary_files_handed_over_are_errors_naming_the_file() {
        super::provide("empty.nff", Vec::new());
        let empty = crate::load(Path::new("empty.nff")).unwrap_err().to_string();
        assert!(empty.starts_with("empty.nff"), "{empty}");
        super::provide("garbage.toml", vec![0x89, b'P', b'N', b'G', 0, 0xff, 0xfe]);
        let garbage = crate::load(Path::new("garbage.toml")).unwrap_err().to_string();
        assert!(garbage.starts_with("garbage.toml:1:") && garbage.contains("not a text file"), "{garbage}");
    }
}
