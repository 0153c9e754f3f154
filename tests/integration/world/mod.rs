//! Scenes, scene files and meshes: the bundled scenes and hostile inputs.

mod gltf;
mod hostile_scenes;
pub(crate) mod scenes;
