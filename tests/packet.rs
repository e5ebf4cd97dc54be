//! Ray packets (shaders/fast/packet.wgsl): with `Tuning::packets` the
//! primary kernel traces the eye rays of each 2×2 block of pixels together,
//! through the BVH or through their eye tile's list (shaders/fast/eye_tiles.wgsl),
//! and each ray must get exactly the hit it gets alone. Every data view and
//! the ray counts of both walks are held to the kernel that traces single
//! rays, bit for bit, for every kind of primitive, both projections, and
//! blocks cut by the image's edge.

mod support;

use glint_encoding::gpu_types::View;
use glint_gpu::{Acceleration, RenderOptions};
use glint_scene::Scene;

/// Width and height odd, so the last column and row of blocks hang over the edge.
const SIZE: (u32, u32) = (37, 27);

/// Returns how many eye rays missed.
fn assert_packets_trace_as_single_rays(scene: &Scene, what: &str) -> u64 {
    let mut scene = scene.clone();
    (scene.width, scene.height) = SIZE;
    let renderer = support::renderer();
    let mut prepared = renderer.prepare(&scene, scene.width, scene.height, Acceleration::Bvh).unwrap_or_else(|e| panic!("{e}"));
    assert!(prepared.buffers.tuning().eye_tiles(), "{what}: binned into eye tiles on lavapipe");
    let mut misses = 0;
    for view in View::ALL.into_iter().filter(|v| v.is_primary_only()) {
        let mut render = |packets, eye_tiles| {
            prepared.buffers.retune(prepared.buffers.tuning().with_packets(packets).with_eye_tiles(eye_tiles));
            let options = RenderOptions { view, ..Default::default() };
            renderer.render(&prepared.buffers, &options, &mut |_, _| {}).unwrap_or_else(|e| panic!("{e}"))
        };
        let (single, single_stats) = render(false, false);
        for (eye_tiles, walk) in [(false, "the BVH"), (true, "eye tiles")] {
            let (packets, packet_stats) = render(true, eye_tiles);
            support::assert_images_equal(&packets.linear, &single.linear, 0, &format!("{what}, {view:?} view, packets through {walk}"));
            assert_eq!(packet_stats, single_stats, "{what}, {view:?} view, packets through {walk}");
        }
        misses = single_stats.eye_miss;
    }
    assert!(misses < u64::from(SIZE.0 * SIZE.1), "{what}: no ray hit anything");
    misses
}

#[test]
fn packets_of_every_primitive_kind_hit_what_single_rays_hit() {
    // tetra: triangles; gears: polygons cut into sectors; balls: spheres and a
    // polygon; tree: cones, cylinders and spheres; rings: cylinders; mount:
    // triangles and spheres.
    let mut misses = 0;
    for name in ["tetra:2", "gears:1", "balls:1", "tree:2", "rings:1", "mount:1"] {
        let scene = glint_scene::load(std::path::Path::new(&format!("spd:{name}"))).unwrap_or_else(|e| panic!("{e}"));
        misses += assert_packets_trace_as_single_rays(&scene, name);
    }
    for seed in 0..4 {
        misses += assert_packets_trace_as_single_rays(&glint_reference::random_scene(seed), &format!("random scene {seed}"));
    }
    // Every kind in one scene, smooth triangles and a concave polygon among them.
    let gallery = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("scenes/gallery/primitives.toml");
    misses += assert_packets_trace_as_single_rays(&glint_scene::load(&gallery).unwrap_or_else(|e| panic!("{e}")), "primitives.toml");
    assert!(misses > 0, "no eye ray missed: packets of hits and misses were not tried");
}

#[test]
fn packets_hit_what_single_rays_hit_through_an_orthographic_camera_and_on_a_plane() {
    let dir = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("scenes/gallery");
    let scene = glint_scene::load(&dir.join("orthographic.toml")).unwrap_or_else(|e| panic!("{e}"));
    assert_packets_trace_as_single_rays(&scene, "orthographic");
    let scene = support::parse(
        r#"
[image]
width = 8
height = 8

[camera]
eye = [0.5, 2, 6]
look_at = [0, 0, 0]
fov = 50

[[light]]
type = "point"
position = [1, 6, 2]

[[object]]
type = "plane"
point = [0, 0, 0]
normal = [0, 1, 0]

[[object]]
type = "sphere"
center = [-0.6, 0.5, 0]
radius = 0.6

[[object]]
type = "triangle"
vertices = [[0.2, 0, 1], [1.6, 0, 1], [0.9, 1.4, 0.6]]
"#,
    );
    assert_packets_trace_as_single_rays(&scene, "plane, sphere and triangle");
}

