//! A procedural mesh: an icosahedron whose faces are subdivided into a
//! triangular grid and pushed onto a sphere, optionally displaced along the
//! radius by a smooth deterministic bump function. Gives scenes of any size
//! (20·4^s triangles for s subdivisions) without shipping a mesh file.

use glam::Vec3;

use crate::Shape;

/// The most subdivisions accepted: 20·4^10 ≈ 21 million triangles.
pub const MAX_SUBDIVISIONS: u32 = 10;

/// The triangles of an icosphere of `radius` at `center`, each face of the
/// icosahedron cut into 4^`subdivisions` triangles. `displacement` scales the
/// bumps as a fraction of the radius (0 gives a smooth sphere).
pub fn icosphere(center: Vec3, radius: f32, subdivisions: u32, displacement: f32) -> Vec<Shape> {
    let t = (1.0 + 5f32.sqrt()) / 2.0;
    let v = [
        Vec3::new(-1.0, t, 0.0), Vec3::new(1.0, t, 0.0), Vec3::new(-1.0, -t, 0.0), Vec3::new(1.0, -t, 0.0),
        Vec3::new(0.0, -1.0, t), Vec3::new(0.0, 1.0, t), Vec3::new(0.0, -1.0, -t), Vec3::new(0.0, 1.0, -t),
        Vec3::new(t, 0.0, -1.0), Vec3::new(t, 0.0, 1.0), Vec3::new(-t, 0.0, -1.0), Vec3::new(-t, 0.0, 1.0),
    ];
    const FACES: [[usize; 3]; 20] = [
        [0, 11, 5], [0, 5, 1], [0, 1, 7], [0, 7, 10], [0, 10, 11], [1, 5, 9], [5, 11, 4], [11, 10, 2], [10, 7, 6], [7, 1, 8],
        [3, 9, 4], [3, 4, 2], [3, 2, 6], [3, 6, 8], [3, 8, 9], [4, 9, 5], [2, 4, 11], [6, 2, 10], [8, 6, 7], [9, 8, 1],
    ];
    let n = 1usize << subdivisions.min(MAX_SUBDIVISIONS);
    // A point of the unit sphere, displaced and placed in the scene.
    let place = |p: Vec3| {
        let d = p.normalize();
        let bump = (7.0 * d.x).sin() * (9.0 * d.y).sin() * (11.0 * d.z).sin();
        center + d * radius * (1.0 + displacement * bump)
    };
    let mut shapes = Vec::with_capacity(20 * n * n);
    for face in FACES {
        let [a, b, c] = face.map(|i| v[i]);
        // Grid point (i, j) of the face, i + j ≤ n.
        let grid = |i: usize, j: usize| place(a + (b - a) * (i as f32 / n as f32) + (c - a) * (j as f32 / n as f32));
        for j in 0..n {
            for i in 0..n - j {
                shapes.push(Shape::Triangle { vertices: [grid(i, j), grid(i + 1, j), grid(i, j + 1)], normals: None });
                if i + j + 1 < n {
                    shapes.push(Shape::Triangle { vertices: [grid(i + 1, j), grid(i + 1, j + 1), grid(i, j + 1)], normals: None });
                }
            }
        }
    }
    shapes
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn triangle_count_is_twenty_times_four_to_the_subdivisions() {
        for s in 0..4 {
            assert_eq!(icosphere(Vec3::ZERO, 1.0, s, 0.0).len(), 20 * 4usize.pow(s));
        }
    }

    #[test]
    fn vertices_lie_on_the_sphere_within_the_displacement() {
        let center = Vec3::new(1.0, 2.0, 3.0);
        for (displacement, tolerance) in [(0.0, 1e-5), (0.1, 0.1 + 1e-5)] {
            for shape in icosphere(center, 2.0, 3, displacement) {
                let Shape::Triangle { vertices, .. } = shape else { panic!("only triangles") };
                for p in vertices {
                    assert!(((p - center).length() / 2.0 - 1.0).abs() <= tolerance);
                }
            }
        }
    }

    #[test]
    fn faces_point_outwards() {
        for shape in icosphere(Vec3::ZERO, 1.0, 2, 0.0) {
            let Shape::Triangle { vertices: [a, b, c], .. } = shape else { panic!("only triangles") };
            assert!((b - a).cross(c - a).dot(a + b + c) > 0.0);
        }
    }
}
