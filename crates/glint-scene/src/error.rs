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
        let before = &source[..source.floor_char_boundary(offset)];
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

/// `text` with control characters (line breaks, escape sequences, NUL) written
/// as Rust escapes, so that a message quoting a scene file stays one line.
pub(crate) fn escape_controls(text: &str) -> String {
    text.chars()
        .flat_map(|c| {
            let escaped = c.is_control().then(|| c.escape_default());
            escaped.into_iter().flatten().chain((!c.is_control()).then_some(c))
        })
        .collect()
}

impl fmt::Display for LoadError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        // A message is always one line, whatever the file or its name holds.
        write!(f, "{}", escape_controls(&self.path.display().to_string()))?;
        match self.location {
            Some(Location { line, column: Some(c) }) => write!(f, ":{line}:{c}")?,
            Some(Location { line, column: None }) => write!(f, ":{line}")?,
            None => {}
        }
        write!(f, ": {}", escape_controls(&self.message))
    }
}

impl std::error::Error for LoadError {}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn display_is_one_line_whatever_the_message_holds() {
        let e = LoadError::new(Path::new("a\nb.nff"), Some(Location::line(3)), "unknown keyword `x\n\u{1b}[31m\0`");
        let shown = e.to_string();
        assert_eq!(shown, "a\\nb.nff:3: unknown keyword `x\\n\\u{1b}[31m\\u{0}`");
        assert_eq!(shown.lines().count(), 1);
    }

    #[test]
    fn location_of_an_offset_counts_characters() {
        let src = "ab\né x\n";
        assert_eq!(Location::of_offset(src, 0), Location { line: 1, column: Some(1) });
        assert_eq!(Location::of_offset(src, 6), Location { line: 2, column: Some(3) });
        assert_eq!(Location::of_offset(src, 100), Location { line: 3, column: Some(1) });
        // Inside `é`: the place of the character, not a panic.
        assert_eq!(Location::of_offset(src, 4), Location { line: 2, column: Some(1) });
    }
}

