//! Scene arguments: a file path, or `spd:NAME[:SIZE]` for a generated
//! Standard Procedural Database, checked while the command line is parsed so
//! that a misspelt database is a usage error before any work.

use std::path::{Path, PathBuf};

pub fn parse(text: &str) -> Result<PathBuf, String> {
    if let Some(spec) = glint_scene::spd::spec_of(Path::new(text)) {
        glint_scene::spd::check(spec).map_err(|e| e.to_string())?;
    }
    Ok(PathBuf::from(text))
}
