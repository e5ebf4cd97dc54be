//! The viewer's switches of the Whitted model on the command line, for
//! `glint render` and `glint probe`: leave out one kind of secondary ray, to
//! see what it adds, or what a tracer that forgot it renders.

use clap::Args;
use glint_scene::RenderSettings;

#[derive(Args, Debug, Clone, Copy)]
pub struct EffectArgs {
    /// Trace no shadow rays: every light reaches every point
    #[arg(long)]
    no_shadows: bool,
    /// Trace no reflected rays
    #[arg(long)]
    no_reflection: bool,
    /// Trace no refracted rays
    #[arg(long)]
    no_refraction: bool,
}

impl EffectArgs {
    /// Turns off what the switches say in the scene's `render` settings.
    pub fn apply(&self, render: &mut RenderSettings) {
        render.shadows &= !self.no_shadows;
        render.reflections &= !self.no_reflection;
        render.refractions &= !self.no_refraction;
    }
}
