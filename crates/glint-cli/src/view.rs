//! `glint view`: the interactive viewer.

use std::path::{Path, PathBuf};

use clap::Args;

use crate::{exit, Failure};

/// Opened when no scene is named, if it exists.
const DEFAULT_SCENE: &str = "scenes/showcase.toml";

#[derive(Args)]
pub struct ViewArgs {
    /// Scene file (.toml, .nff or .obj), or spd:NAME[:SIZE]; default: scenes/showcase.toml when it exists
    #[arg(value_parser = crate::scene_arg::parse)]
    scene: Option<PathBuf>,
}

pub fn run(args: ViewArgs) -> Result<(), Failure> {
    let scene = args.scene.or_else(|| Path::new(DEFAULT_SCENE).is_file().then(|| DEFAULT_SCENE.into()));
    glint_viewer::run(scene).map_err(|e| Failure::new(exit::GPU, e))
}
