//! Notices when files change on disk, by polling their modification times: a
//! scene file or the shader folder is a handful of files, and polling needs no
//! platform watcher.

use std::path::{Path, PathBuf};
use std::time::{Duration, SystemTime};

use web_time::Instant;
/// How often the files are looked at.
const INTERVAL: Duration = Duration::from_millis(400);

pub struct Watch {
    files: Vec<PathBuf>,
    seen: Vec<Option<(SystemTime, u64)>>,
    last_look: Instant,
}

impl Watch {
    pub fn new(files: Vec<PathBuf>) -> Self {
        let seen = files.iter().map(|f| stamp(f)).collect();
        Self { files, seen, last_look: Instant::now() }
    }

    /// True once after any of the files changed (or appeared or vanished).
    pub fn changed(&mut self) -> bool {
        if self.last_look.elapsed() < INTERVAL {
            return false;
        }
        self.last_look = Instant::now();
        let now: Vec<_> = self.files.iter().map(|f| stamp(f)).collect();
        let changed = now != self.seen;
        self.seen = now;
        changed
    }
}

fn stamp(path: &Path) -> Option<(SystemTime, u64)> {
    let meta = std::fs::metadata(path).ok()?;
    Some((meta.modified().ok()?, meta.len()))
}
