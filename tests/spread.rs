//! The order of a dispatch's workgroups over a band (`fast/spread.wgsl`), run
//! on the device: every workgroup gets a place of its own, and each of the
//! runs of consecutive workgroups lavapipe deals its threads holds its share
//! of every strip of the band, whatever the count; and a workgroup's
//! invocations cover its pixels in 2×2 blocks, a SIMD group's lanes together.
//! The plain profile's row order traces the same bits.

mod support;

use glint_encoding::gpu_types::{wgsl_prelude, View, SPREAD_STRIPS};
use glint_gpu::shaders::ShaderSource;
use glint_gpu::WorkgroupSizes;
use wgpu::util::DeviceExt;

const PLACES_KERNEL: &str = r#"
@group(0) @binding(0) var<storage, read_write> places: array<u32>;

@compute @workgroup_size(1)
fn main(@builtin(workgroup_id) wid: vec3<u32>, @builtin(num_workgroups) groups: vec3<u32>) {
    let place = spread_workgroup(wid, groups);
    places[wid.y * groups.x + wid.x] = place.y * groups.x + place.x;
}
"#;

/// The place in the band, as a row-major workgroup index, of each workgroup
/// of a dispatch of `groups`, in the order the driver numbers them.
fn places(groups: [u32; 2]) -> Vec<u32> {
    run_places(PLACES_KERNEL, groups, (groups[0] * groups[1]) as usize)
}

/// The `count` places `kernel`, with spread.wgsl, writes in a dispatch of `groups`.
fn run_places(kernel: &str, groups: [u32; 2], count: usize) -> Vec<u32> {
    let gpu = support::gpu();
    let device = &gpu.device;
    let spread = std::fs::read_to_string(ShaderSource::source_dir().join("fast/spread.wgsl")).unwrap();
    let source = format!("{}{spread}{kernel}", wgsl_prelude());
    let module = device.create_shader_module(wgpu::ShaderModuleDescriptor {
        label: Some("spread"),
        source: wgpu::ShaderSource::Wgsl(source.into()),
    });
    let pipeline = device.create_compute_pipeline(&wgpu::ComputePipelineDescriptor {
        label: Some("spread"),
        layout: None,
        module: &module,
        entry_point: Some("main"),
        compilation_options: Default::default(),
        cache: None,
    });
    let bytes = (count * 4) as u64;
    let out = device.create_buffer_init(&wgpu::util::BufferInitDescriptor {
        label: None,
        contents: &vec![0xffu8; count * 4],
        usage: wgpu::BufferUsages::STORAGE | wgpu::BufferUsages::COPY_SRC,
    });
    let readback = device.create_buffer(&wgpu::BufferDescriptor {
        label: None,
        size: bytes,
        usage: wgpu::BufferUsages::MAP_READ | wgpu::BufferUsages::COPY_DST,
        mapped_at_creation: false,
    });
    let bind = device.create_bind_group(&wgpu::BindGroupDescriptor {
        label: None,
        layout: &pipeline.get_bind_group_layout(0),
        entries: &[wgpu::BindGroupEntry { binding: 0, resource: out.as_entire_binding() }],
    });
    let mut encoder = device.create_command_encoder(&Default::default());
    {
        let mut pass = encoder.begin_compute_pass(&Default::default());
        pass.set_pipeline(&pipeline);
        pass.set_bind_group(0, &bind, &[]);
        pass.dispatch_workgroups(groups[0], groups[1], 1);
    }
    encoder.copy_buffer_to_buffer(&out, 0, &readback, 0, bytes);
    gpu.queue.submit([encoder.finish()]);
    readback.map_async(wgpu::MapMode::Read, .., |r| r.unwrap());
    device.poll(wgpu::PollType::wait_indefinitely()).unwrap();
    let mapped = readback.get_mapped_range(..).unwrap();
    mapped.chunks_exact(4).map(|b| u32::from_le_bytes(b.try_into().unwrap())).collect()
}

/// Dispatch shapes of bands: one workgroup, one row of them, odd counts on
/// either side of a multiple of the strips, a whole 512×512 image.
const SHAPES: [[u32; 2]; 8] = [[1, 1], [5, 1], [64, 1], [7, 5], [13, 17], [64, 3], [33, 31], [64, 64]];

/// Asserts that `places` holds each of 0..places.len() once.
fn assert_each_place_once(places: &[u32], what: &str) {
    let mut seen = places.to_vec();
    seen.sort_unstable();
    let all: Vec<u32> = (0..places.len() as u32).collect();
    assert_eq!(seen, all, "{what}: not every place once");
}

#[test]
fn every_workgroup_has_a_place_of_its_own() {
    for groups in SHAPES {
        assert_each_place_once(&places(groups), &format!("a dispatch of {groups:?} workgroups"));
    }
}

