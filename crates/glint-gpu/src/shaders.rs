//! WGSL composition. `shaders/kernels/` holds one file per kernel (its entry
//! point and its own bindings), `shaders/lib/` the shared code as the lecture
//! reads it, and `shaders/fast/` the variants a device's tuning asks for. A
//! file states what it uses in a line `// import: a b fast/c` (files of `lib/`,
//! or with a folder of `shaders/`, without the extension); a kernel is the generated prelude of constants shared with the
//! host (`gpu_types::wgsl_prelude`), the flags of the scene it is
//! specialised to (`Specialization`) and of the device's tuning (`Tuning`),
//! followed by the files its imports reach,
//! each once, every file after the files it imports. A `fast/` file stands in
//! for a `lib/` file where the tuning says (`Tuning::file`), and a kernel's own
//! file for a `lib/` file in that kernel alone (`Kernel::file_for`: the probe's
//! notes, which record the ray tree). So a kernel's file list
//! is derived from the code, and holds only what the kernel uses. A line
//! `// generated: NAME` becomes the dispatch on primitive kinds generated from
//! glint-encoding's registry (primitive_dispatch.rs), and its file imports every
//! kind's file. Errors are mapped back to the file and line they came from.
//!
//! build.rs embeds every file under `shaders/`; `ShaderSource::Dir` reads
//! them from disk instead (the viewer's hot reload).

use std::path::{Path, PathBuf};

use glint_encoding::specialization::Specialization;

pub use crate::kernel::{Kernel, KernelStandIn, KERNEL_STAND_INS};
use crate::primitive_dispatch;
pub use crate::tuning::SceneArrays;
use crate::tuning::Tuning;
use crate::GpuError;

// `SOURCES` and `EMBEDDED`: every file under `shaders/`, listed by build.rs.
include!(concat!(env!("OUT_DIR"), "/shader_files.rs"));

/// The files `source` imports, as paths relative to `shaders/`: a name
/// without a folder is in `lib/`. A file that asks for generated dispatch
/// also imports the files of the kinds it calls, in the order of names as
/// import lines are written.
pub fn imports(source: &str) -> Vec<String> {
    imports_by_line(source).into_iter().map(|(_, file)| file).collect()
}

/// [`imports`], each with the number of the line that imports it (1-based).
fn imports_by_line(source: &str) -> Vec<(usize, String)> {
    let lines = || source.lines().enumerate().map(|(i, line)| (i + 1, line.trim()));
    let mut files: Vec<(usize, String)> = lines()
        .filter_map(|(n, line)| Some((n, line.strip_prefix("// import:")?)))
        .flat_map(|(n, names)| names.split_whitespace().map(move |name| (n, import_path(name))))
        .collect();
    let pieces: Vec<(usize, &str)> = lines().filter_map(|(n, line)| Some((n, line.strip_prefix(primitive_dispatch::MARKER)?.trim()))).collect();
    if !pieces.is_empty() {
        files.extend(pieces.into_iter().flat_map(|(n, piece)| primitive_dispatch::files(piece).into_iter().map(move |file| (n, file.to_string()))));
        files.sort_by(|a, b| a.1.cmp(&b.1));
        files.dedup_by(|a, b| a.1 == b.1);
    }
    files
}

/// The file an import names: a name without a folder is in `lib/`.
fn import_path(name: &str) -> String {
    if name.contains('/') { format!("{name}.wgsl") } else { format!("lib/{name}.wgsl") }
}

/// `source` with each line that asks for a generated piece replaced by it.
pub fn expand(source: &str) -> Result<String, String> {
    let text = |part: Part| match part {
        Part::Own(_, text) | Part::Generated(text) => text,
    };
    Ok(parts(source)?.into_iter().map(text).collect())
}

/// A run of a file's own lines (the number of the first, 1-based) or a
/// generated piece one of its lines asks for.
enum Part {
    Own(usize, String),
    Generated(String),
}

/// `source` cut at the lines that ask for generated pieces, each piece made;
/// an error names the line and the piece no one generates.
fn parts(source: &str) -> Result<Vec<Part>, String> {
    let mut parts = vec![Part::Own(1, String::new())];
    for (i, line) in source.lines().enumerate() {
        match line.trim().strip_prefix(primitive_dispatch::MARKER).map(str::trim) {
            Some(name) => {
                parts.push(Part::Generated(primitive_dispatch::piece(name).ok_or_else(|| format!("{}: no generated piece {name}", i + 1))?));
                parts.push(Part::Own(i + 2, String::new()));
            }
            None => {
                let Some(Part::Own(_, text)) = parts.last_mut() else { unreachable!("a piece is followed by the file's own lines") };
                text.push_str(line);
                text.push('\n');
            }
        }
    }
    Ok(parts)
}

/// Where the WGSL files come from.
#[derive(Debug, Clone)]
pub enum ShaderSource {
    Embedded,
    Dir(PathBuf),
}

/// A composed kernel: its source and where each file starts in it.
#[derive(Debug, Clone)]
pub struct Composed {
    pub source: String,
    /// (file name relative to `shaders/`, first line in `source`, that
    /// line's number in the file; all 1-based). A file with generated pieces
    /// is several parts, one before and one after each piece.
    pub files: Vec<(String, usize, usize)>,
}

