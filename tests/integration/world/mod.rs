//! Scenes, scene files and meshes: the bundled scenes and hostile inputs.

mod gltf;
mod gltf_hostile;
mod hostile_scenes;
pub(crate) mod scenes;
