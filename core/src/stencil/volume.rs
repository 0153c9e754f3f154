//! Shadow volumes: the light as a volume generator sees it, and one occluder's volume.

use crate::front::clip::ClipVertex;

/// The light as a shadow-volume generator sees it, in camera clip space.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct VolumeLight {
    /// Camera clip coordinates of the light's position `(L, 1)`, or of the
    /// direction towards a directional light `(d, 0)`.
    pub clip: ClipVertex,
    /// `true` for a point (spot) light, `false` for a directional one.
    pub point: bool,
    /// The extrusion parameter `t`: a point light's extruded vertices lie at
    /// `1 + t` times their distance from the light; a directional light's at
    /// `t` world units beyond them. Choose it so the volumes reach past
    /// every receiver.
    pub t: f64,
}

impl VolumeLight {
    /// Vertex `v` extruded away from the light.
    #[must_use]
    pub fn extrude(&self, v: &ClipVertex) -> ClipVertex {
        let w = if self.point { 1.0 } else { 0.0 };
        [0, 1, 2, 3].map(|k| v[k] + self.t * (w * v[k] - self.clip[k]))
    }
}

/// The triangles of one occluder triangle's share of a shadow volume.
#[derive(Clone, Copy, Debug)]
pub struct Volume {
    /// The occluder triangle, light-facing, in camera clip space.
    pub tri: [ClipVertex; 3],
    /// Which edges (`k` is `tri[k] → tri[k + 1]`) are silhouette edges.
    pub sides: [bool; 3],
}

impl Volume {
    /// Every triangle of this share: near cap, far cap, and two per side,
    /// wound so that their front faces point out of the volume.
    pub fn triangles(&self, light: &VolumeLight) -> impl Iterator<Item = [ClipVertex; 3]> + '_ {
        let [a, b, c] = self.tri;
        let far = self.tri.map(|v| light.extrude(&v));
        let caps = [[a, b, c], [far[0], far[2], far[1]]];
        let sides = (0..3).filter(|&k| self.sides[k]).flat_map(move |k| {
            let (p, q) = (self.tri[k], self.tri[(k + 1) % 3]);
            let (pf, qf) = (far[k], far[(k + 1) % 3]);
            [[q, p, pf], [q, pf, qf]]
        });
        caps.into_iter().chain(sides)
    }
}
