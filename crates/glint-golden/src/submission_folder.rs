//! Students' folders as they arrive from students and archivers: which
//! folders are not work (`__MACOSX`, `.git`), and did-you-mean for a
//! submitted image that is not where the case asks: a file whose name
//! differs only in letter case (`Balls_S1.png`), in extension
//! (`balls_s1.ppm`, `.jpg`), or by sitting in one folder more
//! (`hw2/balls_s1.png`).

use std::fmt;
use std::path::{Path, PathBuf};

/// Folders that archivers add beside the students': macOS's zip resource
/// forks. Hidden ones (`.git`, `.DS_Store`) are tools' too.
const ARCHIVERS: [&str; 1] = ["__MACOSX"];

/// Whether a folder or file in submissions is an archiver's or a tool's,
/// not a student's work.
pub fn is_not_work(name: &str) -> bool {
    name.starts_with('.') || ARCHIVERS.contains(&name)
}

/// A file that is probably the one asked for, and how it differs.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct LookAlike {
    /// Relative to the student's folder.
    pub path: PathBuf,
    pub differences: Vec<String>,
}

impl fmt::Display for LookAlike {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let path = self.path.components().map(|c| c.as_os_str().to_string_lossy()).collect::<Vec<_>>().join("/");
        write!(f, "{path} ({})", self.differences.join("; "))
    }
}

/// The file in `dir` nearest to `wanted` (relative to `dir`, and missing):
/// the one with fewest differences, then first by name.
pub fn look_alike(dir: &Path, wanted: &Path) -> Option<LookAlike> {
    let depth = wanted.components().count();
    let mut files = Vec::new();
    collect(dir, Path::new(""), depth + 1, &mut files);
    files.sort();
    files.iter().filter_map(|file| compared(file, wanted)).min_by_key(|found| found.differences.len())
}

/// Every file below `dir` at most `depth` levels down, relative to `dir`,
/// skipping what archivers and tools add.
fn collect(dir: &Path, relative: &Path, depth: usize, files: &mut Vec<PathBuf>) {
    let Ok(entries) = std::fs::read_dir(dir) else { return };
    for entry in entries.flatten() {
        let name = entry.file_name().to_string_lossy().into_owned();
        if is_not_work(&name) {
            continue;
        }
        let path = entry.path();
        if path.is_dir() {
            if depth > 1 {
                collect(&path, &relative.join(&name), depth - 1, files);
            }
        } else {
            files.push(relative.join(&name));
        }
    }
}

fn compared(file: &Path, wanted: &Path) -> Option<LookAlike> {
    let names = |p: &Path| p.components().map(|c| c.as_os_str().to_string_lossy().into_owned()).collect::<Vec<_>>();
    let (mut found, asked) = (names(file), names(wanted));
    let mut differences = Vec::new();
    if found.len() == asked.len() + 1 {
        let extra = found.remove(0);
        differences.push(format!("inside the folder {extra}/"));
    } else if found.len() != asked.len() {
        return None;
    }
    let (found_name, asked_name) = (found.pop()?, asked.last()?.clone());
    let split = |name: &str| match name.rsplit_once('.') {
        Some((stem, extension)) if !stem.is_empty() => (stem.to_string(), Some(extension.to_string())),
        _ => (name.to_string(), None),
    };
    let ((found_stem, found_ext), (asked_stem, asked_ext)) = (split(&found_name), split(&asked_name));
    let folders_alike = found.iter().zip(&asked).all(|(a, b)| a.eq_ignore_ascii_case(b));
    if !folders_alike || !found_stem.eq_ignore_ascii_case(&asked_stem) {
        return None;
    }
    let lower = |e: &Option<String>| e.as_deref().map(str::to_ascii_lowercase);
    if lower(&found_ext) != lower(&asked_ext) {
        let dotted = |e: Option<String>| e.map_or_else(|| "no extension".to_string(), |e| format!(".{e}"));
        differences.push(format!("a {} file, not {}", dotted(found_ext.clone()), dotted(asked_ext.clone())));
    }
    let same_case = found.iter().zip(&asked).all(|(a, b)| a == b) && found_stem == asked_stem && (found_ext == asked_ext || lower(&found_ext) != lower(&asked_ext));
    if !same_case {
        differences.push("the letter case differs".to_string());
    }
    if differences.is_empty() {
        return None;
    }
    Some(LookAlike { path: file.to_path_buf(), differences })
}

#[cfg(test)]
mod tests {
    use super::*;

    fn folder(files: &[&str]) -> tempfile::TempDir {
        let dir = tempfile::tempdir().unwrap();
        for file in files {
            let path = dir.path().join(file);
            std::fs::create_dir_all(path.parent().unwrap()).unwrap();
            std::fs::write(path, "").unwrap();
        }
        dir
    }

    fn meant(files: &[&str], wanted: &str) -> Option<String> {
        let dir = folder(files);
        look_alike(dir.path(), Path::new(wanted)).map(|found| found.to_string())
    }

    #[test]
    fn case_extension_and_one_more_folder_are_found() {
        assert_eq!(meant(&["Balls_S1.png", "notes.txt"], "balls_s1.png").as_deref(), Some("Balls_S1.png (the letter case differs)"));
        assert_eq!(meant(&["balls_s1.PNG"], "balls_s1.png").as_deref(), Some("balls_s1.PNG (the letter case differs)"));
        assert_eq!(meant(&["balls_s1.ppm"], "balls_s1.png").as_deref(), Some("balls_s1.ppm (a .ppm file, not .png)"));
        assert_eq!(meant(&["BALLS_S1.jpg"], "balls_s1.png").as_deref(), Some("BALLS_S1.jpg (a .jpg file, not .png; the letter case differs)"));
        assert_eq!(meant(&["hw2/balls_s1.png", "hw2/room.png"], "balls_s1.png").as_deref(), Some("hw2/balls_s1.png (inside the folder hw2/)"));
        assert_eq!(meant(&["out/Balls.png"], "out/balls.png").as_deref(), Some("out/Balls.png (the letter case differs)"));
    }

    #[test]
    fn the_nearest_wins_and_strangers_are_not_offered() {
        // The extension alone differs less than extension and case together.
        assert_eq!(meant(&["BALLS_S1.ppm", "balls_s1.ppm"], "balls_s1.png").as_deref(), Some("balls_s1.ppm (a .ppm file, not .png)"));
        assert_eq!(meant(&["room.png", "balls_s2.png", "hw2/deep/balls_s1.png"], "balls_s1.png"), None);
        // What archivers add is never offered.
        assert_eq!(meant(&["__MACOSX/balls_s1.png", ".hidden/balls_s1.png"], "balls_s1.png"), None);
        assert_eq!(meant(&[], "balls_s1.png"), None);
    }
}
