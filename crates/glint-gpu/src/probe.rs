//! One pixel's ray tree, as the kernels trace it: the probe kernel runs the
//! trace kernel's own ray-tree and shading code over one pixel and records
//! every ray and every term it adds (shaders/kernels/probe.wgsl, whose notes shaders/kernels/probe_notes.wgsl records).

use bytemuck::Zeroable;
use glint_encoding::gpu_types::{
    DispatchParams, ProbeHeader, ProbeRay, View, NO_RAY, PROBE_BACKFACE, PROBE_BLOCKED, PROBE_CAPACITY, PROBE_SHADOW_TRACED,
    PROBE_TOTAL_INTERNAL_REFLECTION, RAY_EYE, RAY_REFLECT, RAY_REFRACT, RAY_SHADOW,
};
use glint_encoding::specialization::Specialization;
use glint_scene::Scene;

use crate::error_scope::ErrorScope;
use crate::pipelines::create_pipeline;
use crate::shaders::{Kernel, ShaderSource};
use crate::{GpuError, Readback, RenderOptions, Renderer, SceneBuffers};

/// A pixel's ray tree: the rays in the order the kernel traced them (a ray's
/// parent always comes before it) and the colour the tree adds up to.
#[derive(Debug, Clone, PartialEq)]
pub struct RayTree {
    pub color: [f32; 3],
    pub rays: Vec<ProbeRay>,
    /// The tree had more than `PROBE_CAPACITY` rays; the rest are missing.
    pub truncated: bool,
}

impl RayTree {
    /// The linear colour `ray` adds to the pixel: its weight times what it
    /// found (the background on a miss, the ambient term and the depth cue at
    /// a hit); a shadow ray adds its light's diffuse and specular terms,
    /// weighted like the ray that cast it. The contributions of all rays sum
    /// to the pixel's colour.
    pub fn contribution(&self, ray: &ProbeRay, background: [f32; 3], depth_cue_color: Option<[f32; 3]>) -> [f32; 3] {
        let scaled = |w: [f32; 3], s: f32, v: [f32; 3]| [0, 1, 2].map(|c| w[c] * s * v[c]);
        if ray.kind == RAY_SHADOW {
            let parent = &self.rays[ray.parent as usize];
            let terms = [0, 1, 2].map(|c| ray.diffuse[c] + ray.specular[c]);
            return scaled(parent.weight, parent.cue_scale, terms);
        }
        if ray.object == NO_RAY {
            return scaled(ray.weight, 1.0, background);
        }
        let local = scaled(ray.weight, ray.cue_scale, ray.ambient);
        let cue = depth_cue_color.map_or([0.0; 3], |c| scaled(ray.weight, 1.0 - ray.cue_scale, c));
        [0, 1, 2].map(|c| local[c] + cue[c])
    }
}

/// The probe kernel, compiled.
pub struct Prober {
    pipeline: wgpu::ComputePipeline,
    layout: wgpu::BindGroupLayout,
}

/// Bytes of the probe buffer: its head and room for `PROBE_CAPACITY` rays.
const PROBE_BYTES: u64 = (size_of::<ProbeHeader>() + PROBE_CAPACITY as usize * size_of::<ProbeRay>()) as u64;

