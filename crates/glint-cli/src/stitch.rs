//! `glint stitch`: parts rendered with `--region` or `--shard` → the whole image.

use std::path::PathBuf;

use clap::Args;

use crate::{exit, Failure};

#[derive(Args)]
pub struct StitchArgs {
    /// The parts (.png, .ppm, .exr or .pfm, each with the PART.json that `glint render
    /// --region/--shard` writes beside it), in any order
    #[arg(required = true)]
    parts: Vec<PathBuf>,
    /// The whole image, in the parts' format
    #[arg(short, long)]
    output: PathBuf,
    /// No line saying what was written
    #[arg(short, long)]
    quiet: bool,
}

pub fn run(args: &StitchArgs) -> Result<(), Failure> {
    crate::render::check_output(&args.output)?;
    let (width, height) = glint_gpu::stitch::stitch(&args.parts, &args.output).map_err(|e| match glint_gpu::GpuError::from(e) {
        glint_gpu::GpuError::Stitch(m) => Failure::new(exit::INPUT, m),
        other => Failure::from(other),
    })?;
    if !args.quiet {
        eprintln!("glint: stitched {width}x{height} from {} parts -> {}", args.parts.len(), args.output.display());
    }
    Ok(())
}
