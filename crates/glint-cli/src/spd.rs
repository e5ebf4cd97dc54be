//! `glint spd`: write one of the Standard Procedural Databases as NFF.

use std::io::Write;
use std::path::PathBuf;

use clap::Args;

use crate::{exit, Failure};

#[derive(Args)]
pub struct SpdArgs {
    /// Database: balls, gears, mount, rings, teapot, tetra, tree, jacks, shells, lattice, sombrero, nurbtst
    #[arg(value_parser = database)]
    name: &'static glint_scene::spd::Database,
    /// Size (default: the database's classic benchmark size)
    #[arg(short, long)]
    size: Option<u32>,
    /// Output .nff file (default: standard output)
    #[arg(short, long)]
    output: Option<PathBuf>,
}

fn database(name: &str) -> Result<&'static glint_scene::spd::Database, String> {
    glint_scene::spd::database(name).map_err(|e| e.to_string())
}

pub fn run(args: &SpdArgs) -> Result<(), Failure> {
    let text = args.name.generate(args.size).map_err(|e| Failure::new(exit::USAGE, e))?;
    match &args.output {
        Some(path) => glint_gpu::write_atomically(path, text.as_bytes())
            .map_err(|e| Failure::new(exit::OUTPUT, format!("{}: {e}", path.display()))),
        None => std::io::stdout()
            .lock()
            .write_all(text.as_bytes())
            .map_err(|e| Failure::new(exit::OUTPUT, format!("standard output: {e}"))),
    }
}
