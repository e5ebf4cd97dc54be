//! Large polygons cut into sectors for the kernels. The polygon test walks
//! every edge, so a gear face of 144 vertices costs a ray that reaches its box
//! 145 steps; cut at its centre into sectors of a few edges each, the BVH
//! leads a ray to the one or two it can hit (SPD gears: primary rays 2.2×,
//! Whitted frames 1.8× faster, the image unchanged).
//!
//! Only polygons star-shaped from their vertex centroid are cut: every edge
//! then turns the same way around the centre and goes round it once, so the
//! sectors tile the polygon exactly. Neighbouring sectors share the edge from
//! the centre to a vertex, the very same numbers in both, which the crossing
//! test's tie rule gives to exactly one of them: no ray slips between. Other
//! polygons stay whole.

use std::borrow::Cow;
use std::f64::consts::TAU;

use glam::{DVec3, Vec3};

use crate::shape::polygon_normal;
use crate::{Scene, Shape};

/// Polygons with more vertices than this are cut.
pub const MAX_WHOLE: usize = 16;
/// Edges of the polygon's outline in each sector (the last may have fewer).
pub const SECTOR_EDGES: usize = 8;

/// `scene` with its large star-shaped polygons cut into sectors, each in its
/// polygon's object; borrowed when there are none.
pub fn split_large_polygons(scene: &Scene) -> Cow<'_, Scene> {
    let large = |s: &Shape| matches!(s, Shape::Polygon { vertices } if vertices.len() > MAX_WHOLE);
    if !scene.objects.iter().flat_map(|o| &o.shapes).any(large) {
        return Cow::Borrowed(scene);
    }
    let mut split = scene.clone();
    for object in &mut split.objects {
        object.shapes = object
            .shapes
            .drain(..)
            .flat_map(|shape| match &shape {
                Shape::Polygon { vertices } if vertices.len() > MAX_WHOLE => match sectors(vertices) {
                    Some(pieces) => pieces.into_iter().map(|vertices| Shape::Polygon { vertices }).collect(),
                    None => vec![shape],
                },
                _ => vec![shape],
            })
            .collect();
    }
    Cow::Owned(split)
}

/// The sectors of `vertices` around their centroid, each its stretch of the
/// outline (in order, so it winds as the polygon does, its first vertex one of the polygon's)
/// closed through the centre; `None` when the polygon is not star-shaped from
/// the centroid.
pub fn sectors(vertices: &[Vec3]) -> Option<Vec<Vec<Vec3>>> {
    let n = vertices.len();
    let normal = polygon_normal(vertices)?.as_dvec3();
    let centre = (vertices.iter().map(|v| v.as_dvec3()).sum::<DVec3>() / n as f64).as_vec3();
    let c = centre.as_dvec3();
    let mut turned = 0.0;
    for (i, a) in vertices.iter().enumerate() {
        let (a, b) = (a.as_dvec3() - c, vertices[(i + 1) % n].as_dvec3() - c);
        let (sin, cos) = (a.cross(b).dot(normal), a.dot(b));
        // Clearly to the left, not within rounding of the centre's line.
        if sin <= 1e-6 * a.length() * b.length() {
            return None;
        }
        turned += sin.atan2(cos);
    }
    // Once round the centre, not twice (a self-crossing outline).
    if (turned - TAU).abs() > 1e-3 {
        return None;
    }
    let pieces = (0..n)
        .step_by(SECTOR_EDGES)
        .map(|start| {
            let end = (start + SECTOR_EDGES).min(n);
            let mut piece: Vec<Vec3> = (start..=end).map(|i| vertices[i % n]).collect();
            piece.push(centre);
            piece
        })
        .collect();
    Some(pieces)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A gear's face: `teeth` teeth of two vertices out, two in.
    fn gear(teeth: usize) -> Vec<Vec3> {
        (0..4 * teeth)
            .map(|i| {
                let angle = i as f32 / (4 * teeth) as f32 * std::f32::consts::TAU;
                let r = if i % 4 < 2 { 1.1 } else { 1.0 };
                Vec3::new(3.0 + r * angle.cos(), 2.0 + r * angle.sin(), 0.5)
            })
            .collect()
    }

    /// Twice the signed area of an outline in the z = const plane.
    fn area2(vertices: &[Vec3]) -> f64 {
        (0..vertices.len())
            .map(|i| {
                let (a, b) = (vertices[i].as_dvec3(), vertices[(i + 1) % vertices.len()].as_dvec3());
                a.x * b.y - a.y * b.x
            })
            .sum()
    }

    #[test]
    fn a_gear_face_becomes_sectors_that_tile_it() {
        let face = gear(36);
        let pieces = sectors(&face).expect("a gear face is star-shaped from its centre");
        assert_eq!(pieces.len(), 144 / SECTOR_EDGES);
        let centre = *pieces[0].last().unwrap();
        for (k, piece) in pieces.iter().enumerate() {
            assert_eq!(piece.len(), SECTOR_EDGES + 2);
            assert_eq!(&piece[..SECTOR_EDGES + 1], (0..=SECTOR_EDGES).map(|i| face[(k * SECTOR_EDGES + i) % 144]).collect::<Vec<_>>());
            assert_eq!(*piece.last().unwrap(), centre, "every sector closes through the same centre");
            assert!(area2(piece) > 0.0, "each sector winds as the face does");
        }
        let total: f64 = pieces.iter().map(|p| area2(p)).sum();
        assert!((total - area2(&face)).abs() < 1e-5 * area2(&face), "{total} vs {}", area2(&face));
    }

    #[test]
    fn outlines_not_star_shaped_from_the_centroid_stay_whole() {
        // A C shape: its centroid lies in the gap.
        let mut c: Vec<Vec3> = (0..=12).map(|i| Vec3::new((i as f32 * 0.4).cos() * 2.0, (i as f32 * 0.4).sin() * 2.0, 0.0)).collect();
        c.extend((0..=12).rev().map(|i| Vec3::new((i as f32 * 0.4).cos(), (i as f32 * 0.4).sin(), 0.0)));
        assert_eq!(sectors(&c), None);
        // A star polygon drawn as one line round the centre twice.
        let twice: Vec<Vec3> = (0..17).map(|i| Vec3::new((i as f32 * 4.0 * std::f32::consts::PI / 17.0).cos(), (i as f32 * 4.0 * std::f32::consts::PI / 17.0).sin(), 0.0)).collect();
        assert_eq!(sectors(&twice), None);
    }

    #[test]
    fn only_large_polygons_are_cut_each_in_its_object() {
        let nff = |faces: &[Vec<Vec3>]| {
            let mut text = String::from("v\nfrom 3 2 6\nat 3 2 0\nup 0 1 0\nangle 45\nhither 0.01\nresolution 8 8\nf 1 0 0 1 0 1 0 0\n");
            for face in faces {
                text += &format!("p {}\n", face.len());
                text.extend(face.iter().map(|v| format!("{} {} {}\n", v.x, v.y, v.z)));
            }
            crate::nff::parse(&text, std::path::Path::new("gears.nff"), &Default::default()).unwrap()
        };
        let small = nff(&[gear(4)]);
        assert!(matches!(split_large_polygons(&small), Cow::Borrowed(_)), "16 vertices stay whole");
        let scene = nff(&[gear(4), gear(36)]);
        let split = split_large_polygons(&scene);
        assert_eq!(split.objects.len(), 2);
        assert_eq!(split.objects[0], scene.objects[0]);
        assert_eq!(split.objects[1].shapes.len(), 144 / SECTOR_EDGES);
        assert_eq!(split.objects[1].material, scene.objects[1].material);
    }
}
