//! The oracle: what a case may end in. An error must name a file of the case
//! and a place inside it; a scene must be one the renderer can take, and the
//! host half of rendering must run on it.

use std::path::{Path, PathBuf};
use std::sync::atomic::Ordering;

use glam::Vec3;
use glint_encoding::gpu_bvh::GpuBvh;
use glint_encoding::gpu_types::{
    pack, primitive_bounds, scene_uniforms, GpuScene, BVH_STACK, LEAF, PRIM_PLANE, PRIM_POLYGON, PRIM_TRIANGLE,
    RIGHT_LEAF,
};
use glint_scene::bvh::Bvh;
use glint_scene::{MAX_DEPTH_LIMIT, MAX_IMAGE_SIDE};
use glint_scene::{Attenuation, LightKind, LoadError, Projection, Scene, Shape};
use proptest::prelude::*;
use proptest::test_runner::TestCaseError;

use crate::mutate::line_spans;
use crate::Tally;

/// A file of the case: its path and bytes, for checking the places errors name.
pub(crate) struct CaseFile {
    pub(crate) path: PathBuf,
    pub(crate) bytes: Vec<u8>,
}

pub(crate) fn write_case(dir: &Path, name: &str, bytes: &[u8]) -> CaseFile {
    let path = dir.join(name);
    std::fs::write(&path, bytes).expect("the case directory is writable");
    CaseFile { path, bytes: bytes.to_vec() }
}

/// An error must name a file of the case, a line inside it and, when it has
/// one, a column inside that line, and it must print as one line.
pub(crate) fn check_error(e: &LoadError, files: &[&CaseFile]) -> Result<(), TestCaseError> {
    let shown = e.to_string();
    prop_assert!(!shown.contains(['\n', '\r']), "the message is not one line: {shown:?}");
    prop_assert!(!e.message.trim().is_empty(), "no message: {shown:?}");
    let file = files.iter().find(|f| f.path == e.path);
    prop_assert!(file.is_some(), "the error names a file that is not part of the case: {shown}");
    let file = file.unwrap();
    let Some(location) = e.location else {
        return Err(TestCaseError::fail(format!("the error names no line: {shown}")));
    };
    prop_assert!(
        shown.starts_with(&format!("{}:{}", e.path.display(), location.line)),
        "the message does not start with file:line: {shown}"
    );
    let lines = line_spans(&file.bytes);
    prop_assert!(
        location.line >= 1 && location.line <= lines.len().max(1) + 1,
        "line {} outside the file's {} lines: {shown}",
        location.line,
        lines.len()
    );
    if let Some(column) = location.column {
        let text = lines.get(location.line - 1).map_or(&[][..], |&(s, e)| &file.bytes[s..e]);
        let chars = String::from_utf8_lossy(text).chars().count();
        prop_assert!(column >= 1 && column <= chars + 1, "column {column} outside a line of {chars} characters: {shown}");
    }
    Ok(())
}

pub(crate) fn finite_non_negative(v: Vec3) -> bool {
    v.is_finite() && v.min_element() >= 0.0
}

