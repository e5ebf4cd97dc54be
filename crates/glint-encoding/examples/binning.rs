//! Times eye-tile binning alone, for a profiler: an SPD scene's footprints
//! binned from its own camera, again and again.
//!
//!     cargo run --release -p glint-encoding --example binning -- gears 200

use std::time::Instant;

use glam::Vec3;
use glint_encoding::eye_tiles::Footprints;
use glint_encoding::gpu_bvh::GpuBvh;
use glint_encoding::gpu_types;
use glint_scene::bvh::Bvh;
use glint_scene::{polygon_split, spd};

fn main() {
    let mut args = std::env::args().skip(1);
    let name = args.next().unwrap_or_else(|| "gears".into());
    let rounds: usize = args.next().map_or(200, |n| n.parse().expect("a number of rounds"));
    let scene = glint_scene::load(format!("{}{name}", spd::PREFIX).as_ref()).expect("an SPD scene");
    let scene = polygon_split::split_large_polygons(&scene);
    let bounds = gpu_types::primitive_bounds(&scene);
    let bvh = Bvh::build(&bounds);
    let packed = gpu_types::pack(&scene, &bvh.order, GpuBvh::encode(&bvh).expect("an encodable BVH"));
    let ordered: Vec<(Vec3, Vec3)> = bvh.order.iter().map(|&i| bounds[i as usize]).collect();
    let footprints = Footprints::new(&packed, &ordered);
    let camera = gpu_types::scene_uniforms(&scene, 512, 512, 0, Default::default()).camera;
    let mut times: Vec<f64> = (0..rounds)
        .map(|_| {
            let start = Instant::now();
            std::hint::black_box(footprints.bin(&camera, 512, 512));
            start.elapsed().as_secs_f64() * 1e3
        })
        .collect();
    times.sort_by(f64::total_cmp);
    println!("{name}: median {:.3} ms, fastest {:.3} ms of {rounds}", times[rounds / 2], times[0]);
}