/// lavapipe deals a dispatch's workgroups to its threads in runs of
/// count / threads consecutive ones (the remainder one at a time).
#[test]
fn every_threads_run_holds_its_share_of_every_strip() {
    for groups in SHAPES {
        let places = places(groups);
        let count = places.len();
        let strip_of = |place: u32| {
            let (length, longer) = (count / SPREAD_STRIPS as usize, count % SPREAD_STRIPS as usize);
            let place = place as usize;
            // The first `longer` strips hold one place more.
            if place < longer * (length + 1) { place / (length + 1) } else { longer + (place - longer * (length + 1)) / length }
        };
        for threads in 2..=4 {
            let run = count / threads;
            if run < SPREAD_STRIPS as usize {
                continue;
            }
            for (t, chunk) in places[..run * threads].chunks(run).enumerate() {
                let mut per_strip = vec![0usize; SPREAD_STRIPS as usize];
                for &place in chunk {
                    per_strip[strip_of(place)] += 1;
                }
                let share = count / SPREAD_STRIPS as usize / threads;
                assert!(
                    per_strip.iter().all(|&n| n + 1 >= share && n <= share + 2),
                    "thread {t} of {threads}, dispatch of {groups:?}: {per_strip:?} places per strip, not about {share}"
                );
            }
        }
    }
}

/// The place in its workgroup, as a row-major index, of each invocation of a
/// workgroup of `size`, in the order the driver numbers them.
fn invocation_places(size: [u32; 2]) -> Vec<u32> {
    let kernel = format!(
        "@group(0) @binding(0) var<storage, read_write> places: array<u32>;\n\
         @compute @workgroup_size({}, {})\n\
         fn main(@builtin(local_invocation_id) lid: vec3<u32>) {{\n\
             let size = vec2<u32>({}u, {}u);\n\
             let place = spread_invocation(lid, size);\n\
             places[lid.y * size.x + lid.x] = place.y * size.x + place.x;\n\
         }}",
        size[0], size[1], size[0], size[1]
    );
    run_places(&kernel, [1, 1], (size[0] * size[1]) as usize)
}

#[test]
fn every_four_consecutive_invocations_trace_a_2x2_block() {
    let profiles = [WorkgroupSizes::PLAIN, WorkgroupSizes::LAVAPIPE].into_iter().flat_map(|w| [w.band(), w.primary()]);
    for size in profiles.chain([[2, 2], [6, 4]]) {
        let places = invocation_places(size);
        assert_each_place_once(&places, &format!("a workgroup of {size:?}"));
        for (g, group) in places.chunks(4).enumerate() {
            let (xs, ys): (Vec<u32>, Vec<u32>) = group.iter().map(|p| (p % size[0], p / size[0])).unzip();
            let (x, y) = (xs[0], ys[0]);
            assert_eq!(xs, [x, x + 1, x, x + 1], "group {g} of a workgroup of {size:?}: {group:?}");
            assert_eq!(ys, [y, y, y + 1, y + 1], "group {g} of a workgroup of {size:?}: {group:?}");
        }
    }
}

/// The plain profile's row order and workgroup sizes trace the pixels and
/// count the rays that lavapipe's spread order and sizes do: for the trace,
/// primary and diffuse kernels in every view, single rays and packets, in an
/// image whose workgroups overhang its edges, over every kind of primitive,
/// shadows, reflection and refraction.
#[test]
fn row_order_traces_what_spread_order_traces() {
    let renderer = support::renderer();
    let scenes = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("scenes");
    for name in ["spd:tetra:2", "spd:balls:1", "gallery/primitives.toml", "showcase.toml"] {
        let path = if name.starts_with("spd:") { name.into() } else { scenes.join(name) };
        let scene = glint_scene::load(&path).unwrap_or_else(|e| panic!("{e}"));
        let mut prepared = renderer.prepare(&scene, 45, 29, glint_gpu::Acceleration::Bvh).unwrap_or_else(|e| panic!("{e}"));
        for view in View::ALL {
            for packets in [false, true] {
                let options = glint_gpu::RenderOptions { view, spp: 2, ..Default::default() };
                let mut render = |spread, workgroups| {
                    let tuning = prepared.buffers.tuning().with_packets(packets).with_eye_tiles(false).with_spread(spread).with_workgroups(workgroups);
                    prepared.buffers.retune(tuning);
                    renderer.render(&prepared.buffers, &options, &mut |_, _| {}).unwrap_or_else(|e| panic!("{e}"))
                };
                let (spread, spread_stats) = render(true, WorkgroupSizes::LAVAPIPE);
                let (rows, row_stats) = render(false, WorkgroupSizes::PLAIN);
                let case = format!("{name}, {view:?} view, packets {packets}");
                support::assert_images_equal(&rows.linear, &spread.linear, 0, &case);
                assert_eq!(row_stats, spread_stats, "{case}");
            }
        }
    }
}
