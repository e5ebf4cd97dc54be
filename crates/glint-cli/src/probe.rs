//! `glint probe`: one pixel's camera ray and its whole ray tree, as the kernels
//! traced it, with every term each ray adds to the pixel, so a student can
//! check a hand calculation against the lecture's trace(R).

use std::path::PathBuf;

use clap::Args;
use glint_encoding::gpu_types::{MISS, NO_RAY, PROBE_BACKFACE, PROBE_BLOCKED, PROBE_TOTAL_INTERNAL_REFLECTION, RAY_SHADOW};
use glint_gpu::probe::{kind_name, number_text as num, vec3_text as v3, Prober, RayTree, TreeText};
use glint_gpu::shaders::ShaderSource;
use glint_gpu::{Acceleration, Gpu, RenderOptions, Renderer};
use glint_scene::camera_frame::CameraFrame;
use glint_scene::MAX_DEPTH_LIMIT;
use glint_scene::{Projection, Scene};
use serde_json::json;

use crate::probe_observer::ObserverArgs;
use crate::{exit, Failure};

#[derive(Args)]
pub struct ProbeArgs {
    /// Scene file (.toml, .nff or .obj), or spd:NAME[:SIZE]
    #[arg(value_parser = crate::scene_arg::parse)]
    scene: PathBuf,
    /// Column of the pixel, from the left (0 is the first)
    x: u32,
    /// Row of the pixel, from the top (0 is the first)
    y: u32,
    /// Image width in pixels (default: the scene's)
    #[arg(long)]
    width: Option<u32>,
    /// Image height in pixels (default: the scene's)
    #[arg(long)]
    height: Option<u32>,
    /// Samples per pixel of the render: with more than 1 the first sample's ray is followed
    #[arg(long, default_value_t = 1, value_parser = clap::value_parser!(u32).range(1..=4096))]
    spp: u32,
    /// Seed of the sample jitter
    #[arg(long, default_value_t = 0)]
    seed: u32,
    /// Longest ray path, the eye ray counting as depth 1 (default: the scene's, else 5)
    #[arg(long, value_parser = clap::value_parser!(u32).range(1..=i64::from(MAX_DEPTH_LIMIT)))]
    max_depth: Option<u32>,
    /// Follow every reflection and refraction ray to the maximum depth
    #[arg(long)]
    no_cutoff: bool,
    #[command(flatten)]
    effects: crate::effects::EffectArgs,
    /// One JSON object on standard output
    #[arg(long)]
    json: bool,
    #[command(flatten)]
    observer: ObserverArgs,
}

pub fn run(args: &ProbeArgs) -> Result<(), Failure> {
    let mut scene = glint_scene::load(&args.scene).map_err(|e| Failure::new(exit::INPUT, e))?;
    // An animated scene at frame 0, the image `glint render` makes of it.
    scene.set_frame(0);
    if let Some(d) = args.max_depth {
        scene.render.max_depth = d;
    }
    if args.no_cutoff {
        scene.render.cutoff = 0.0;
    }
    args.effects.apply(&mut scene.render);
    let (width, height) = (args.width.unwrap_or(scene.width), args.height.unwrap_or(scene.height));
    if args.x >= width || args.y >= height {
        return Err(Failure::new(
            exit::USAGE,
            format!("pixel ({}, {}) is outside the {width} x {height} image: X is 0 to {}, Y is 0 to {}", args.x, args.y, width - 1, height - 1),
        ));
    }
    let frame = CameraFrame::new(&scene.camera, width, height).expect("a loaded scene's camera has a basis");
    let picture = args.observer.picture(&scene)?;
    let gpu = Gpu::new()?;
    let renderer = Renderer::new(gpu.device.clone(), gpu.queue.clone(), &ShaderSource::Embedded)?;
    let prober = Prober::new(&renderer, &ShaderSource::Embedded)?;
    let prepared = renderer.prepare(&scene, width, height, Acceleration::Bvh)?;
    let options = RenderOptions { spp: args.spp, seed: args.seed, ..RenderOptions::default() };
    let tree = prober.probe(&renderer, &prepared.buffers, args.x, args.y, &options)?;
    if let Some(picture) = &picture {
        picture.draw(&renderer, &scene, &frame, (args.x, args.y), &tree.rays)?;
    }
    let report = Report { scene: &scene, frame, width, height, x: args.x, y: args.y, tree: &tree };
    if args.json {
        println!("{}", report.json());
    } else {
        print!("{}", report.text());
    }
    Ok(())
}

struct Report<'a> {
    scene: &'a Scene,
    /// The camera frame printed, and drawn in the observer's picture.
    frame: CameraFrame,
    width: u32,
    height: u32,
    x: u32,
    y: u32,
    tree: &'a RayTree,
}

