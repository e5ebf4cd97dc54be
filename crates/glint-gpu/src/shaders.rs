//! WGSL composition. Each kernel is the generated prelude of constants shared
//! with the host (`gpu_types::wgsl_prelude`) followed by an ordered
//! concatenation of the one-concept files in `shaders/`; WGSL allows
//! module-scope declarations in any order, so the order only makes errors
//! easier to read. Errors are mapped back to the file and line they came from.
//!
//! The files are embedded at build time; `ShaderSource::from_dir` reads them from
//! disk instead (the viewer's hot reload).

use std::path::{Path, PathBuf};

use crate::GpuError;

/// Declares each kernel's file list and embeds every listed file, so a file
/// is named once.
macro_rules! kernels {
    ($($(#[$doc:meta])* $kernel:ident = [$($name:literal),* $(,)?];)*) => {
        $($(#[$doc])* pub const $kernel: &[&str] = &[$($name),*];)*
        const EMBEDDED: &[(&str, &str)] =
            &[$($(($name, include_str!(concat!("../../../shaders/", $name))),)*)*];
    };
}

kernels! {
    /// The files of the trace and primary kernels, in order.
    TRACE_FILES = [
        "types.wgsl",
        "bindings.wgsl",
        "camera.wgsl",
        "sample.wgsl",
        "ray_frame.wgsl",
        "sphere.wgsl",
        "triangle.wgsl",
        "polygon.wgsl",
        "cone.wgsl",
        "primitive.wgsl",
        "bvh.wgsl",
        "reflect.wgsl",
        "refract.wgsl",
        "shadow.wgsl",
        "shade.wgsl",
        "trace.wgsl",
        "primary.wgsl",
    ];
    /// The files of the resolve kernel (accumulated samples → display values).
    RESOLVE_FILES = ["resolve.wgsl"];
    /// The files of the viewer's present kernel: the resolve, written into a texture.
    PRESENT_FILES = ["resolve.wgsl", "present.wgsl"];
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
    /// (file name, first line in `source`, 1-based)
    pub files: Vec<(&'static str, usize)>,
}

/// How errors name the generated prelude.
const PRELUDE: &str = "the generated prelude (gpu_types.rs)";

impl Composed {
    /// Turns a line of the composed source into "file:line".
    pub fn locate(&self, line: usize) -> String {
        match self.files.iter().rev().find(|(_, start)| *start <= line) {
            Some((name, start)) if *name == PRELUDE => format!("{name}, line {}", line - start + 1),
            Some((name, start)) => format!("shaders/{name}:{}", line - start + 1),
            None => format!("line {line}"),
        }
    }

    /// Parses and validates with naga, naming the file and line of any error.
    pub fn validate(&self) -> Result<naga::Module, GpuError> {
        let module = naga::front::wgsl::parse_str(&self.source).map_err(|e| {
            let place = e.location(&self.source).map_or(String::new(), |l| self.locate(l.line_number as usize));
            GpuError::Shader(format!("{place}: {}", e.message()))
        })?;
        naga::valid::Validator::new(naga::valid::ValidationFlags::all(), naga::valid::Capabilities::all())
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

    fn read(&self, name: &'static str) -> Result<String, GpuError> {
        match self {
            ShaderSource::Embedded => Ok(EMBEDDED
                .iter()
                .find(|(n, _)| *n == name)
                .map(|(_, s)| s.to_string())
                .expect("every kernel file is embedded")),
            ShaderSource::Dir(dir) => std::fs::read_to_string(dir.join(name))
                .map_err(|e| GpuError::Shader(format!("{}: {e}", dir.join(name).display()))),
        }
    }

    pub fn compose(&self, files: &[&'static str]) -> Result<Composed, GpuError> {
        let mut source = glint_scene::gpu_types::wgsl_prelude();
        let mut starts = vec![(PRELUDE, 1)];
        for name in files {
            starts.push((*name, source.lines().count() + 1));
            source.push_str(&self.read(name)?);
            if !source.ends_with('\n') {
                source.push('\n');
            }
        }
        Ok(Composed { source, files: starts })
    }
}
