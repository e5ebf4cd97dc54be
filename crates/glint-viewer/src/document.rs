//! The scene being viewed: the file it comes from (watched, and reloaded when
//! it changes), its loading in the background, where it and its image are saved,
//! and the scene that loaded, as edited, with what the controls derive from it.

use std::path::{Path, PathBuf};

use glam::Vec3;
use glint_scene::{Camera, DepthCue, Light, Material, Projection, Scene};

use crate::one_line;
use crate::camera_control;
use crate::jobs::{Job, Jobs};
use crate::settings::SpecularChoice;
use crate::warm_up::WarmUp;
use crate::watch::Watch;

#[derive(Default)]
pub(crate) struct Document {
    /// The scene file, or the name of a built-in scene.
    pub path: Option<PathBuf>,
    /// The text of a built-in scene, read instead of `path`.
    built_in: Option<&'static str>,
    /// Watches the scene file; a built-in scene never changes.
    watch: Option<Watch>,
    /// Counts loads, so a load overtaken by a newer one is dropped.
    generation: u64,
    pub loading: bool,
    /// The Scene section's file field.
    pub open_path: String,
    /// Where "Save image" writes.
    pub screenshot_path: String,
    /// Where "Save scene as" writes.
    pub save_path: String,
    /// The last scene that loaded.
    pub loaded: Option<LoadedScene>,
    /// Takes the first scene loaded.
    warm_up: Option<WarmUp>,
}

impl Document {
    pub fn new(warm_up: WarmUp) -> Self {
        Self { warm_up: Some(warm_up), ..Self::default() }
    }

    pub fn is_watched(&self) -> bool {
        self.watch.is_some()
    }

    /// True once after the scene file changed.
    pub fn changed(&mut self) -> bool {
        self.watch.as_mut().is_some_and(Watch::changed)
    }

    /// Opens the scene at `path`, keeping the current one until it has loaded.
    pub fn open(&mut self, path: PathBuf, jobs: &Jobs<Job>) {
        self.watch = Some(Watch::new(vec![path.clone()]));
        self.open_path = path.display().to_string();
        self.path = Some(path);
        self.built_in = None;
        self.start_load(false, jobs);
    }

    /// Opens a TOML scene built into the program, called `name`.
    pub fn open_built_in(&mut self, name: PathBuf, text: &'static str, jobs: &Jobs<Job>) {
        self.watch = None;
        self.open_path = String::new();
        self.path = Some(name);
        self.built_in = Some(text);
        self.start_load(false, jobs);
    }

    /// Loads the scene in the background; a `reload` keeps the user's view.
    pub fn start_load(&mut self, reload: bool, jobs: &Jobs<Job>) {
        let Some(path) = self.path.clone() else { return };
        self.generation += 1;
        self.loading = true;
        let generation = self.generation;
        let text = self.built_in;
        let warm_up = self.warm_up.take();
        jobs.spawn("load", move || {
            let result = match text {
                Some(text) => glint_scene::toml_scene::parse(text, &path),
                None => glint_scene::load(&path),
            };
            if let (Ok(scene), Some(warm_up)) = (&result, warm_up) {
                warm_up.scene(scene);
            }
            Job::Loaded { generation, path, reload, result }
        });
    }

    /// Takes a finished load of `path`. The latest load's scene becomes the one
    /// viewed and is returned; its error goes to `error`, and the last good scene stays.
    pub fn finish_load(
        &mut self,
        generation: u64,
        path: &Path,
        reload: bool,
        result: Result<Scene, glint_scene::LoadError>,
        error: &mut Option<String>,
    ) -> Option<&LoadedScene> {
        if generation != self.generation {
            return None;
        }
        self.loading = false;
        let scene = match result {
            Ok(scene) => scene,
            Err(e) => {
                *error = Some(one_line(e));
                return None;
            }
        };
        *error = None;
        let mut loaded = LoadedScene::new(scene, generation);
        if let (true, Some(old)) = (reload, &self.loaded) {
            // Keep the user's view unless the file's camera changed.
            if old.file_camera == loaded.scene.camera {
                loaded.scene.camera = old.scene.camera;
                loaded.fov = old.fov;
            }
        }
        if !reload {
            // Saved files go beside the scene by default.
            let stem = path.file_stem().map_or("scene".into(), |s| s.to_string_lossy().into_owned());
            let dir = path.parent().unwrap_or(Path::new(""));
            self.screenshot_path = dir.join(format!("{stem}-view.png")).display().to_string();
            self.save_path = dir.join(format!("{stem}-view.toml")).display().to_string();
        }
        Some(self.loaded.insert(loaded))
    }
}

