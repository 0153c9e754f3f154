//! The bundled scene as constant data: a floor quad and a table (a top and
//! four legs, each a box), one mesh in world space, and the light's and
//! camera's matrices.

use umbra_core::glam::{Mat4, Vec3};
use umbra_core::shade::SceneTriangle;

/// Boxes in the scene: the table top and four legs.
const BOXES: usize = 5;
/// Vertices: 4 for the floor, 8 per box.
pub const VERTICES: usize = 4 + 8 * BOXES;
/// Triangles: 2 for the floor, 12 per box.
pub const TRIANGLES: usize = 2 + 12 * BOXES;

/// The boxes' corners `(min, max)`: the top, then the legs.
const BOX_BOUNDS: [([f32; 3], [f32; 3]); BOXES] = [
    ([-0.55, 0.50, -0.40], [0.55, 0.58, 0.40]),
    ([-0.50, 0.0, -0.35], [-0.42, 0.50, -0.27]),
    ([0.42, 0.0, -0.35], [0.50, 0.50, -0.27]),
    ([-0.50, 0.0, 0.27], [-0.42, 0.50, 0.35]),
    ([0.42, 0.0, 0.27], [0.50, 0.50, 0.35]),
];

/// The floor's half side; it lies in `y = 0`.
const FLOOR: f32 = 1.0;

/// A box's faces over its corners numbered `x + 2y + 4z` (bit set = max
/// side), counter-clockwise seen from outside.
const BOX_FACES: [[u32; 3]; 12] = [
    [0, 4, 6],
    [0, 6, 2],
    [1, 3, 7],
    [1, 7, 5],
    [0, 1, 5],
    [0, 5, 4],
    [2, 6, 7],
    [2, 7, 3],
    [0, 2, 3],
    [0, 3, 1],
    [4, 5, 7],
    [4, 7, 6],
];

const fn build_positions() -> [Vec3; VERTICES] {
    let mut p = [Vec3::ZERO; VERTICES];
    p[0] = Vec3::new(-FLOOR, 0.0, -FLOOR);
    p[1] = Vec3::new(FLOOR, 0.0, -FLOOR);
    p[2] = Vec3::new(FLOOR, 0.0, FLOOR);
    p[3] = Vec3::new(-FLOOR, 0.0, FLOOR);
    let mut b = 0;
    while b < BOXES {
        let (lo, hi) = BOX_BOUNDS[b];
        let mut c = 0;
        while c < 8 {
            let x = if c & 1 == 0 { lo[0] } else { hi[0] };
            let y = if c & 2 == 0 { lo[1] } else { hi[1] };
            let z = if c & 4 == 0 { lo[2] } else { hi[2] };
            p[4 + 8 * b + c] = Vec3::new(x, y, z);
            c += 1;
        }
        b += 1;
    }
    p
}

const fn build_triangles() -> [[u32; 3]; TRIANGLES] {
    let mut t = [[0; 3]; TRIANGLES];
    // The floor faces up (+y).
    t[0] = [0, 3, 2];
    t[1] = [0, 2, 1];
    let mut b = 0;
    while b < BOXES {
        let mut f = 0;
        while f < 12 {
            #[allow(clippy::cast_possible_truncation, reason = "at most 44 vertices")]
            let base = (4 + 8 * b) as u32;
            let [i, j, k] = BOX_FACES[f];
            t[2 + 12 * b + f] = [base + i, base + j, base + k];
            f += 1;
        }
        b += 1;
    }
    t
}

/// World-space vertex positions.
pub const POSITIONS: [Vec3; VERTICES] = build_positions();

/// Vertex indices, three per triangle, counter-clockwise seen from outside.
/// A triangle's id in the passes is its index here.
pub const INDICES: [[u32; 3]; TRIANGLES] = build_triangles();

/// Where the spot light is and what it looks at.
pub const LIGHT_EYE: Vec3 = Vec3::new(0.9, 2.4, 1.3);
/// Where the camera is.
pub const CAMERA_EYE: Vec3 = Vec3::new(-0.4, 1.5, 2.4);
/// The point both look at.
pub const TARGET: Vec3 = Vec3::new(0.0, 0.2, 0.0);