/// A loaded scene must be one the renderer can take as it is.
pub(crate) fn check_scene(scene: &Scene) -> Result<(), TestCaseError> {
    prop_assert!((1..=MAX_IMAGE_SIDE).contains(&scene.width) && (1..=MAX_IMAGE_SIDE).contains(&scene.height));
    let camera = &scene.camera;
    prop_assert!(camera.eye.is_finite() && camera.look_at.is_finite() && camera.up.is_finite(), "{camera:?}");
    let basis = camera.basis();
    prop_assert!(
        basis.is_some_and(|b| b.u.is_finite() && b.v.is_finite() && b.w.is_finite()),
        "the camera has no usable basis: {camera:?}"
    );
    match camera.projection {
        Projection::Perspective { fov_y_degrees } => prop_assert!(fov_y_degrees > 0.0 && fov_y_degrees < 180.0, "{camera:?}"),
        Projection::Orthographic { height } => prop_assert!(height > 0.0 && height.is_finite(), "{camera:?}"),
    }
    prop_assert!(finite_non_negative(scene.background) && finite_non_negative(scene.ambient), "{:?} {:?}", scene.background, scene.ambient);
    let r = &scene.render;
    prop_assert!((1..=MAX_DEPTH_LIMIT).contains(&r.max_depth) && (0.0..=1.0).contains(&r.cutoff), "{r:?}");
    if let Some(d) = &scene.depth_cue {
        prop_assert!(finite_non_negative(d.color) && d.near.is_finite() && d.far.is_finite() && d.far > d.near, "{d:?}");
        prop_assert!((0.0..=1.0).contains(&d.near_scale) && (0.0..=1.0).contains(&d.far_scale), "{d:?}");
    }
    for light in &scene.lights {
        match light.kind {
            LightKind::Point { position } => prop_assert!(position.is_finite(), "{light:?}"),
            LightKind::Directional { direction } => {
                prop_assert!(direction.is_finite() && (direction.length() - 1.0).abs() < 1e-4, "{light:?}")
            }
        }
        prop_assert!(finite_non_negative(light.radiance()), "the light's radiance is not finite: {light:?}");
        if let Attenuation::Polynomial { c1, c2, c3 } = light.attenuation {
            prop_assert!(finite_non_negative(Vec3::new(c1, c2, c3)) && c1 + c2 + c3 > 0.0, "{light:?}");
        }
    }
    prop_assert!(!scene.materials.is_empty(), "no materials");
    for m in &scene.materials {
        let scalars = [m.ambient, m.diffuse, m.specular, m.shininess];
        prop_assert!(scalars.iter().all(|v| v.is_finite() && *v >= 0.0), "{m:?}");
        prop_assert!(m.ior.is_finite() && m.ior > 0.0, "{m:?}");
        let checker = m.checker.map(|c| c.color);
        let colours = [Some(m.color), m.specular_color, m.metallic_f0, Some(m.reflect), Some(m.transmit), checker];
        prop_assert!(colours.iter().flatten().all(|c| finite_non_negative(*c)), "{m:?}");
        prop_assert!(m.checker.is_none_or(|c| c.size.is_finite() && c.size > 0.0), "{m:?}");
    }
    for object in &scene.objects {
        prop_assert!(object.material < scene.materials.len(), "material {} of {}", object.material, scene.materials.len());
        prop_assert!(!object.shapes.is_empty(), "an object without shapes");
        for shape in &object.shapes {
            // The shape policy, by the shape's own check: no degenerate shape
            // kept, no bounds (or plane offset) beyond f32.
            prop_assert!(shape.problem().is_none(), "{:?}: {shape:?}", shape.problem());
            prop_assert!(shape.bounds().is_none_or(|(lo, hi)| lo.cmple(hi).all()), "inside-out bounds: {shape:?}");
            if let Shape::Triangle { normals: Some(ns), .. } = shape {
                prop_assert!(ns.iter().all(|n| n.is_finite() && (n.length() - 1.0).abs() < 1e-3), "{shape:?}");
            }
        }
    }
    // The host half of rendering: none of it may panic on what a loader
    // accepted, and what it uploads keeps every index the kernels follow
    // inside its array.
    prop_assert!(scene.validate().is_ok(), "a loaded scene fails validation: {:?}", scene.validate());
    let bvh = Bvh::build(&primitive_bounds(scene));
    let gpu_bvh = GpuBvh::encode(&bvh).map_err(|e| TestCaseError::fail(e.to_string()))?;
    let packed = pack(scene, &bvh.order, gpu_bvh);
    check_indices(&packed)?;
    check_planes(&packed, packed.planes, scene.primitive_count())?;
    let g = scene_uniforms(scene, scene.width, scene.height, packed.light_count, packed.layout());
    let camera_values = [g.camera.u, g.camera.v, g.camera.w].concat();
    prop_assert!(
        camera_values.iter().chain([&g.camera.half_width, &g.camera.half_height]).all(|v| v.is_finite()),
        "the packed camera is not finite: {:?}",
        g.camera
    );
    Ok(())
}

