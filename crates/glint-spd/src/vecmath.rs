//! SPD's libvec: 4×4 matrices act on row vectors (`p' = p · M`, translation in
//! the last row). Every sum is written in libvec's order, so results match the
//! C generators bit for bit.

/// A point or colour, as SPD's `COORD3`.
pub type Vec3 = [f64; 3];
/// A point with a radius (spheres, cone ends) or a light with an intensity, as SPD's `COORD4`.
pub type Vec4 = [f64; 4];

pub type Matrix = [[f64; 4]; 4];

pub const IDENTITY: Matrix =
    [[1.0, 0.0, 0.0, 0.0], [0.0, 1.0, 0.0, 0.0], [0.0, 0.0, 1.0, 0.0], [0.0, 0.0, 0.0, 1.0]];

#[derive(Clone, Copy)]
pub enum Axis {
    X,
    Y,
    Z,
}

pub fn sub(a: Vec3, b: Vec3) -> Vec3 {
    [a[0] - b[0], a[1] - b[1], a[2] - b[2]]
}

pub fn dot(a: Vec3, b: Vec3) -> f64 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}

pub fn cross(a: Vec3, b: Vec3) -> Vec3 {
    [a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]]
}

pub fn length(v: Vec3) -> f64 {
    dot(v, v).sqrt()
}

/// `lib_normalize_vector`: a zero vector stays zero.
pub fn normalize(v: Vec3) -> Vec3 {
    let divisor = length(v);
    if divisor > 0.0 { [v[0] / divisor, v[1] / divisor, v[2] / divisor] } else { v }
}

/// `lib_create_rotate_matrix`: `angle` radians about a coordinate axis.
pub fn rotate(axis: Axis, angle: f64) -> Matrix {
    let (cosine, sine) = (angle.cos(), angle.sin());
    let mut m = [[0.0; 4]; 4];
    // The plane of rotation, ordered so that a positive angle turns `a` toward `b`.
    let (a, b) = match axis {
        Axis::X => (1, 2),
        Axis::Y => (2, 0),
        Axis::Z => (0, 1),
    };
    m[3 - a - b][3 - a - b] = 1.0;
    m[a][a] = cosine;
    m[b][b] = cosine;
    m[a][b] = sine;
    m[b][a] = -sine;
    m[3][3] = 1.0;
    m
}

/// `lib_create_axis_rotate_matrix`: `angle` radians about the unit vector `axis`.
pub fn rotate_about(axis: Vec3, angle: f64) -> Matrix {
    let [x, y, z] = axis;
    let (cosine, sine) = (angle.cos(), angle.sin());
    let one_minus_cosine = 1.0 - cosine;
    [
        [
            x * x + (1.0 - x * x) * cosine,
            x * y * one_minus_cosine + z * sine,
            x * z * one_minus_cosine - y * sine,
            0.0,
        ],
        [
            x * y * one_minus_cosine - z * sine,
            y * y + (1.0 - y * y) * cosine,
            y * z * one_minus_cosine + x * sine,
            0.0,
        ],
        [
            x * z * one_minus_cosine + y * sine,
            y * z * one_minus_cosine - x * sine,
            z * z + (1.0 - z * z) * cosine,
            0.0,
        ],
        [0.0, 0.0, 0.0, 1.0],
    ]
}

pub fn scale(factors: Vec3) -> Matrix {
    let mut m = [[0.0; 4]; 4];
    for (i, f) in factors.into_iter().enumerate() {
        m[i][i] = f;
    }
    m[3][3] = 1.0;
    m
}

pub fn translate(offset: Vec3) -> Matrix {
    let mut m = IDENTITY;
    m[3][..3].copy_from_slice(&offset);
    m
}

/// `a · b`: `a` applies first.
pub fn multiply(a: &Matrix, b: &Matrix) -> Matrix {
    std::array::from_fn(|i| {
        std::array::from_fn(|j| a[i][0] * b[0][j] + a[i][1] * b[1][j] + a[i][2] * b[2][j] + a[i][3] * b[3][j])
    })
}

/// `lib_transform_point`: `p` with an implicit w of 1.
pub fn transform_point(p: Vec3, m: &Matrix) -> Vec3 {
    std::array::from_fn(|j| p[0] * m[0][j] + p[1] * m[1][j] + p[2] * m[2][j] + m[3][j])
}

/// `lib_transform_coord`: a homogeneous 4-vector.
pub fn transform_coord(p: Vec4, m: &Matrix) -> Vec4 {
    std::array::from_fn(|j| p[0] * m[0][j] + p[1] * m[1][j] + p[2] * m[2][j] + p[3] * m[3][j])
}
