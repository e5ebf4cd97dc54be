//! The GPU operations the viewer is built on (glint_gpu::interactive), against
//! the one-shot renderer: banded tracing, presenting into a texture, in-place
//! edits, picking and ray counting. No adapter is a failure, never a skip.

use std::path::Path;
use std::sync::OnceLock;

use glint_encoding::gpu_types::{self, View};
use glint_gpu::shaders::ShaderSource;
use glint_gpu::{Acceleration, Gpu, GpuError, Image, RenderOptions, Renderer, SceneBuffers};
use glint_scene::{LightKind, Scene};

const SCENE: &str = r#"
[image]
width = 67
height = 41
background = [0.2, 0.3, 0.5]

[camera]
eye = [0, 1.5, 6]
look_at = [0, 0.8, 0]
fov = 40

[[light]]
type = "point"
position = [-3, 5, 4]

[[light]]
type = "point"
position = [3, 2, 4]
color = [0.2, 0.3, 1]

[material.red]
color = [0.9, 0.15, 0.1]
ks = 0.5
reflect = 0.3

[[object]]
type = "polygon"
vertices = [[-4, 0, -4], [4, 0, -4], [4, 0, 4], [-4, 0, 4]]

[[object]]
type = "sphere"
center = [-0.9, 0.8, 0]
radius = 0.8
material = "red"

[[object]]
type = "sphere"
center = [1.1, 0.6, 0.5]
radius = 0.6
"#;

fn gpu() -> &'static Gpu {
    static GPU: OnceLock<Gpu> = OnceLock::new();
    GPU.get_or_init(|| Gpu::new().unwrap_or_else(|e| panic!("GPU tests need an adapter (a software adapter in CI): {e}")))
}

fn renderer() -> &'static Renderer {
    static RENDERER: OnceLock<Renderer> = OnceLock::new();
    RENDERER.get_or_init(|| Renderer::new(gpu().device.clone(), gpu().queue.clone(), &ShaderSource::Embedded).unwrap())
}

fn scene() -> Scene {
    glint_scene::toml_scene::parse(SCENE, Path::new("inline.toml")).unwrap()
}

fn upload(scene: &Scene) -> SceneBuffers {
    renderer().prepare(scene, scene.width, scene.height, Acceleration::Bvh).unwrap().buffers
}

/// Traces `spp` samples in bands of 16 rows, as the viewer does: the first
/// sample clears each band before tracing it.
fn trace_in_bands(scene: &SceneBuffers, options: &RenderOptions) {
    for sample in 0..options.spp {
        for y in (0..scene.height()).step_by(16) {
            if sample == 0 {
                renderer().clear_rows(scene, y..y + 16);
            }
            renderer().trace_rows(scene, sample, options, y..y + 16).unwrap();
        }
    }
}

fn resolve(scene: &SceneBuffers, options: &RenderOptions) -> Image {
    renderer().resolve(scene, options).unwrap()
}

/// The rgba8 texels of `texture`, rows top first.
fn read_texture(texture: &wgpu::Texture) -> Vec<[u8; 4]> {
    let (w, h) = (texture.width(), texture.height());
    let row = (w * 4).div_ceil(256) * 256;
    let device = &gpu().device;
    let buffer = device.create_buffer(&wgpu::BufferDescriptor {
        label: None,
        size: u64::from(row * h),
        usage: wgpu::BufferUsages::MAP_READ | wgpu::BufferUsages::COPY_DST,
        mapped_at_creation: false,
    });
    let mut encoder = device.create_command_encoder(&Default::default());
    encoder.copy_texture_to_buffer(
        texture.as_image_copy(),
        wgpu::TexelCopyBufferInfo {
            buffer: &buffer,
            layout: wgpu::TexelCopyBufferLayout { offset: 0, bytes_per_row: Some(row), rows_per_image: None },
        },
        texture.size(),
    );
    gpu().queue.submit([encoder.finish()]);
    buffer.map_async(wgpu::MapMode::Read, .., |r| r.unwrap());
    device.poll(wgpu::PollType::wait_indefinitely()).unwrap();
    let bytes = buffer.get_mapped_range(..).unwrap().to_vec();
    (0..h)
        .flat_map(|y| (0..w).map(move |x| (y, x)))
        .map(|(y, x)| {
            let i = (y * row + x * 4) as usize;
            [bytes[i], bytes[i + 1], bytes[i + 2], bytes[i + 3]]
        })
        .collect()
}