impl Prober {
    pub fn new(renderer: &Renderer, source: &ShaderSource) -> Result<Self, GpuError> {
        let device = &renderer.device;
        let layout = device.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
            label: Some("probe"),
            entries: &[wgpu::BindGroupLayoutEntry {
                binding: 0,
                visibility: wgpu::ShaderStages::COMPUTE,
                ty: wgpu::BindingType::Buffer {
                    ty: wgpu::BufferBindingType::Storage { read_only: false },
                    has_dynamic_offset: false,
                    min_binding_size: None,
                },
                count: None,
            }],
        });
        let pipeline_layout = device.create_pipeline_layout(&wgpu::PipelineLayoutDescriptor {
            label: Some("probe"),
            bind_group_layouts: &[Some(&renderer.scene_layout), Some(&layout)],
            immediate_size: 0,
        });
        // Compiled for every kind: for the kinds a scene holds it runs the same code
        // as the trace kernel specialised to that scene.
        let pipeline = create_pipeline(device, source, Kernel::Probe, (Specialization::ALL, renderer.plain_tuning()), Some(&pipeline_layout))?;
        Ok(Self { pipeline, layout })
    }

    /// The ray tree of pixel (`x`, `y`) (from the top-left corner) as the
    /// render with `options` traces it: through the pixel centre, or with
    /// `spp` > 1 through its first sample's position.
    pub fn probe(&self, renderer: &Renderer, scene: &SceneBuffers, x: u32, y: u32, options: &RenderOptions) -> Result<RayTree, GpuError> {
        let scope = ErrorScope::push(&renderer.device);
        let tree = self.probe_later(renderer, scene, x, y, options).and_then(|tree| tree.wait(&renderer.device));
        if let Some(e) = scope.pop() {
            return Err(GpuError::Runtime(e.to_string()));
        }
        tree
    }

    /// [`Prober::probe`] without waiting: the tree arrives in the read-back
    /// (how a browser probes).
    pub fn probe_later(&self, renderer: &Renderer, scene: &SceneBuffers, x: u32, y: u32, options: &RenderOptions) -> Result<Readback<RayTree>, GpuError> {
        if x >= scene.width || y >= scene.height {
            return Err(GpuError::Output(format!(
                "pixel ({x}, {y}) is outside the {} x {} image",
                scene.width, scene.height
            )));
        }
        let device = &renderer.device;
        let buffer = device.create_buffer(&wgpu::BufferDescriptor {
            label: Some("probe"),
            size: PROBE_BYTES,
            usage: wgpu::BufferUsages::STORAGE | wgpu::BufferUsages::COPY_SRC,
            mapped_at_creation: false,
        });
        let bind = device.create_bind_group(&wgpu::BindGroupDescriptor {
            label: Some("probe"),
            layout: &self.layout,
            entries: &[wgpu::BindGroupEntry { binding: 0, resource: buffer.as_entire_binding() }],
        });
        let region = DispatchParams {
            origin: [x, y],
            end: [x + 1, y + 1],
            seed: options.seed,
            sample_count: options.spp,
            pixel_filter: options.filter as u32,
            view: View::Shaded as u32,
            ..Zeroable::zeroed()
        };
        renderer.queue.write_buffer(&scene.dispatch, 0, bytemuck::bytes_of(&region));
        let readback = renderer.readback_buffer(PROBE_BYTES);
        let mut encoder = device.create_command_encoder(&Default::default());
        {
            let mut pass = encoder.begin_compute_pass(&Default::default());
            pass.set_pipeline(&self.pipeline);
            pass.set_bind_group(0, &scene.scene_bind, &[]);
            pass.set_bind_group(1, &bind, &[]);
            pass.dispatch_workgroups(1, 1, 1);
        }
        encoder.copy_buffer_to_buffer(&buffer, 0, &readback, 0, PROBE_BYTES);
        renderer.queue.submit([encoder.finish()]);
        Ok(Readback::start(readback, |bytes| {
            let (head, rest) = bytes.split_at(size_of::<ProbeHeader>());
            let header: ProbeHeader = bytemuck::pod_read_unaligned(head);
            let count = header.count.min(PROBE_CAPACITY) as usize;
            let rays = rest.chunks_exact(size_of::<ProbeRay>()).take(count).map(bytemuck::pod_read_unaligned).collect();
            Ok(RayTree { color: header.color, rays, truncated: header.truncated != 0 })
        }))
    }
}

/// A ray tree in words, as `glint probe` prints it and the viewer's inspector
/// shows it: what each ray is, hits and adds, with the scene's names.
pub struct TreeText<'a> {
    pub scene: &'a Scene,
    pub tree: &'a RayTree,
    /// The number of the first object and light: 0 as `--json` counts, 1 as
    /// the viewer's panels count.
    pub first_number: usize,
}

/// A vector as the lecture writes it, to five decimals without trailing zeros.
pub fn vec3_text(v: [f32; 3]) -> String {
    format!("({}, {}, {})", number_text(v[0]), number_text(v[1]), number_text(v[2]))
}

/// A number to five decimals without trailing zeros (and no "-0").
pub fn number_text(v: f32) -> String {
    let s = format!("{v:.5}");
    let s = s.trim_end_matches('0').trim_end_matches('.');
    if s == "-0" { "0".into() } else { s.into() }
}

pub fn kind_name(kind: u32) -> &'static str {
    match kind {
        RAY_EYE => "eye",
        RAY_REFLECT => "reflect",
        RAY_REFRACT => "refract",
        _ => "shadow",
    }
}

