//! Rayshade scenes on the GPU: SPD's `.ray` files trace the same depth,
//! normal and id AOVs as their NFF twins, and a `.ray` surface shades by
//! Rayshade's equations (docs/scene-format.md, Rayshade).

mod support;

use std::path::Path;

use glam::DVec3;
use glint_encoding::gpu_types::View;
use glint_gpu::{Acceleration, RenderOptions};
use glint_scene::nff::{NffAngle, NffOptions};
use glint_scene::spd::{database, Format, CLASSIC};
use glint_scene::Scene;
use support::{assert_close, assert_images_equal, render_options};

fn ray(text: &str) -> Scene {
    glint_scene::rayshade::parse(text, Path::new("inline.ray")).unwrap_or_else(|e| panic!("{e}"))
}

fn view(scene: &Scene, view: View) -> Vec<[f32; 4]> {
    render_options(scene, Acceleration::Bvh, RenderOptions { view, ..RenderOptions::default() }).0.linear
}

/// Each classic database at sizes 1 to 3, generated both ways by `glint spd`
/// and rendered at 64 × 64: the `.ray` scene (its `fov` edge to edge) and the
/// `.nff` scene read edge to edge see the same surfaces at every pixel.
#[test]
fn spd_rayshade_scenes_trace_the_aovs_of_their_nff_twins() {
    for name in CLASSIC {
        let db = database(name).unwrap();
        for size in 1..=3 {
            let what = format!("{name} size {size}");
            let mut from_ray = ray(&db.generate_as(Some(size), Format::Rayshade).unwrap());
            let nff_text = db.generate(Some(size)).unwrap();
            let options = NffOptions { angle: NffAngle::Edges };
            let mut from_nff = glint_scene::nff::parse(&nff_text, Path::new("spd.nff"), &options).unwrap();
            for scene in [&mut from_ray, &mut from_nff] {
                (scene.width, scene.height) = (64, 64);
            }
            for v in [View::Depth, View::Normal, View::Id] {
                assert_images_equal(&view(&from_ray, v), &view(&from_nff, v), 0, &format!("{what}, {v:?}"));
            }
        }
    }
}

/// A square facing the camera at z = 0, seen from z = 10 through the image
/// centre, under `lights`, with `surface` named `s`.
fn facing_square(lights: &str, surface: &str) -> Scene {
    ray(&format!(
        "screen 9 9\neyep 0 0 10\nlookp 0 0 0\nup 0 1 0\nfov 20\nbackground 1 0.5 0.25\n{lights}\nsurface s\n{surface}\n\
         polygon s -50 -50 0 50 -50 0 50 50 0 -50 50 0\n"
    ))
}

fn centre(scene: &Scene) -> [f32; 3] {
    render_options(scene, Acceleration::Bvh, RenderOptions::default()).0.linear_at(4, 4)
}

/// ambient·I_a + I·(diffuse·(N·L) + specular·(R·L)^specpow), with R the eye
/// ray's mirror direction: at the centre N = V = +z, and a light at (4, 0, 3)
/// gives N·L = R·L = 0.6.
#[test]
fn ray_surfaces_shade_by_rayshades_equation() {
    let (a, d, s) = (DVec3::new(0.2, 0.1, 0.05), DVec3::new(0.4, 0.2, 0.1), DVec3::new(0.3, 0.6, 0.9));
    let scene = facing_square(
        "light 0.8 point 4 0 3\nlight 0.1 ambient",
        "ambient 0.2 0.1 0.05\ndiffuse 0.4 0.2 0.1\nspecular 0.3 0.6 0.9\nspecpow 5",
    );
    let want = a * 0.1 + (d * 0.6 + s * 0.6f64.powi(5)) * 0.8;
    assert_close(centre(&scene), want.to_array(), 1e-4, "ambient, diffuse and highlight");
}

/// Without `light … ambient` the ambient light is white with intensity 1; a
/// surface with only an ambient colour shows it as it is.
#[test]
fn the_default_ambient_light_is_one() {
    let scene = facing_square("light 1 point 0 0 10", "ambient 0.3 0.2 0.1");
    assert_close(centre(&scene), [0.3, 0.2, 0.1], 1e-5, "ambient × 1");
}

/// `reflect` scales the specular colour into the mirror's weight, and a
/// `specpow` of 0 (as SPD writes for a mirror without highlights) leaves no
/// highlight, though the light shines straight back along the mirror ray.
#[test]
fn reflection_is_reflect_times_specular_and_specpow_zero_has_no_highlight() {
    let scene = facing_square("light 1 point 0 0 10", "specular 0.5 0.5 0.5\nspecpow 0\nreflect 0.5");
    // The mirror ray goes back past the eye and finds the background.
    assert_close(centre(&scene), [0.25, 0.125, 0.0625], 1e-5, "0.25 × background");
}

/// `transp` times `body` weighs the transmitted ray; with `index 1` it goes
/// straight on to the background.
#[test]
fn transmission_is_transp_times_body() {
    let scene = facing_square("light 1 point 0 0 10", "transp 0.5\nbody 1 0.5 0.5\nindex 1");
    assert_close(centre(&scene), [0.5, 0.125, 0.0625], 1e-5, "0.5 × body × background");
}