#[test]
fn banded_tracing_equals_a_one_shot_render() {
    let scene = scene();
    let buffers = upload(&scene);
    let options = RenderOptions { spp: 4, ..RenderOptions::default() };
    let (want, _) = renderer().render(&buffers, &options, &mut |_, _| {}).unwrap();
    // Whatever was accumulated before is cleared band by band.
    trace_in_bands(&buffers, &RenderOptions { view: View::Normal, spp: 3, ..RenderOptions::default() });
    trace_in_bands(&buffers, &options);
    assert_eq!(resolve(&buffers, &options), want);
}

#[test]
fn present_writes_the_resolved_image_into_the_texture() {
    let scene = scene();
    let buffers = upload(&scene);
    let pipeline = renderer().present_pipeline(&ShaderSource::Embedded).unwrap();
    let target = renderer().present_target(&pipeline, &buffers);
    for options in [
        RenderOptions { spp: 2, exposure: 1.7, tone_map: glint_gpu::ToneMap::Aces, ..RenderOptions::default() },
        RenderOptions { view: View::Normal, ..RenderOptions::default() },
    ] {
        trace_in_bands(&buffers, &options);
        renderer().present(&pipeline, &target, &options);
        let texels = read_texture(&target.texture);
        let want = resolve(&buffers, &options);
        for (t, d) in texels.iter().zip(&want.display) {
            for c in 0..3 {
                let expected = (d[c] * 255.0).round();
                assert!((f32::from(t[c]) - expected).abs() <= 1.0, "{:?}: texel {t:?}, resolve {d:?}", options.view);
            }
            assert_eq!(t[3], 255);
        }
    }
}

#[test]
fn edits_in_place_equal_a_fresh_upload() {
    let mut edited = scene();
    let mut buffers = upload(&edited);
    edited.lights[0].kind = LightKind::Point { position: glam::Vec3::new(2.0, 4.0, 1.0) };
    edited.lights[1].enabled = false;
    edited.materials[1].color = glam::Vec3::new(0.1, 0.8, 0.2);
    edited.camera.eye = glam::Vec3::new(1.0, 2.5, 5.0);
    edited.ambient = glam::Vec3::splat(0.3);

    let lights: Vec<_> = edited.lights.iter().filter(|l| l.enabled).map(gpu_types::pack_light).collect();
    let materials: Vec<_> = edited.materials.iter().map(gpu_types::pack_material).collect();
    renderer().write_lights(&buffers, &lights).unwrap();
    renderer().write_materials(&buffers, &materials).unwrap();
    let uniforms = gpu_types::scene_uniforms(&edited, edited.width, edited.height, lights.len() as u32, buffers.layout());
    renderer().write_uniforms(&mut buffers, &uniforms).unwrap();
    let options = RenderOptions::default();
    trace_in_bands(&buffers, &options);

    let fresh = upload(&edited);
    let (want, _) = renderer().render(&fresh, &options, &mut |_, _| {}).unwrap();
    assert_eq!(resolve(&buffers, &options), want);

    // More lights than were uploaded is an error, not a silent overrun.
    let too_many = vec![lights[0]; buffers.light_capacity() + 1];
    assert!(renderer().write_lights(&buffers, &too_many).is_err());
}

/// A scene that reflects nothing is uploaded for eye rays only; making a
/// material reflect in place is refused, unless the scene was uploaded
/// editable (with every term), as the viewer uploads, and then it renders as a
/// fresh upload.
#[test]
fn a_material_made_to_reflect_in_place_needs_secondary_rays() {
    let mut matte = scene();
    for m in &mut matte.materials {
        m.reflect = glam::Vec3::ZERO;
        m.transmit = glam::Vec3::ZERO;
    }
    let mut mirror = matte.clone();
    mirror.materials[1].reflect = glam::Vec3::splat(0.6);
    let materials: Vec<_> = mirror.materials.iter().map(gpu_types::pack_material).collect();

    let buffers = upload(&matte);
    assert!(!buffers.specialization.secondary_rays);
    refused_until_editable(buffers, "eye rays only", &mirror, |b| renderer().write_materials(b, &materials));
}