impl TreeText<'_> {
    /// The linear colour `ray` adds to the pixel ([`RayTree::contribution`]
    /// with the scene's background and depth cue).
    pub fn contribution(&self, ray: &ProbeRay) -> [f32; 3] {
        let cue = self.scene.depth_cue.map(|d| d.color.into());
        self.tree.contribution(ray, self.scene.background.into(), cue)
    }

    /// The scene's index of the light a shadow ray went to: the kernels see
    /// only the lights that are on, in scene order.
    pub fn scene_light(&self, ray: &ProbeRay) -> Option<usize> {
        glint_encoding::gpu_types::shadow_ray_light(self.scene, ray)
    }

    /// "object N (shape, material "name")".
    pub fn object(&self, index: u32) -> String {
        let number = index as usize + self.first_number;
        let Some(object) = self.scene.objects.get(index as usize) else { return format!("object {number}") };
        let shape = match object.shapes.as_slice() {
            [shape] => shape.name().to_string(),
            shapes => format!("mesh of {} primitives", shapes.len()),
        };
        let material = self.scene.materials.get(object.material).map_or("?", |m| m.name.as_str());
        format!("object {number} ({shape}, material \"{material}\")")
    }

    /// A shadow ray blocked, in opaque shadow mode, by the transmissive
    /// object its ray hit: from inside glass the light is always blocked,
    /// which puzzles when the glass looks clear.
    fn blocked_by_its_own_glass(&self, ray: &ProbeRay) -> bool {
        let Some(parent) = self.tree.rays.get(ray.parent as usize) else { return false };
        let transmissive = self.scene.materials.get(parent.material as usize).is_some_and(|m| m.is_transmissive());
        ray.flags & PROBE_BLOCKED != 0
            && ray.blocker == parent.object
            && transmissive
            && self.scene.render.shadow_mode == glint_scene::ShadowMode::Opaque
    }

    /// What `ray` is, hit and added, a line per fact; the first says which ray it is.
    pub fn describe(&self, ray: &ProbeRay) -> Vec<String> {
        let (v3, num) = (vec3_text, number_text);
        let contribution = v3(self.contribution(ray));
        if ray.kind == RAY_SHADOW {
            let light = self.scene_light(ray).unwrap_or(ray.light as usize) + self.first_number;
            let state = if ray.flags & PROBE_SHADOW_TRACED == 0 {
                "shadows off: not traced".to_string()
            } else if ray.flags & PROBE_BLOCKED != 0 {
                format!("blocked by {}", self.object(ray.blocker))
            } else if ray.transmittance != [1.0; 3] {
                format!("let through, tinted S = {}", v3(ray.transmittance))
            } else {
                "reaches the light (S = 1)".to_string()
            };
            let mut lines = vec![
                format!("shadow ray to light {light}, from {} along {}", v3(ray.origin), v3(ray.dir)),
                format!("N·L = {}, distance {}, {state}", num(ray.n_dot_l), num(ray.distance)),
                format!("diffuse {}, specular {}, contributes {contribution}", v3(ray.diffuse), v3(ray.specular)),
            ];
            if self.blocked_by_its_own_glass(ray) {
                lines.push(
                    "the glass it leaves blocks it: shadows are opaque; with shadow_mode = \"tinted\" in [render], light passes through glass, tinted by its transmit".into(),
                );
            }
            return lines;
        }
        let mut lines = vec![format!(
            "{} ray, depth {}, weight {}, from {} along {}",
            kind_name(ray.kind),
            ray.depth,
            v3(ray.weight),
            v3(ray.origin),
            v3(ray.dir)
        )];
        if ray.object == NO_RAY {
            lines.push(format!("misses everything: the background, contributes {contribution}"));
            return lines;
        }
        let side = if ray.flags & PROBE_BACKFACE != 0 { "back face (from inside)" } else { "front face" };
        lines.push(format!("hits {} at t = {}, point {}, {side}", self.object(ray.object), num(ray.t), v3(ray.point)));
        lines.push(format!("geometric normal {}, shading normal {}", v3(ray.geometric), v3(ray.shading)));
        let mut local = format!("ambient {}", v3(ray.ambient));
        if self.scene.depth_cue.is_some() {
            local.push_str(&format!(", depth cue s_o = {}", num(ray.cue_scale)));
        }
        lines.push(format!("{local}, contributes {contribution} (its lights below)"));
        if ray.flags & PROBE_TOTAL_INTERNAL_REFLECTION != 0 {
            lines.push(format!("η = {}: total internal reflection, the transmitted share is reflected", num(ray.eta)));
        } else if self.scene.materials.get(ray.material as usize).is_some_and(|m| m.is_transmissive()) {
            lines.push(format!("refracts with η = n1/n2 = {}", num(ray.eta)));
        }
        lines
    }
}
