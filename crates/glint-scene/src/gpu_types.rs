//! The plain arrays the WGSL kernels read. Every struct here has a twin of the
//! same name in shaders/types.wgsl; a naga test checks sizes and offsets agree.

use bytemuck::{Pod, Zeroable};
use glam::Vec3;

use crate::gpu_bvh::{GpuBvh, GpuGrid, GpuNode};
use crate::shape::polygon_normal;
use crate::{Attenuation, LightKind, Projection, Scene, ShadowMode, Shape, SpecularModel};

pub const PROJECTION_PERSPECTIVE: u32 = 0;
pub const PROJECTION_ORTHOGRAPHIC: u32 = 1;

pub const PRIM_SPHERE: u32 = 0;
pub const PRIM_TRIANGLE: u32 = 1;
pub const PRIM_POLYGON: u32 = 2;
pub const PRIM_CONE: u32 = 3;

pub const LIGHT_POINT: u32 = 0;
pub const LIGHT_DIRECTIONAL: u32 = 1;

pub const ATTENUATION_NONE: u32 = 0;
pub const ATTENUATION_INVERSE_SQUARE: u32 = 1;
pub const ATTENUATION_POLYNOMIAL: u32 = 2;

pub const MATERIAL_BLINN: u32 = 1;
pub const MATERIAL_METALLIC: u32 = 2;
pub const MATERIAL_FRESNEL: u32 = 4;

pub const FLAG_SHADOWS: u32 = 1;
pub const FLAG_TINTED_SHADOWS: u32 = 2;
pub const FLAG_REFLECTIONS: u32 = 4;
pub const FLAG_REFRACTIONS: u32 = 8;
pub const FLAG_DEPTH_CUE: u32 = 16;

/// What the trace kernel writes per pixel; mirrored by the VIEW_ constants in
/// shaders/types.wgsl.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
#[repr(u32)]
pub enum View {
    /// The full Whitted render.
    #[default]
    Shaded = 0,
    /// Unit geometric normal turned towards the viewer; 0 on a miss.
    Normal = 1,
    /// Distance along the unit primary ray; `MISS_DEPTH` on a miss.
    Depth = 2,
    /// The diffuse colour O_d of the material hit; 0 on a miss.
    Albedo = 3,
    /// Direct diffuse light only: Σ k_d·O_d·I_l·max(0, N·L)·V/d².
    Diffuse = 4,
    /// Object index; −1 on a miss.
    Id = 5,
    /// BVH nodes visited by the primary ray.
    Heatmap = 6,
}

impl View {
    /// Views computed from the primary ray alone, through the pixel centre.
    pub fn is_primary_only(self) -> bool {
        self != View::Shaded
    }
}

/// The depth the kernel reports for a ray that hits nothing (WGSL's MISS).
pub const MISS_DEPTH: f32 = 3.4e38;

/// How samples are spread over and around their pixel.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
#[repr(u32)]
pub enum Filter {
    /// Uniform within the pixel.
    #[default]
    Box = 0,
    /// Tent-distributed over two pixels' width around the centre.
    Tent = 1,
}

#[repr(C)]
#[derive(Debug, Clone, Copy, PartialEq, Pod, Zeroable)]
pub struct GpuCamera {
    pub eye: [f32; 3],
    pub projection: u32,
    pub u: [f32; 3],
    /// r: half width of the view window (at distance 1 for perspective).
    pub half_width: f32,
    pub v: [f32; 3],
    /// t: half height of the view window.
    pub half_height: f32,
    pub w: [f32; 3],
    pub _pad: f32,
}

/// Per-frame settings, one uniform buffer.
#[repr(C)]
#[derive(Debug, Clone, Copy, PartialEq, Pod, Zeroable)]
pub struct Globals {
    pub camera: GpuCamera,
    pub background: [f32; 3],
    pub width: u32,
    pub ambient: [f32; 3],
    pub height: u32,
    pub depth_cue_color: [f32; 3],
    pub light_count: u32,
    /// near, far, near_scale, far_scale
    pub depth_cue: [f32; 4],
    pub max_depth: u32,
    pub cutoff: f32,
    pub flags: u32,
    pub view: u32,
    /// Top-left pixel of the tile this dispatch covers.
    pub tile_origin: [u32; 2],
    pub sample_index: u32,
    pub seed: u32,
    /// Samples per pixel of the render (1: the pixel centre; 0: open-ended).
    pub sample_count: u32,
    pub pixel_filter: u32,
    /// The last row (exclusive) of the band a dispatch covers.
    pub row_end: u32,
    /// The BVH record traversal starts from (`GpuScene::bvh_root`).
    pub bvh_root: u32,
}

