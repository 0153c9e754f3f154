//! The world around the chip: scenes (TOML files and the bundled ones),
//! meshes (OBJ files and generated shapes), and the occluders a scene
//! casts shadows with (Sen et al.'s silhouette edges and volumes), and a
//! scene's light moved where its user puts it.

pub mod cascade;
pub mod gltf;
pub mod mesh;
pub(crate) mod occluders;
pub mod relight;
pub mod scene;
pub mod scene_file;