/// World to light clip space: a spot light at [`LIGHT_EYE`] looking at
/// [`TARGET`], 55° field of view, near 1, far 5 (D3D depth `[0, 1]`, y up,
/// right-handed, square aspect). Stored as the f32 bits glam's `look_at`
/// and `perspective` give (a test checks them), so that a firmware carries
/// no trigonometry.
pub const LIGHT_MATRIX: Mat4 = Mat4::from_cols_array(&[
    1.579_416_5,
    -0.887_913_1,
    -0.415_245_03,
    -0.332_196_03,
    0.0,
    1.121_102_3,
    -1.015_043_5,
    -0.812_034_8,
    -1.093_442_2,
    -1.282_541_2,
    -0.599_798_4,
    -0.479_838_7,
    0.0,
    -0.224_220_51,
    2.339_563,
    2.871_650_2,
]);

/// World to camera clip space: the camera at [`CAMERA_EYE`] looking at
/// [`TARGET`], 38° field of view, near 0.5, far 6, as [`LIGHT_MATRIX`].
pub const CAMERA_MATRIX: Mat4 = Mat4::from_cols_array(&[
    2.864_696,
    0.224_997_82,
    0.158_181_7,
    0.144_999_89,
    0.0,
    2.561_513_7,
    -0.514_090_5,
    -0.471_249_6,
    0.477_449_33,
    -1.349_986_9,
    -0.949_090_24,
    -0.869_999_35,
    0.0,
    -0.512_302_7,
    2.566_770_8,
    2.852_873,
]);

/// World to light clip space ([`LIGHT_MATRIX`]).
#[must_use]
pub const fn light_matrix() -> Mat4 {
    LIGHT_MATRIX
}

/// World to camera clip space ([`CAMERA_MATRIX`]).
#[must_use]
pub const fn camera_matrix() -> Mat4 {
    CAMERA_MATRIX
}

/// The triangle with id `id`, with its face normal at every vertex.
#[must_use]
pub fn triangle(id: u32) -> Option<SceneTriangle> {
    let [a, b, c] = INDICES.get(id as usize)?.map(|i| POSITIONS.get(i as usize).copied());
    let positions = [a?, b?, c?];
    let n = (positions[1] - positions[0]).cross(positions[2] - positions[0]);
    Some(SceneTriangle { positions, normals: [n; 3] })
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Every face's normal points away from its box's centre (the floor's up).
    #[test]
    fn faces_wind_outwards() {
        for (t, tri) in INDICES.iter().enumerate() {
            let [a, b, c] = tri.map(|i| POSITIONS[i as usize]);
            let n = (b - a).cross(c - a);
            let centre = if t < 2 {
                Vec3::new(0.0, -1.0, 0.0)
            } else {
                let (lo, hi) = BOX_BOUNDS[(t - 2) / 12];
                (Vec3::from_array(lo) + Vec3::from_array(hi)) / 2.0
            };
            assert!(n.dot((a + b + c) / 3.0 - centre) > 0.0, "triangle {t} winds inwards");
        }
    }

    /// The stored matrices are the views they are documented as, bit for
    /// bit: glam's `look_at` and D3D `perspective` from the eyes, target,
    /// fields of view and planes named.
    #[test]
    fn the_matrices_are_the_named_views() {
        use umbra_core::glam::camera::rh::{proj::directx::perspective, view::look_at_mat4};
        let view = |eye: Vec3, fov: f32, near: f32, far: f32| {
            perspective(fov.to_radians(), 1.0, near, far) * look_at_mat4(eye, TARGET, Vec3::Y)
        };
        let bits = |m: Mat4| m.to_cols_array().map(f32::to_bits);
        assert_eq!(bits(LIGHT_MATRIX), bits(view(LIGHT_EYE, 55.0, 1.0, 5.0)));
        assert_eq!(bits(CAMERA_MATRIX), bits(view(CAMERA_EYE, 38.0, 0.5, 6.0)));
    }

    #[test]
    fn every_index_names_a_vertex() {
        assert!(INDICES.iter().flatten().all(|&i| (i as usize) < VERTICES));
        assert_eq!(POSITIONS[4 + 7], Vec3::new(0.55, 0.58, 0.40));
    }
}
