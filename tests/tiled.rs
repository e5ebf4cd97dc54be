//! Tiled rendering: an image larger than the device holds at once renders tile
//! by tile with exactly the pixels and ray counts of an untiled render, for
//! every view and with jittered samples; a region renders the pixels it has
//! in the whole image.

mod support;

use glint_encoding::gpu_types::{Filter, View};
use glint_gpu::shaders::ShaderSource;
use glint_gpu::{Acceleration, Bits, Channels, Image, ImageSink, RayStats, Region, RenderOptions, Renderer};
use support::{gpu, parse, renderer};

fn showcase(width: u32, height: u32) -> glint_scene::Scene {
    let scene = parse(&std::fs::read_to_string(concat!(env!("CARGO_MANIFEST_DIR"), "/scenes/showcase.toml")).unwrap());
    glint_scene::Scene { width, height, ..scene }
}

/// A renderer that holds at most `pixels` pixels of an image at once.
fn renderer_with_tiles_of(pixels: u64) -> Renderer {
    Renderer::new(gpu().device.clone(), gpu().queue.clone(), &ShaderSource::Embedded).unwrap().with_max_tile_pixels(pixels)
}

fn render(r: &Renderer, scene: &glint_scene::Scene, region: Option<Region>, options: RenderOptions) -> (Image, RayStats) {
    let prepared = r.prepare(scene, scene.width, scene.height, Acceleration::Bvh).unwrap();
    let options = RenderOptions { view_scale: prepared.view_scale(options.view), ..options };
    let region = region.unwrap_or(Region::whole(scene.width, scene.height));
    r.render_region(&prepared.buffers, region, &options, &mut |_, _| {}).unwrap()
}

fn every_view() -> Vec<RenderOptions> {
    let shaded = RenderOptions { spp: 5, seed: 11, filter: Filter::Tent, ..RenderOptions::default() };
    let views = [View::Normal, View::Depth, View::Albedo, View::Diffuse, View::Id, View::Heatmap];
    std::iter::once(shaded).chain(views.map(|view| RenderOptions { view, ..RenderOptions::default() })).collect()
}

#[test]
fn tiled_renders_equal_untiled_ones_in_every_view() {
    let scene = showcase(45, 29);
    // Tiles of whole rows (45 × 11), and tiles narrower than a row (7 × 1).
    for tile_pixels in [500, 7] {
        let tiled = renderer_with_tiles_of(tile_pixels);
        let prepared = tiled.prepare(&scene, scene.width, scene.height, Acceleration::Bvh).unwrap();
        assert!(!prepared.buffers.holds_whole_image(), "tiles of {tile_pixels}: the image should not fit");
        for options in every_view() {
            let what = format!("{:?} in tiles of {tile_pixels} pixels", options.view);
            let (whole, whole_stats) = render(renderer(), &scene, None, options);
            let (tiles, tile_stats) = render(&tiled, &scene, None, options);
            assert!(whole.linear == tiles.linear && whole.display == tiles.display, "{what}: pixels differ");
            assert_eq!(whole_stats, tile_stats, "{what}: ray counts differ");
        }
    }
}

/// What `glint render` does with tiles: each goes straight into the file,
/// which holds no more than a band of tiles' rows of 8-bit samples, and the
/// file is the one an untiled render writes.
#[test]
fn tiles_stream_into_a_png_that_holds_one_band_of_rows() {
    let (width, height) = (45, 29);
    let scene = showcase(width, height);
    let tiled = renderer_with_tiles_of(u64::from(width) * 4);
    let prepared = tiled.prepare(&scene, width, height, Acceleration::Bvh).unwrap();
    let options = RenderOptions { spp: 2, ..RenderOptions::default() };
    let dir = tempfile::tempdir().unwrap();
    let (streamed, untiled) = (dir.path().join("streamed.png"), dir.path().join("untiled.png"));
    let mut sink = ImageSink::create(&streamed, width, height, Bits::Eight.into(), Channels::Rgb).unwrap();
    let mut held = 0;
    let region = Region::whole(width, height);
    tiled
        .render_tiles(&prepared.buffers, region, &options, &mut |_, _| {}, &mut |tile, pixels| {
            sink.paste(&pixels, tile.x0, tile.y0)?;
            held = held.max(sink.retained_bytes());
            Ok(())
        })
        .unwrap();
    sink.finish().unwrap().commit().unwrap();
    let band = width as usize * 4 * 3;
    assert!(held <= band + 4 * 4, "{held} bytes held, a band of 4 rows is {band}");
    let (image, _) = render(renderer(), &scene, None, options);
    glint_gpu::write_image(&image, &untiled, Bits::Eight).unwrap();
    assert!(std::fs::read(&streamed).unwrap() == std::fs::read(&untiled).unwrap(), "the files differ");
}

#[test]
fn progress_runs_over_the_whole_image_once() {
    let scene = showcase(40, 20);
    let tiled = renderer_with_tiles_of(150);
    let prepared = tiled.prepare(&scene, scene.width, scene.height, Acceleration::Bvh).unwrap();
    let options = RenderOptions { spp: 3, ..RenderOptions::default() };
    let mut calls = Vec::new();
    tiled.render(&prepared.buffers, &options, &mut |done, total| calls.push((done, total))).unwrap();
    assert!(calls.windows(2).all(|w| w[0].0 < w[1].0), "progress must only grow: {calls:?}");
    assert_eq!(calls.last(), Some(&(3 * 800, 3 * 800)));
    assert!(calls.iter().all(|&(_, total)| total == 3 * 800));
}

#[test]
fn a_region_has_the_pixels_of_the_whole_render() {
    let scene = showcase(48, 30);
    let region = Region { x0: 5, y0: 7, x1: 31, y1: 26 };
    let tiled = renderer_with_tiles_of(60);
    for options in every_view() {
        let (whole, _) = render(renderer(), &scene, None, options);
        for r in [renderer(), &tiled] {
            let (part, _) = render(r, &scene, Some(region), options);
            assert_eq!((part.width, part.height), (26, 19));
            for y in 0..part.height {
                for x in 0..part.width {
                    let (at_part, at_whole) = ((y * 26 + x) as usize, ((y + 7) * 48 + x + 5) as usize);
                    assert_eq!(part.linear[at_part], whole.linear[at_whole], "{:?} at ({x}, {y})", options.view);
                    assert_eq!(part.display[at_part], whole.display[at_whole], "{:?} at ({x}, {y})", options.view);
                }
            }
        }
    }
}

#[test]
fn a_region_outside_the_image_is_an_error() {
    let scene = showcase(20, 10);
    let prepared = renderer().prepare(&scene, 20, 10, Acceleration::Bvh).unwrap();
    for region in [Region { x0: 0, y0: 0, x1: 21, y1: 10 }, Region { x0: 5, y0: 5, x1: 5, y1: 8 }] {
        let e = renderer().render_region(&prepared.buffers, region, &RenderOptions::default(), &mut |_, _| {}).unwrap_err();
        assert!(e.to_string().contains("not inside the 20x10 image"), "{e}");
    }
}

#[test]
fn interactive_use_of_a_tiled_scene_is_refused_not_undefined() {
    let scene = showcase(20, 10);
    let tiled = renderer_with_tiles_of(50);
    let prepared = tiled.prepare(&scene, 20, 10, Acceleration::Bvh).unwrap();
    let e = tiled.pick(&prepared.buffers, 3, 3).unwrap_err().to_string();
    assert!(e.contains("too large for the device to hold at once"), "{e}");
    assert!(tiled.resolve(&prepared.buffers, &RenderOptions::default()).is_err());
}
