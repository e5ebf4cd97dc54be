//! Which of the files a user opens in the page is the scene, and which files
//! the page refuses before reading them: one line each, as the CLI says it.

/// The largest file the page reads: larger ones would take the tab's memory
/// (a browser gives a page a few GiB at most).
pub const MAX_FILE_BYTES: u64 = 256 << 20;

/// The file of `names` to open as the scene; the others (an OBJ's MTL, a
/// TOML scene's meshes) are read through it.
pub fn scene_of<'a>(names: &[&'a str]) -> Result<&'a str, String> {
    let is_scene = |name: &&str| {
        let extension = name.rsplit_once('.').map(|(_, e)| e.to_ascii_lowercase());
        matches!(extension.as_deref(), Some("toml" | "nff" | "ray" | "obj"))
    };
    names.iter().copied().find(is_scene).ok_or_else(|| match names {
        [] => "no file was opened".to_string(),
        [name, ..] => format!("{name}: unknown scene format: expected a .toml, .nff, .ray or .obj file (open an .obj together with its .mtl)"),
    })
}

/// Refuses a file of `bytes` bytes that is too large to read.
pub fn check_size(name: &str, bytes: u64) -> Result<(), String> {
    if bytes > MAX_FILE_BYTES {
        return Err(format!("{name}: the file is {} MiB; the page opens files up to {} MiB", bytes >> 20, MAX_FILE_BYTES >> 20));
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_scene_is_the_first_scene_file_whatever_comes_with_it() {
        assert_eq!(scene_of(&["cube.mtl", "cube.OBJ"]), Ok("cube.OBJ"));
        assert_eq!(scene_of(&["a.nff", "b.toml"]), Ok("a.nff"));
        assert_eq!(scene_of(&["notes.txt", "tetra_s3.ray"]), Ok("tetra_s3.ray"));
        let only_mtl = scene_of(&["cube.mtl"]).unwrap_err();
        assert!(only_mtl.starts_with("cube.mtl: unknown scene format"), "{only_mtl}");
        assert_eq!(scene_of(&[]), Err("no file was opened".into()));
    }

    #[test]
    fn an_oversized_file_is_refused_before_it_is_read() {
        assert_eq!(check_size("big.obj", MAX_FILE_BYTES), Ok(()));
        assert_eq!(check_size("big.obj", 3 << 30), Err("big.obj: the file is 3072 MiB; the page opens files up to 256 MiB".into()));
    }
}
