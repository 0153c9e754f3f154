//! Scenes, scene files and meshes: the bundled scenes and hostile inputs.

mod hostile_scenes;
mod scenes;