/// A loaded scene, as edited.
pub(crate) struct LoadedScene {
    pub scene: Scene,
    /// The camera the file gave, for "reset".
    pub file_camera: Camera,
    /// The load it came from, so work for an older scene is recognised.
    pub generation: u64,
    pub bounds: (Vec3, Vec3),
    /// Half the diagonal of the bounds: how large the scene is.
    pub radius: f32,
    /// The field of view to return to from an orthographic camera.
    pub fov: f32,
    /// The frame of the scene's animation shown.
    pub frame: u32,
}

impl LoadedScene {
    fn new(mut scene: Scene, generation: u64) -> Self {
        scene.set_frame(0);
        let bounds = glint_observer::object_bounds(&scene);
        let radius = if bounds.0.cmple(bounds.1).all() { (bounds.1 - bounds.0).length() / 2.0 } else { 1.0 };
        let fov = match scene.camera.projection {
            Projection::Perspective { fov_y_degrees } => fov_y_degrees,
            Projection::Orthographic { .. } => 40.0,
        };
        Self { file_camera: scene.camera, scene, generation, bounds, radius: radius.max(1e-3), fov, frame: 0 }
    }

    /// About the distance from the eye to the far side of the scene.
    pub fn depth_extent(&self) -> f32 {
        let (lo, hi) = self.bounds;
        let centre = if lo.cmple(hi).all() { (lo + hi) / 2.0 } else { self.scene.camera.look_at };
        (self.scene.camera.eye - centre).length() + self.radius
    }

    pub fn aspect(&self) -> f32 {
        self.scene.width as f32 / self.scene.height as f32
    }

    pub fn reset_camera(&mut self) {
        // An animated camera returns to where the frame shown puts it.
        self.scene.camera = self.scene.animation.as_ref().and_then(|a| a.camera_at(self.frame)).unwrap_or(self.file_camera);
    }

    pub fn frame_all(&mut self) {
        let aspect = self.aspect();
        camera_control::frame_all(&mut self.scene.camera, self.bounds.0, self.bounds.1, aspect);
    }

    /// Writes the scene as edited, with `specular` applied to its materials, to `path` as TOML.
    pub fn save(&self, path: &Path, specular: SpecularChoice) -> Result<(), String> {
        self.toml(specular)
            .and_then(|text| glint_gpu::write_atomically(path, text.as_bytes()).map_err(|e| one_line(format!("{}: {e}", path.display()))))
    }

    /// The scene as edited, with `specular` applied to its materials, as TOML.
    pub fn toml(&self, specular: SpecularChoice) -> Result<String, String> {
        let mut scene = self.scene.clone();
        for m in &mut scene.materials {
            *m = specular.apply(m);
        }
        glint_scene::toml_write::to_string(&scene).map_err(one_line)
    }

    /// The parts of the scene the side panel edits, to notice a change.
    pub fn edits(&self) -> Edits {
        let s = &self.scene;
        Edits {
            camera: s.camera,
            background: s.background,
            ambient: s.ambient,
            lights: s.lights.clone(),
            materials: s.materials.clone(),
            depth_cue: s.depth_cue,
            render: s.render,
        }
    }
}

/// The parts of a scene the side panel edits.
#[derive(Clone, PartialEq)]
pub(crate) struct Edits {
    camera: Camera,
    background: Vec3,
    ambient: Vec3,
    lights: Vec<Light>,
    materials: Vec<Material>,
    depth_cue: Option<DepthCue>,
    render: glint_scene::RenderSettings,
}
