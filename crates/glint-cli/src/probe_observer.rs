//! `glint probe --observer EYE LOOK_AT -o tree.png`: the probed pixel's ray
//! tree seen from outside. The GPU renders the scene from the observer and the
//! camera frame, the view window and the tree are painted over it.

use std::path::PathBuf;

use clap::Args;
use glam::Vec3;
use glint_encoding::gpu_types::ProbeRay;
use glint_gpu::{Acceleration, RenderOptions, Renderer};
use glint_observer::{Observer, Overlay, OverlayOptions, ProbedPixel, GRID_CELL_PIXELS};
use glint_scene::camera_frame::CameraFrame;
use glint_scene::{Camera, Projection, Scene, MAX_DEPTH_LIMIT};

use crate::paint::paint_overlay;
use crate::{exit, Failure};

#[derive(Args)]
pub struct ObserverArgs {
    /// Draw the camera frame, the view window and the ray tree as seen by an
    /// observer at EYE looking at LOOK_AT (each x,y,z) into the PNG named by -o
    #[arg(long, num_args = 2, value_names = ["EYE", "LOOK_AT"], value_parser = parse_point, requires = "output", allow_hyphen_values = true)]
    observer: Option<Vec<Vec3>>,
    /// The observer's vertical field of view, in degrees
    #[arg(long, default_value_t = 45.0, requires = "observer")]
    observer_fov: f32,
    /// The observer picture's width in pixels
    #[arg(long, default_value_t = 640, requires = "observer", value_parser = clap::value_parser!(u32).range(16..=8192))]
    observer_width: u32,
    /// The observer picture's height in pixels
    #[arg(long, default_value_t = 480, requires = "observer", value_parser = clap::value_parser!(u32).range(16..=8192))]
    observer_height: u32,
    /// Where the observer's picture goes (.png)
    #[arg(short, long, requires = "observer")]
    output: Option<PathBuf>,
}

/// A point given as x,y,z.
fn parse_point(text: &str) -> Result<Vec3, String> {
    let numbers: Vec<f32> = text.split(',').map(|n| n.trim().parse::<f32>()).collect::<Result<_, _>>().map_err(|_| bad_point(text))?;
    match numbers[..] {
        [x, y, z] if numbers.iter().all(|n| n.is_finite()) => Ok(Vec3::new(x, y, z)),
        _ => Err(bad_point(text)),
    }
}

fn bad_point(text: &str) -> String {
    format!("`{text}` is not a point: give three numbers x,y,z, such as 3,2,5")
}

/// The observer and where its picture goes, checked before any GPU work.
pub struct ObserverPicture {
    observer: Observer,
    output: PathBuf,
}

impl ObserverArgs {
    /// `None` without `--observer`; an error for an observer that cannot see
    /// (its eye on the point it looks at, a field of view out of range) or a
    /// picture that cannot be written.
    pub fn picture(&self, scene: &Scene) -> Result<Option<ObserverPicture>, Failure> {
        let (Some(points), Some(output)) = (&self.observer, &self.output) else { return Ok(None) };
        let (eye, look_at) = (points[0], points[1]);
        if !(1.0..=179.0).contains(&self.observer_fov) {
            return Err(Failure::new(exit::USAGE, format!("--observer-fov {}: give a field of view from 1 to 179 degrees", self.observer_fov)));
        }
        if !output.extension().is_some_and(|e| e.eq_ignore_ascii_case("png")) {
            return Err(Failure::new(exit::USAGE, format!("{}: the observer's picture is a PNG: name it NAME.png", output.display())));
        }
        crate::render::check_output(output)?;
        let projection = Projection::Perspective { fov_y_degrees: self.observer_fov };
        // The scene's up, unless the observer looks straight along it.
        let camera = [scene.camera.up, Vec3::Y, Vec3::Z]
            .into_iter()
            .map(|up| Camera { eye, look_at, up, projection })
            .find(|c| c.basis().is_some())
            .ok_or_else(|| Failure::new(exit::USAGE, format!("--observer: the eye {eye} is the point it looks at; give two different points")))?;
        let observer = Observer { camera, width: self.observer_width, height: self.observer_height };
        Ok(Some(ObserverPicture { observer, output: output.clone() }))
    }
}

impl ObserverPicture {
    /// Renders `scene` from the observer, paints the frame of `frame` and the
    /// tree probed at `pixel` over it, and writes the PNG (complete, or not at all).
    pub fn draw(&self, renderer: &Renderer, scene: &Scene, frame: &CameraFrame, pixel: (u32, u32), rays: &[ProbeRay]) -> Result<(), Failure> {
        let observer = &self.observer;
        let mut seen = scene.clone();
        seen.camera = observer.camera;
        let prepared = renderer.prepare(&seen, observer.width, observer.height, Acceleration::Bvh)?;
        let (render, _) = renderer.render(&prepared.buffers, &RenderOptions::default(), &mut |_, _| {})?;
        let mut image = render.to_rgb8();
        let bounds = glint_observer::object_bounds(scene);
        let options = OverlayOptions { max_depth: MAX_DEPTH_LIMIT, grid: observer.cell_size(frame) >= GRID_CELL_PIXELS };
        let overlay = Overlay::new(scene, frame, bounds, &[ProbedPixel { pixel, rays }], options);
        paint_overlay(&mut image, &overlay, observer);
        let mut png = Vec::new();
        image
            .write_to(&mut std::io::Cursor::new(&mut png), image::ImageFormat::Png)
            .map_err(|e| Failure::new(exit::OUTPUT, format!("{}: {e}", self.output.display())))?;
        glint_gpu::write_atomically(&self.output, &png).map_err(|e| Failure::new(exit::OUTPUT, format!("{}: cannot write: {e}", self.output.display())))
    }
}
