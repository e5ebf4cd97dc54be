//! `glint kernels --dump DIR`: the WGSL each kernel is given, one file per
//! kernel and tuning, for readers and for other WGSL compilers (a browser's
//! WebGPU among them). No GPU is needed.

use std::path::PathBuf;

use clap::Args;

use crate::Failure;

#[derive(Args)]
pub struct KernelsArgs {
    /// Write each kernel's WGSL into DIR (made if missing), with kernels.json
    /// listing their entry points and which need subgroup operations
    #[arg(long, value_name = "DIR")]
    dump: PathBuf,
}

pub fn run(args: &KernelsArgs) -> Result<(), Failure> {
    for path in glint_gpu::kernel_dump::dump(&args.dump)? {
        println!("{}", path.display());
    }
    Ok(())
}