pub(crate) fn check_outcome(outcome: Result<Scene, LoadError>, files: &[&CaseFile], tally: &Tally) -> Result<(), TestCaseError> {
    match outcome {
        Err(e) => {
            tally.errors.fetch_add(1, Ordering::Relaxed);
            check_error(&e, files)
        }
        Ok(scene) => {
            tally.scenes.fetch_add(1, Ordering::Relaxed);
            check_scene(&scene)
        }
    }
}

/// The infinite planes, which every ray tests beside the BVH, are where the
/// uniforms say: all the planes of the scene's `primitives`, and nothing
/// else, at the end of the packed primitives, with materials in range.
pub(crate) fn check_planes(scene: &GpuScene, (first, count): (u32, u32), primitives: usize) -> Result<(), TestCaseError> {
    let (first, count) = (first as usize, count as usize);
    prop_assert!(first + count == primitives && primitives <= scene.prims.len(), "planes {first}+{count} of {primitives} primitives");
    for (i, p) in scene.prims[..primitives].iter().enumerate() {
        let (kind, material) = (p.kind_material & 0xff, (p.kind_material >> 8) as usize);
        prop_assert_eq!(kind == PRIM_PLANE, i >= first, "primitive {} is of kind {}; planes start at {}", i, kind, first);
        prop_assert!(material < scene.materials.len(), "material {material} of {}", scene.materials.len());
    }
    Ok(())
}

/// Walks every BVH record reachable from the root, as any traversal might
/// (the kernel's stack holds each level's far child: never deeper than
/// `BVH_STACK`), and checks each index the kernels read: child records, leaf
/// primitive ranges, materials, polygon vertices and vertex normals.
pub(crate) fn check_indices(scene: &GpuScene) -> Result<(), TestCaseError> {
    let mut pending = vec![(scene.bvh_root, 0usize)];
    while let Some((reference, depth)) = pending.pop() {
        prop_assert!(depth <= BVH_STACK as usize, "a path {depth} deep overflows the traversal stack");
        let record = (reference & !LEAF) as usize;
        prop_assert!(record < scene.nodes.len(), "record {record} of {}", scene.nodes.len());
        let node = scene.nodes[record];
        if reference & LEAF != 0 {
            let (first, count) = (node.quantized[0] as usize, node.quantized[1] as usize);
            prop_assert!(first + count <= scene.prims.len(), "leaf {first}+{count} of {} primitives", scene.prims.len());
            for p in &scene.prims[first..first + count] {
                let (kind, material) = (p.kind_material & 0xff, (p.kind_material >> 8) as usize);
                prop_assert!(material < scene.materials.len(), "material {material} of {}", scene.materials.len());
                let points = p.first as usize + p.count as usize;
                if kind == PRIM_POLYGON {
                    prop_assert!(p.count >= 3 && points <= scene.points.len(), "polygon {}+{} of {} points", p.first, p.count, scene.points.len());
                }
                if kind == PRIM_TRIANGLE && p.count == 3 {
                    prop_assert!(points <= scene.points.len(), "normals {}+3 of {} points", p.first, scene.points.len());
                }
            }
        } else {
            let first = node.children & !(LEAF | RIGHT_LEAF);
            for (child, leaf_flag) in [(first, LEAF), (first + 1, RIGHT_LEAF)] {
                let is_leaf = node.children & leaf_flag != 0;
                pending.push((child | if is_leaf { LEAF } else { 0 }, depth + 1));
            }
        }
    }
    prop_assert!(!scene.materials.is_empty() && !scene.lights.is_empty() && !scene.points.is_empty(), "an empty binding");
    Ok(())
}