#[test]
fn packets_hit_what_single_rays_hit_on_the_shared_edges_and_corners_of_polygons() {
    // Unit squares, each an object of its own, seen straight on by an
    // orthographic camera whose pixels are a quarter unit: every fourth row
    // and column of eye rays runs along the squares' shared edges, and where
    // they cross through shared corners, the cases the crossing rule's ties
    // decide.
    let mut toml = String::from(
        "[image]\nwidth = 37\nheight = 27\n\n[camera]\ntype = \"orthographic\"\neye = [0, 0, 5]\nlook_at = [0, 0, 0]\nheight = 6.75\n",
    );
    for x in -4..4 {
        for y in -3..3 {
            let (x1, y1) = (x + 1, y + 1);
            toml += &format!("\n[[object]]\ntype = \"polygon\"\nvertices = [[{x}, {y}, 0], [{x1}, {y}, 0], [{x1}, {y1}, 0], [{x}, {y1}, 0]]\n");
        }
    }
    assert_packets_trace_as_single_rays(&support::parse(&toml), "a grid of squares");
}

/// Eye tiles belong to the view they were binned for: moved in place, the
/// camera's primary rays walk the BVH until `pose` bins the tiles again, and
/// either way the image is that of the scene uploaded with the new camera,
/// also when a view's lists are written over the last view's.
#[test]
fn eye_tiles_follow_the_camera() {
    let mut scene = glint_scene::load(std::path::Path::new("spd:tetra:2")).unwrap_or_else(|e| panic!("{e}"));
    (scene.width, scene.height) = SIZE;
    let renderer = support::renderer();
    let mut moved = scene.clone();
    moved.camera.eye = moved.camera.eye * 0.8 + glam::Vec3::new(0.3, -0.2, 0.1);
    let options = RenderOptions { view: View::Depth, ..Default::default() };
    let depth = |buffers: &glint_gpu::SceneBuffers| renderer.render(buffers, &options, &mut |_, _| {}).unwrap_or_else(|e| panic!("{e}")).0;
    let fresh = renderer.prepare(&moved, SIZE.0, SIZE.1, Acceleration::Bvh).unwrap();
    assert!(fresh.buffers.tuning().eye_tiles());
    let want = depth(&fresh.buffers);

    let mut prepared = renderer.prepare(&scene, SIZE.0, SIZE.1, Acceleration::Bvh).unwrap();
    let uniforms = glint_encoding::gpu_types::scene_uniforms(&moved, SIZE.0, SIZE.1, prepared.lights, prepared.buffers.layout());
    renderer.write_uniforms(&mut prepared.buffers, &uniforms).unwrap();
    assert!(!prepared.buffers.tuning().eye_tiles(), "the tiles of the old view are not walked");
    support::assert_images_equal(&depth(&prepared.buffers).linear, &want.linear, 0, "camera moved in place");
    renderer.pose(&mut prepared, &moved).unwrap();
    assert!(prepared.buffers.tuning().eye_tiles(), "posed: binned for the new view");
    support::assert_images_equal(&depth(&prepared.buffers).linear, &want.linear, 0, "camera posed");

    // Forgotten, as `glint bench` forgets it to time a camera move.
    prepared.buffers.forget_view();
    assert!(!prepared.buffers.tuning().eye_tiles(), "the forgotten view's tiles are not walked");
    support::assert_images_equal(&depth(&prepared.buffers).linear, &want.linear, 0, "view forgotten");
    renderer.pose(&mut prepared, &moved).unwrap();
    assert!(prepared.buffers.tuning().eye_tiles(), "posed again: binned again");
    support::assert_images_equal(&depth(&prepared.buffers).linear, &want.linear, 0, "view forgotten and posed");
    let unmoved = depth(&renderer.prepare(&scene, SIZE.0, SIZE.1, Acceleration::Bvh).unwrap().buffers);
    assert_ne!(unmoved.linear, want.linear, "the camera moved");

    // Back again: one of the two views' lists was written over the other's.
    renderer.pose(&mut prepared, &scene).unwrap();
    support::assert_images_equal(&depth(&prepared.buffers).linear, &unmoved.linear, 0, "camera posed back");
}