impl Report<'_> {
    fn text_of_tree(&self) -> TreeText<'_> {
        TreeText { scene: self.scene, tree: self.tree, first_number: 0 }
    }

    /// e, u, v, w, the view window and the screen point of the eye ray.
    fn camera_lines(&self) -> Vec<String> {
        let frame = &self.frame;
        let f = |v: glam::DVec3| v3(v.as_vec3().into());
        let mut lines = vec![
            format!("e = {}   (the eye)", f(frame.e)),
            format!("u = {}   (right)", f(frame.u)),
            format!("v = {}   (up)", f(frame.v)),
            format!("w = {}   (backwards: from look_at towards the eye)", f(frame.w)),
        ];
        let window = format!("l = {}, r = {}, b = {}, t = {}", num(frame.l as f32), num(frame.r as f32), num(frame.b as f32), num(frame.t as f32));
        let eye_ray = &self.tree.rays[0];
        let d = glam::Vec3::from(eye_ray.dir).as_dvec3();
        match frame.projection {
            Projection::Perspective { fov_y_degrees } => {
                lines.push(format!(
                    "view window at distance d = {}: {window} (vertical field of view {}°)",
                    num(frame.d as f32), num(fov_y_degrees)
                ));
                let depth = -d.dot(frame.w) / frame.d;
                let (us, vs) = (d.dot(frame.u) / depth, d.dot(frame.v) / depth);
                lines.push(format!("screen point s = (u_s, v_s) = ({}, {})", num(us as f32), num(vs as f32)));
                lines.push(format!("ray direction = normalize(-w + u_s·u + v_s·v) = {}", v3(eye_ray.dir)));
            }
            Projection::Orthographic { height } => {
                lines.push(format!("orthographic, view window {} high: {window}", num(height)));
                let o = glam::Vec3::from(eye_ray.origin).as_dvec3() - frame.e;
                lines.push(format!("screen point s = (u_s, v_s) = ({}, {})", num(o.dot(frame.u) as f32), num(o.dot(frame.v) as f32)));
                lines.push(format!("ray origin = e + u_s·u + v_s·v = {}, direction = -w", v3(eye_ray.origin)));
            }
        }
        lines
    }

    fn text(&self) -> String {
        let mut out = format!("pixel ({}, {}) of {} x {}\ncamera\n", self.x, self.y, self.width, self.height);
        for line in self.camera_lines() {
            out.push_str(&format!("  {line}\n"));
        }
        out.push_str(&format!("ray tree: the contributions add up to the pixel's linear colour {}\n", v3(self.tree.color)));
        for (id, ray) in self.tree.rays.iter().enumerate() {
            let indent = "  ".repeat(ray.depth as usize) + if ray.kind == RAY_SHADOW { "  " } else { "" };
            out.push_str(&format!("{indent}#{id} {}\n", self.text_of_tree().describe(ray).join(&format!("\n{indent}   "))));
        }
        if self.tree.truncated {
            out.push_str("(the tree has more rays than the probe records; the rest are left out)\n");
        }
        out
    }

    fn json(&self) -> serde_json::Value {
        let frame = &self.frame;
        let d3 = |v: glam::DVec3| [v.x, v.y, v.z];
        let rays: Vec<_> = self
            .tree
            .rays
            .iter()
            .enumerate()
            .map(|(id, r)| {
                let hit = r.object != NO_RAY && r.kind != RAY_SHADOW;
                json!({
                    "id": id,
                    "parent": (r.parent != NO_RAY).then_some(r.parent),
                    "kind": kind_name(r.kind),
                    "depth": r.depth,
                    "origin": r.origin,
                    "dir": r.dir,
                    "t": (r.t < MISS).then_some(r.t),
                    "object": hit.then_some(r.object),
                    "weight": r.weight,
                    "contribution": self.text_of_tree().contribution(r),
                    "point": hit.then_some(r.point),
                    "geometric_normal": hit.then_some(r.geometric),
                    "shading_normal": hit.then_some(r.shading),
                    "back_face": hit.then_some(r.flags & PROBE_BACKFACE != 0),
                    "ambient": hit.then_some(r.ambient),
                    "eta": hit.then_some(r.eta),
                    "total_internal_reflection": hit.then_some(r.flags & PROBE_TOTAL_INTERNAL_REFLECTION != 0),
                    "light": (r.kind == RAY_SHADOW).then_some(r.light),
                    "n_dot_l": (r.kind == RAY_SHADOW).then_some(r.n_dot_l),
                    "blocked": (r.kind == RAY_SHADOW).then_some(r.flags & PROBE_BLOCKED != 0),
                    "blocker": (r.blocker != NO_RAY).then_some(r.blocker),
                    "transmittance": (r.kind == RAY_SHADOW).then_some(r.transmittance),
                    "diffuse": (r.kind == RAY_SHADOW).then_some(r.diffuse),
                    "specular": (r.kind == RAY_SHADOW).then_some(r.specular),
                })
            })
            .collect();
        json!({
            "pixel": [self.x, self.y],
            "image": [self.width, self.height],
            "color": self.tree.color,
            "camera": {
                "e": frame.e.as_vec3().to_array(), "u": d3(frame.u), "v": d3(frame.v), "w": d3(frame.w),
                "l": frame.l, "r": frame.r, "b": frame.b, "t": frame.t, "d": frame.d,
            },
            "rays": rays,
            "truncated": self.tree.truncated,
        })
    }
}
