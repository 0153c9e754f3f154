//! A scene's first light placed where the user puts it (`umbra render
//! --light-from X,Y,Z`): aimed at the centre of the scene's bounds, its
//! view holding their bounding sphere, so that a light a loader supplied
//! (a glTF file without one) can be moved as a scene file's is.

use glam::Vec3;

use crate::world::mesh::Mesh;
use crate::world::scene::{CLEARANCE, Light, Orthographic, Perspective, Scene, bounding_sphere, point_text};

/// Why a light could not be placed.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
#[non_exhaustive]
pub enum RelightError {
    /// The text (held here; the flag's parser quotes it) is not three
    /// finite numbers `X,Y,Z`.
    #[error("expected three numbers, X,Y,Z (as `2,3,1.5`)")]
    Point(String),
    /// The scene has no vertex to aim at.
    #[error("--light-from: the scene has no vertex to aim the light at")]
    Empty,
    /// The point lies within the scene, where no view holds it.
    #[error(
        "--light-from {at}: the point lies {distance:.4} from the scene's centre {center}, within its bounds' sphere; a light at least {least:.4} from the centre (1.2 times the sphere's radius {radius:.4}) sees the whole scene"
    )]
    Inside {
        /// The point, as `x,y,z`.
        at: String,
        /// The scene's centre, as `x,y,z`.
        center: String,
        /// The point's distance from the centre.
        distance: f32,
        /// The bounding sphere's radius.
        radius: f32,
        /// The least distance a light may lie at.
        least: f32,
    },
}

/// `X,Y,Z` as a point.
///
/// # Errors
/// [`RelightError::Point`] unless the text is three finite numbers.
pub fn parse_point(text: &str) -> Result<Vec3, RelightError> {
    let numbers: Vec<f32> = text
        .split(',')
        .map(|s| s.trim().parse::<f32>())
        .collect::<Result<_, _>>()
        .map_err(|_| RelightError::Point(text.to_owned()))?;
    match numbers[..] {
        [x, y, z] if [x, y, z].iter().all(|v| v.is_finite()) => Ok(Vec3::new(x, y, z)),
        _ => Err(RelightError::Point(text.to_owned())),
    }
}

impl Scene {
    /// The scene with its first light (`lights[0]`) moved to `from` and
    /// aimed at the centre of the scene's bounds: a spot light's view
    /// framing them ([`Perspective::framing_from`]), a glTF spot's cone
    /// keeping its angle, a directional light shining from `from`'s side
    /// with its map holding them. Its notes say where the light went, and
    /// [`Scene::arguments`] names the move again.
    ///
    /// # Errors
    /// [`RelightError::Empty`] for a scene without vertices,
    /// [`RelightError::Inside`] for a point within 1.2 radii of the centre
    /// of the scene's bounding sphere.
    pub fn with_light_from(mut self, from: Vec3) -> Result<Self, RelightError> {
        let mut all = Mesh::default();
        for o in &self.objects {
            all.positions.extend(o.mesh.bounds().into_iter().flat_map(|(lo, hi)| [lo, hi]));
        }
        let (center, radius) = bounding_sphere(&all).ok_or(RelightError::Empty)?;
        let view = Perspective::framing_from(&all, from).ok_or_else(|| RelightError::Inside {
            at: point_text(from),
            center: point_text(center),
            distance: (from - center).length(),
            radius,
            least: CLEARANCE * radius,
        })?;
        let moved = match self.lights.first() {
            Some(Light::Cone(cone)) => Light::Cone(Perspective { fov_degrees: cone.fov_degrees, ..view }),
            Some(Light::Directional(_, cascades)) => Light::Directional(
                Orthographic {
                    position: view.position,
                    target: view.target,
                    extent: radius * 1.05,
                    near: view.near,
                    far: view.far,
                    up: view.up,
                },
                *cascades,
            ),
            Some(Light::Spot(_)) | None => Light::Spot(view),
        };
        match self.lights.first_mut() {
            Some(first) => *first = moved,
            None => self.lights.push(moved),
        }
        self.notes.push(format!(
            "{} moved to {}, aimed at the scene's centre {}",
            Scene::light_key(0),
            point_text(from),
            point_text(center)
        ));
        self.light_from = Some(from);
        Ok(self)
    }
}