/// `write` of an edit to `buffers` is refused, naming `lacking`, until the
/// scene is uploaded editable; then the edited scene renders as `edited`
/// freshly uploaded.
fn refused_until_editable(mut buffers: SceneBuffers, lacking: &str, edited: &Scene, write: impl Fn(&mut SceneBuffers) -> Result<(), GpuError>) {
    let refused = write(&mut buffers).unwrap_err().to_string();
    assert!(refused.contains(lacking) && refused.contains("editable"), "{refused}");
    buffers.specialization = buffers.specialization.editable();
    write(&mut buffers).unwrap();
    let options = RenderOptions::default();
    trace_in_bands(&buffers, &options);
    let (want, _) = renderer().render(&upload(edited), &options, &mut |_, _| {}).unwrap();
    assert_eq!(resolve(&buffers, &options), want);
}

/// A scene without depth cueing is uploaded without its code; turning it on
/// in place is refused unless the scene was uploaded editable, and then it
/// renders as a fresh upload.
#[test]
fn depth_cueing_turned_on_in_place_needs_an_editable_upload() {
    let plain = scene();
    assert!(plain.depth_cue.is_none());
    let mut cued = plain.clone();
    cued.depth_cue = Some(glint_scene::DepthCue { color: glam::Vec3::new(0.2, 0.3, 0.4), near: 1.0, far: 8.0, near_scale: 1.0, far_scale: 0.2 });
    let buffers = upload(&plain);
    assert!(!buffers.specialization.depth_cue);
    let uniforms = gpu_types::scene_uniforms(&cued, cued.width, cued.height, cued.lights.iter().filter(|l| l.enabled).count() as u32, buffers.layout());
    refused_until_editable(buffers, "depth cueing", &cued, |b| renderer().write_uniforms(b, &uniforms));
}

/// A scene's kernels hold the ray trees of its own maximum depth; a deeper
/// one in place is refused unless the scene was uploaded editable, and then
/// it renders as a fresh upload.
#[test]
fn a_deeper_ray_tree_in_place_needs_an_editable_upload() {
    let mut shallow = scene();
    shallow.render.max_depth = 2;
    let mut deep = shallow.clone();
    deep.render.max_depth = 6;
    let buffers = upload(&shallow);
    assert_eq!(buffers.specialization.max_depth, 2);
    let uniforms = gpu_types::scene_uniforms(&deep, deep.width, deep.height, deep.lights.iter().filter(|l| l.enabled).count() as u32, buffers.layout());
    refused_until_editable(buffers, "deeper ray tree", &deep, |b| renderer().write_uniforms(b, &uniforms));
}

#[test]
fn picking_finds_each_pixel_s_object_and_leaves_the_image_alone() {
    let scene = scene();
    let buffers = upload(&scene);
    let ids = RenderOptions { view: View::Id, ..RenderOptions::default() };
    let (id_image, _) = renderer().render(&buffers, &ids, &mut |_, _| {}).unwrap();

    let shaded = RenderOptions::default();
    trace_in_bands(&buffers, &shaded);
    let before = resolve(&buffers, &shaded);
    let mut seen = std::collections::BTreeSet::new();
    for (x, y) in [(0, 0), (20, 20), (50, 30), (33, 2), (66, 40), (10, 35), (45, 22)] {
        let want = id_image.linear_at(x, y)[0];
        let got = renderer().pick(&buffers, x, y).unwrap();
        assert_eq!(got, (want >= 0.0).then_some(want as u32), "pixel ({x}, {y})");
        seen.insert(got);
    }
    assert!(seen.len() >= 3, "the probes cover sky, floor and a sphere: {seen:?}");
    assert_eq!(resolve(&buffers, &shaded), before, "picking must not disturb the accumulation");
}

#[test]
fn the_ray_counter_delivers_the_rays_traced() {
    let scene = scene();
    let buffers = upload(&scene);
    let mut counter = renderer().ray_counter();
    counter.request(renderer(), &buffers);
    gpu().device.poll(wgpu::PollType::wait_indefinitely()).unwrap();
    counter.poll().expect("delivered").unwrap();

    let options = RenderOptions { view: View::Albedo, ..RenderOptions::default() };
    trace_in_bands(&buffers, &options);
    counter.request(renderer(), &buffers);
    gpu().device.poll(wgpu::PollType::wait_indefinitely()).unwrap();
    let stats = counter.poll().expect("delivered").unwrap();
    assert_eq!(stats.eye_hit + stats.eye_miss, u64::from(scene.width * scene.height));
    assert!(stats.eye_hit > 0 && stats.eye_miss > 0);
}