#[repr(C)]
#[derive(Debug, Clone, Copy, PartialEq, Pod, Zeroable)]
pub struct GpuLight {
    /// Position of a point light, or travel direction of a directional one.
    pub position: [f32; 3],
    pub kind: u32,
    /// I_l: colour × intensity.
    pub radiance: [f32; 3],
    pub attenuation: u32,
    /// c1, c2, c3 of polynomial attenuation.
    pub coefficients: [f32; 4],
}

#[repr(C)]
#[derive(Debug, Clone, Copy, PartialEq, Pod, Zeroable)]
pub struct GpuMaterial {
    pub color: [f32; 3],
    pub ka: f32,
    pub specular_color: [f32; 3],
    pub kd: f32,
    pub reflect: [f32; 3],
    pub ks: f32,
    pub transmit: [f32; 3],
    pub shininess: f32,
    pub f0: [f32; 3],
    pub ior: f32,
    pub flags: u32,
    pub _pad0: u32,
    pub _pad1: u32,
    pub _pad2: u32,
}

/// One primitive, 64 bytes; what `a`, `b`, `c` hold depends on the kind:
/// sphere a = (centre, radius); triangle a, b, c = vertices, `first` = index of
/// its three vertex normals when `count` = 3; polygon a = (unit normal, n·v0),
/// vertices[first .. first + count]; cone a = (base, base radius), b = (apex, apex radius).
#[repr(C)]
#[derive(Debug, Clone, Copy, PartialEq, Pod, Zeroable)]
pub struct GpuPrim {
    pub a: [f32; 4],
    pub b: [f32; 4],
    pub c: [f32; 4],
    /// kind in the low 8 bits, material index above.
    pub kind_material: u32,
    pub object: u32,
    pub first: u32,
    pub count: u32,
}

/// Everything the kernels read, ready to upload. Arrays are never empty (wgpu
/// cannot bind an empty buffer), so an empty list holds one unused element.
#[derive(Debug, Clone)]
pub struct GpuScene {
    pub prims: Vec<GpuPrim>,
    pub nodes: Vec<GpuNode>,
    pub grids: Vec<GpuGrid>,
    /// Where BVH traversal starts (`Globals::bvh_root`).
    pub bvh_root: u32,
    pub materials: Vec<GpuMaterial>,
    pub lights: Vec<GpuLight>,
    /// Polygon vertices and triangle vertex normals, xyz + unused w.
    pub points: Vec<[f32; 4]>,
    pub light_count: u32,
}

impl GpuScene {
    pub fn byte_size(&self) -> usize {
        std::mem::size_of_val(self.prims.as_slice())
            + std::mem::size_of_val(self.nodes.as_slice())
            + std::mem::size_of_val(self.grids.as_slice())
            + std::mem::size_of_val(self.materials.as_slice())
            + std::mem::size_of_val(self.lights.as_slice())
            + std::mem::size_of_val(self.points.as_slice())
    }
}

fn v4(v: Vec3, w: f32) -> [f32; 4] {
    [v.x, v.y, v.z, w]
}

/// All primitive bounds in object order, the input of the BVH builder.
pub fn primitive_bounds(scene: &Scene) -> Vec<(Vec3, Vec3)> {
    scene.objects.iter().flat_map(|o| o.shapes.iter().map(Shape::bounds)).collect()
}

/// Packs the scene's primitives in `order` (the BVH's leaf order, `Bvh::order`)
/// with the BVH in the kernel's layout.
pub fn pack(scene: &Scene, order: &[u32], bvh: GpuBvh) -> GpuScene {
    let flat: Vec<(u32, &Shape, usize)> = scene
        .objects
        .iter()
        .enumerate()
        .flat_map(|(id, o)| o.shapes.iter().map(move |s| (id as u32, s, o.material)))
        .collect();
    let mut points = Vec::new();
    let mut prims: Vec<GpuPrim> = order
        .iter()
        .map(|&i| {
            let (object, shape, material) = flat[i as usize];
            let mut p = GpuPrim { object, kind_material: (material as u32) << 8, ..Zeroable::zeroed() };
            match shape {
                Shape::Sphere { center, radius } => {
                    p.kind_material |= PRIM_SPHERE;
                    p.a = v4(*center, *radius);
                }
                Shape::Triangle { vertices, normals } => {
                    p.kind_material |= PRIM_TRIANGLE;
                    (p.a, p.b, p.c) = (v4(vertices[0], 0.0), v4(vertices[1], 0.0), v4(vertices[2], 0.0));
                    if let Some(ns) = normals {
                        p.first = points.len() as u32;
                        p.count = 3;
                        points.extend(ns.iter().map(|n| v4(*n, 0.0)));
                    }
                }
                Shape::Polygon { vertices } => {
                    p.kind_material |= PRIM_POLYGON;
                    let n = polygon_normal(vertices).unwrap_or(Vec3::Z);
                    p.a = v4(n, n.dot(vertices[0]));
                    p.first = points.len() as u32;
                    p.count = vertices.len() as u32;
                    points.extend(vertices.iter().map(|v| v4(*v, 0.0)));
                }
                Shape::Cone { base, base_radius, apex, apex_radius } => {
                    p.kind_material |= PRIM_CONE;
                    p.a = v4(*base, *base_radius);
                    p.b = v4(*apex, *apex_radius);
                }
            }
            p
        })
        .collect();
    if prims.is_empty() {
        prims.push(Zeroable::zeroed());
    }
    if points.is_empty() {
        points.push([0.0; 4]);
    }
    let materials = scene.materials.iter().map(pack_material).collect();
    let mut lights: Vec<GpuLight> = scene.lights.iter().filter(|l| l.enabled).map(pack_light).collect();
    let light_count = lights.len() as u32;
    if lights.is_empty() {
        lights.push(Zeroable::zeroed());
    }
    GpuScene { prims, nodes: bvh.nodes, grids: bvh.grids, bvh_root: bvh.root, materials, lights, points, light_count }
}

