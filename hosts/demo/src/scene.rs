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
const LIGHT_EYE: Vec3 = Vec3::new(0.9, 2.4, 1.3);
/// Where the camera is.
const CAMERA_EYE: Vec3 = Vec3::new(-0.4, 1.5, 2.4);
/// The point both look at.
const TARGET: Vec3 = Vec3::new(0.0, 0.2, 0.0);

/// A perspective view-projection (D3D depth `[0, 1]`, y up, right-handed),
/// square aspect.
fn view_projection(eye: Vec3, fov_degrees: f32, near: f32, far: f32) -> Mat4 {
    let view = umbra_core::glam::camera::rh::view::look_at_mat4(eye, TARGET, Vec3::Y);
    let proj = umbra_core::glam::camera::rh::proj::directx::perspective(fov_degrees.to_radians(), 1.0, near, far);
    proj * view
}

/// World to light clip space: a spot light above and to the side.
#[must_use]
pub fn light_matrix() -> Mat4 {
    view_projection(LIGHT_EYE, 55.0, 1.0, 5.0)
}

/// World to camera clip space.
#[must_use]
pub fn camera_matrix() -> Mat4 {
    view_projection(CAMERA_EYE, 38.0, 0.5, 6.0)
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

    #[test]
    fn every_index_names_a_vertex() {
        assert!(INDICES.iter().flatten().all(|&i| (i as usize) < VERTICES));
        assert_eq!(POSITIONS[4 + 7], Vec3::new(0.55, 0.58, 0.40));
    }
}