/// A view whose primitives would give each eye tile more than
/// `MAX_MEAN_ENTRIES` on average is not binned, and its eye rays walk the BVH
/// one at a time rather than as packets that would part at almost every leaf
/// (docs/decisions/058-single-eye-rays-where-tiles-are-refused.md); a view of
/// the scene that bins gets its tiles and packets back. Each traces the bits
/// the plain profile traces.
#[test]
fn a_view_too_crowded_to_bin_traces_single_eye_rays() {
    // 16×8 pixels are four tiles of 8×4. Six layers of spheres, one behind
    // the other, each over most pixel centres, make more than four times
    // MAX_MEAN_ENTRIES entries.
    let (width, height) = (16, 8);
    assert_eq!(glint_encoding::eye_tiles::MAX_MEAN_ENTRIES, 64, "the scene is sized for 64 entries a tile");
    let mut toml = format!("[image]\nwidth = {width}\nheight = {height}\n\n[camera]\neye = [0, 0, 10]\nlook_at = [0, 0, 0]\nfov = 40\n\n[[light]]\ntype = \"point\"\nposition = [2, 4, 12]\n");
    for layer in 0..6 {
        for i in 0..24 {
            for j in 0..12 {
                let (x, y, z) = (-3.5 + 0.3 * f64::from(i), -1.75 + 0.3 * f64::from(j), -f64::from(layer));
                toml += &format!("\n[[object]]\ntype = \"sphere\"\ncenter = [{x:.2}, {y:.2}, {z}]\nradius = 0.25\n");
            }
        }
    }
    // Off to the side, alone in a view of its own.
    toml += "\n[[object]]\ntype = \"sphere\"\ncenter = [20, 0, 0]\nradius = 1\n";
    let crowded = support::parse(&toml);
    let mut aside = crowded.clone();
    (aside.camera.eye, aside.camera.look_at) = (glam::Vec3::new(20.0, 0.0, 5.0), glam::Vec3::new(20.0, 0.0, 0.0));

    let renderer = support::renderer();
    let render = |buffers: &glint_gpu::SceneBuffers, scene: &Scene, view: View, what: &str| {
        let options = RenderOptions { view, ..Default::default() };
        let (image, stats) = renderer.render(buffers, &options, &mut |_, _| {}).unwrap_or_else(|e| panic!("{e}"));
        let (want, want_stats) = support::render_options(scene, Acceleration::Bvh, options);
        support::assert_images_equal(&image.linear, &want.linear, 0, &format!("{what}, {view:?} view"));
        assert_eq!(stats, want_stats, "{what}, {view:?} view");
        assert!(stats.eye_hit > 0, "{what}: the spheres are in view");
    };
    let single_rays = |t: glint_gpu::Tuning| !t.eye_tiles() && !t.packets();
    let tiles = |t: glint_gpu::Tuning| t.eye_tiles() && t.packets();

    let prepared = renderer.prepare(&crowded, width, height, Acceleration::Bvh).unwrap_or_else(|e| panic!("{e}"));
    assert!(single_rays(prepared.buffers.tuning()), "prepared for the crowded view: {:?}", prepared.buffers.tuning());
    for view in [View::Depth, View::Albedo] {
        render(&prepared.buffers, &crowded, view, "prepared for the crowded view");
    }

    // A camera move from a view that bins to the crowded one and back.
    let mut prepared = renderer.prepare(&aside, width, height, Acceleration::Bvh).unwrap_or_else(|e| panic!("{e}"));
    assert!(tiles(prepared.buffers.tuning()), "a view of one sphere is binned: {:?}", prepared.buffers.tuning());
    renderer.pose(&mut prepared, &crowded).unwrap_or_else(|e| panic!("{e}"));
    assert!(single_rays(prepared.buffers.tuning()), "posed for the crowded view: {:?}", prepared.buffers.tuning());
    render(&prepared.buffers, &crowded, View::Depth, "posed for the crowded view");
    renderer.pose(&mut prepared, &aside).unwrap_or_else(|e| panic!("{e}"));
    assert!(tiles(prepared.buffers.tuning()), "posed back: binned again: {:?}", prepared.buffers.tuning());
    render(&prepared.buffers, &aside, View::Depth, "posed back");
}
