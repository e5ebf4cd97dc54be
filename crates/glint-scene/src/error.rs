use std::fmt;
use std::path::{Path, PathBuf};

/// A place in a scene file: 1-based line and, where known, column.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Location {
    pub line: usize,
    pub column: Option<usize>,
}

impl Location {
    pub fn line(line: usize) -> Self {
        Self { line, column: None }
    }

    /// The location of byte `offset` in `source`.
    pub fn of_offset(source: &str, offset: usize) -> Self {
        let before = &source[..offset.min(source.len())];
        let line = before.matches('\n').count() + 1;
        let column = before.rsplit('\n').next().map_or(0, |l| l.chars().count()) + 1;
        Self { line, column: Some(column) }
    }
}

/// Any problem with a scene file, naming the file and, where it has one, the place.
#[derive(Debug, Clone, PartialEq)]
pub struct LoadError {
    pub path: PathBuf,
    pub location: Option<Location>,
    pub message: String,
}

impl LoadError {
    pub fn new(path: &Path, location: Option<Location>, message: impl Into<String>) -> Self {
        Self { path: path.to_path_buf(), location, message: message.into() }
    }
}

impl fmt::Display for LoadError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{}", self.path.display())?;
        match self.location {
            Some(Location { line, column: Some(c) }) => write!(f, ":{line}:{c}")?,
            Some(Location { line, column: None }) => write!(f, ":{line}")?,
            None => {}
        }
        write!(f, ": {}", self.message)
    }
}

impl std::error::Error for LoadError {}