pub fn pack_material(m: &crate::Material) -> GpuMaterial {
    let mut flags = 0;
    if m.specular_model == SpecularModel::BlinnPhong {
        flags |= MATERIAL_BLINN;
    }
    if m.metallic_f0.is_some() {
        flags |= MATERIAL_METALLIC;
    }
    if m.fresnel {
        flags |= MATERIAL_FRESNEL;
    }
    GpuMaterial {
        color: m.color.into(),
        ka: m.ambient,
        specular_color: m.specular_color.unwrap_or(Vec3::ONE).into(),
        kd: m.diffuse,
        reflect: m.reflect.into(),
        ks: m.specular,
        transmit: m.transmit.into(),
        shininess: m.shininess,
        f0: m.metallic_f0.unwrap_or(Vec3::ZERO).into(),
        ior: m.ior,
        flags,
        _pad0: 0,
        _pad1: 0,
        _pad2: 0,
    }
}

pub fn pack_light(l: &crate::Light) -> GpuLight {
    let (position, kind) = match l.kind {
        LightKind::Point { position } => (position, LIGHT_POINT),
        LightKind::Directional { direction } => (direction.normalize_or_zero(), LIGHT_DIRECTIONAL),
    };
    let (attenuation, coefficients) = match l.attenuation {
        Attenuation::None => (ATTENUATION_NONE, [0.0; 4]),
        Attenuation::InverseSquare => (ATTENUATION_INVERSE_SQUARE, [0.0; 4]),
        Attenuation::Polynomial { c1, c2, c3 } => (ATTENUATION_POLYNOMIAL, [c1, c2, c3, 0.0]),
    };
    GpuLight { position: position.into(), kind, radiance: l.radiance().into(), attenuation, coefficients }
}

/// The per-frame uniforms for rendering `scene` at `width` × `height`.
pub fn globals(scene: &Scene, width: u32, height: u32, light_count: u32) -> Globals {
    let basis = scene.camera.basis().expect("scene loaders reject cameras without a basis");
    let (half_width, half_height) = scene.camera.half_extents(width, height);
    let projection = match scene.camera.projection {
        Projection::Perspective { .. } => PROJECTION_PERSPECTIVE,
        Projection::Orthographic { .. } => PROJECTION_ORTHOGRAPHIC,
    };
    let r = &scene.render;
    let mut flags = 0;
    if r.shadows {
        flags |= FLAG_SHADOWS;
    }
    if r.shadow_mode == ShadowMode::Tinted {
        flags |= FLAG_TINTED_SHADOWS;
    }
    if r.reflections {
        flags |= FLAG_REFLECTIONS;
    }
    if r.refractions {
        flags |= FLAG_REFRACTIONS;
    }
    let (depth_cue_color, depth_cue) = match scene.depth_cue {
        Some(d) => {
            flags |= FLAG_DEPTH_CUE;
            (d.color.into(), [d.near, d.far, d.near_scale, d.far_scale])
        }
        None => ([0.0; 3], [0.0; 4]),
    };
    Globals {
        camera: GpuCamera {
            eye: scene.camera.eye.into(),
            projection,
            u: basis.u.as_vec3().into(),
            half_width: half_width as f32,
            v: basis.v.as_vec3().into(),
            half_height: half_height as f32,
            w: basis.w.as_vec3().into(),
            _pad: 0.0,
        },
        background: scene.background.into(),
        width,
        ambient: scene.ambient.into(),
        height,
        depth_cue_color,
        light_count,
        depth_cue,
        max_depth: r.max_depth,
        cutoff: r.cutoff,
        flags,
        view: View::Shaded as u32,
        tile_origin: [0, 0],
        sample_index: 0,
        seed: 0,
        sample_count: 1,
        pixel_filter: Filter::Box as u32,
        row_end: height,
        bvh_root: 0,
    }
}