/// How errors name the generated prelude.
const PRELUDE: &str = "the generated prelude (gpu_types.rs, specialization.rs, tuning.rs)";

/// How errors name a generated piece.
const DISPATCH: &str = "the generated dispatch (primitive_kinds.rs, primitive_dispatch.rs)";

impl Composed {
    /// Turns a line of the composed source into "file:line".
    pub fn locate(&self, line: usize) -> String {
        match self.files.iter().rev().find(|(_, start, _)| *start <= line) {
            Some((name, start, first)) if name == PRELUDE || name == DISPATCH => format!("{name}, line {}", line - start + first),
            Some((name, start, first)) => format!("shaders/{name}:{}", line - start + first),
            None => format!("line {line}"),
        }
    }

    /// Parses and validates with naga, naming the file and line of any error.
    pub fn validate(&self) -> Result<naga::Module, GpuError> {
        self.validate_with(naga::valid::Capabilities::all())
    }

    /// Parses and validates with naga for a device of `capabilities` (tests
    /// hold the kernels to WebGPU's), naming the file and line of any error.
    pub fn validate_with(&self, capabilities: naga::valid::Capabilities) -> Result<naga::Module, GpuError> {
        let module = naga::front::wgsl::parse_str(&self.source).map_err(|e| {
            let place = e.location(&self.source).map_or(String::new(), |l| self.locate(l.line_number as usize));
            GpuError::Shader(format!("{place}: {}", e.message()))
        })?;
        naga::valid::Validator::new(naga::valid::ValidationFlags::all(), capabilities)
            .validate(&module)
            .map_err(|e| {
                let place = e
                    .spans()
                    .next()
                    .map(|(span, _)| self.locate(span.location(&self.source).line_number as usize))
                    .unwrap_or_default();
                GpuError::Shader(format!("{place}: {}", e.as_inner()))
            })?;
        Ok(module)
    }
}

impl ShaderSource {
    /// The `shaders/` folder of this source tree, for hot reload.
    pub fn source_dir() -> PathBuf {
        Path::new(env!("CARGO_MANIFEST_DIR")).join("../../shaders")
    }

    fn read(&self, name: &str) -> Result<String, GpuError> {
        match self {
            ShaderSource::Embedded => EMBEDDED
                .iter()
                .find(|(n, _)| *n == name)
                .map(|(_, s)| s.to_string())
                .ok_or_else(|| GpuError::Shader(format!("shaders/{name}: no such shader file"))),
            ShaderSource::Dir(dir) => std::fs::read_to_string(dir.join(name))
                .map_err(|e| GpuError::Shader(format!("{}: {e}", dir.join(name).display()))),
        }
    }

    /// The kernel's source for scenes of `specialization` on a device that
    /// tunes it as `tuning` says: the prelude, then every file its imports reach.
    pub fn compose(&self, kernel: Kernel, specialization: Specialization, tuning: Tuning) -> Result<Composed, GpuError> {
        let mut order = Vec::new();
        self.visit(kernel.file(), kernel, tuning, &mut Vec::new(), &mut order)?;
        let mut source = glint_encoding::gpu_types::wgsl_prelude();
        source.push_str(&specialization.wgsl());
        source.push_str(&tuning.wgsl());
        let mut lines = source.lines().count();
        let mut starts = vec![(PRELUDE.to_string(), 1, 1)];
        for (name, text) in order {
            for part in parts(&text).map_err(|e| GpuError::Shader(format!("shaders/{name}:{e}")))? {
                let (start, text) = match part {
                    Part::Own(first, text) => ((name.clone(), lines + 1, first), text),
                    Part::Generated(text) => ((DISPATCH.to_string(), lines + 1, 1), text),
                };
                starts.push(start);
                lines += text.lines().count();
                source.push_str(&text);
            }
        }
        Ok(Composed { source, files: starts })
    }

    /// Appends `name`, or the file that `kernel` or else `tuning` puts in its
    /// place, to `order` after everything it imports (depth first); `path` is
    /// the chain of imports being followed, to report a cycle.
    fn visit(&self, name: &str, kernel: Kernel, tuning: Tuning, path: &mut Vec<String>, order: &mut Vec<(String, String)>) -> Result<(), GpuError> {
        let name = match kernel.file_for(name) {
            own if own != name => own,
            _ => tuning.file(name),
        };
        if order.iter().any(|(done, _)| done == name) {
            return Ok(());
        }
        if path.iter().any(|p| p == name) {
            return Err(GpuError::Shader(format!("shaders/{name}: imports itself through {}", path.join(" → "))));
        }
        let text = self.read(name)?;
        path.push(name.to_string());
        for (line, import) in imports_by_line(&text) {
            if !self.exists(&import) {
                return Err(GpuError::Shader(format!("shaders/{name}:{line}: imports {import}, which is no shader file")));
            }
            self.visit(&import, kernel, tuning, path, order)?;
        }
        path.pop();
        order.push((name.to_string(), text));
        Ok(())
    }

    fn exists(&self, name: &str) -> bool {
        match self {
            ShaderSource::Embedded => SOURCES.contains(&name),
            ShaderSource::Dir(dir) => dir.join(name).is_file(),
        }
    }
}

