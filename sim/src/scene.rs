//! Scenes: objects in world space and a light.

use glam::{Mat4, Vec3};
use umbra_core::CullMode;

use crate::light::Draw;
use crate::mesh::Mesh;

/// A mesh placed in the world.
#[derive(Clone, Debug, PartialEq)]
pub struct Object {
    /// A name for reports.
    pub name: String,
    /// World-space mesh.
    pub mesh: Mesh,
    /// A closed, consistently wound surface (may be back- or front-face culled).
    pub solid: bool,
}

/// A perspective spot light.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SpotLight {
    /// Where the light is.
    pub position: Vec3,
    /// The point it looks at.
    pub target: Vec3,
    /// Vertical (and horizontal) field of view, degrees.
    pub fov_degrees: f32,
    /// Near plane distance.
    pub near: f32,
    /// Far plane distance.
    pub far: f32,
}

impl SpotLight {
    /// World space to light clip space (depth `[0, 1]`, y up, right-handed).
    #[must_use]
    pub fn view_projection(&self) -> Mat4 {
        let dir = (self.target - self.position).normalize_or(Vec3::NEG_Y);
        let up = if dir.cross(Vec3::Y).length_squared() < 1e-6 { Vec3::Z } else { Vec3::Y };
        let view = glam::camera::rh::view::look_at_mat4(self.position, self.target, up);
        let proj =
            glam::camera::rh::proj::directx::perspective(self.fov_degrees.to_radians(), 1.0, self.near, self.far);
        proj * view
    }
}

/// Objects and a light.
#[derive(Clone, Debug, PartialEq)]
pub struct Scene {
    /// A name for reports.
    pub name: String,
    /// The objects.
    pub objects: Vec<Object>,
    /// The light.
    pub light: SpotLight,
}

impl Scene {
    /// The bundled default: Wang & Molnar's table on a floor (legs touching
    /// the floor, the case no bias fixes), with a sphere beside it, lit by a
    /// spot light from above.
    #[must_use]
    pub fn default_scene() -> Self {
        let floor = Mesh::cuboid(Vec3::new(-4.0, -0.1, -4.0), Vec3::new(4.0, 0.0, 4.0));
        let table = Mesh::table(2.0, 1.2, 1.0, 0.08, 0.1);
        let sphere = Mesh::sphere(Vec3::new(2.0, 0.6, 1.2), 0.6, 24, 48);
        Self {
            name: "table".into(),
            objects: vec![
                Object { name: "floor".into(), mesh: floor, solid: true },
                Object { name: "table".into(), mesh: table, solid: true },
                Object { name: "sphere".into(), mesh: sphere, solid: true },
            ],
            light: SpotLight {
                position: Vec3::new(1.5, 6.0, 2.5),
                target: Vec3::new(0.5, 0.0, 0.3),
                fov_degrees: 70.0,
                near: 2.0,
                far: 10.0,
            },
        }
    }

    /// One draw call per object under `transform`, all with cull mode `cull`.
    #[must_use]
    pub fn draws(&self, transform: Mat4, cull: CullMode) -> Vec<Draw<'_>> {
        self.objects
            .iter()
            .map(|o| Draw { positions: &o.mesh.positions, triangles: &o.mesh.triangles, transform, cull })
            .collect()
    }
}
