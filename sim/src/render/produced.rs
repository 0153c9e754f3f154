//! What a render produced: each shadow-casting light's part (its maps,
//! the camera pass's shading against them, its exact reference, verdicts
//! and metrics), the camera pass's events, and the frame's metrics over
//! its lights.

use super::CascadePart;
use crate::base::counters::Counters;
use crate::pass::camera::CameraImage;
use crate::pass::light::RawMaps;
use crate::truth::metrics::{Metrics, Verdict};
use crate::truth::reference::PixelTruth;

/// Everything a render produced: its first light's part in its own
/// fields, each further shadow-casting light's in [`Render::more`].
pub struct Render {
    /// The camera pass's shading against the first light.
    pub image: CameraImage,
    /// The first light's maps, raw bits.
    pub maps: RawMaps,
    /// The exact reference per pixel for the first light.
    pub truth: Vec<Option<PixelTruth>>,
    /// The render against the reference, for the first light.
    pub metrics: Metrics,
    /// Each pixel's verdict for the first light, wrong ones by their cause.
    pub verdicts: Vec<Verdict>,
    /// Events of the first light's pass.
    pub light_events: Counters,
    /// Events of the camera pass: its visibility once, its shading once
    /// per light.
    pub camera_events: Counters,
    /// The `umbra render` command line that renders it again, bit for bit
    /// ([`RenderConfig::command`](super::RenderConfig::command)).
    pub command: String,
    /// The parts of the scene's second and further shadow-casting lights,
    /// in order (empty for a scene of one light).
    pub more: Vec<LightPart>,
    /// Each light that casts no shadow's cosine at each pixel's surface
    /// ([`Reference::facing`](crate::truth::reference::Reference::facing)), for the shaded picture.
    pub shadowless: Vec<Vec<f64>>,
    /// The first light's cascades, nearest first (empty for one map):
    /// [`Render::maps`] and [`Render::light_events`] are its first
    /// cascade's.
    pub cascades: Vec<CascadePart>,
    /// The maps of the first light's cascades after the first.
    pub cascade_maps: Vec<RawMaps>,
    /// The cascade each pixel read, for a cascaded first light (empty
    /// otherwise).
    pub cascade_of: Vec<u8>,
}

/// What a render produced for one of its lights: the maps its light pass
/// drew, the camera pass's shading against them, the exact reference for
/// that light and the metrics between them.
pub struct LightPart {
    /// The camera pass's shading against this light.
    pub image: CameraImage,
    /// Its light pass's maps, raw bits.
    pub maps: RawMaps,
    /// The exact reference per pixel for this light.
    pub truth: Vec<Option<PixelTruth>>,
    /// The render against the reference, for this light.
    pub metrics: Metrics,
    /// Each pixel's verdict for this light.
    pub verdicts: Vec<Verdict>,
    /// Events of its light pass (its first cascade's, for a cascaded
    /// light).
    pub light_events: Counters,
    /// Its cascades, nearest first (empty for one map).
    pub cascades: Vec<CascadePart>,
    /// The maps of its cascades after the first.
    pub cascade_maps: Vec<RawMaps>,
    /// The cascade each pixel read, for a cascaded light (empty otherwise).
    pub cascade_of: Vec<u8>,
}

impl Render {
    /// Every light's part, the first's first: its shading, maps,
    /// reference, metrics, verdicts and light-pass events.
    pub fn parts(&self) -> impl Iterator<Item = PartRef<'_>> {
        let first = PartRef {
            image: &self.image,
            maps: &self.maps,
            truth: &self.truth,
            metrics: &self.metrics,
            verdicts: &self.verdicts,
            light_events: &self.light_events,
            cascades: &self.cascades,
            cascade_maps: &self.cascade_maps,
            cascade_of: &self.cascade_of,
        };
        core::iter::once(first).chain(self.more.iter().map(|p| PartRef {
            image: &p.image,
            maps: &p.maps,
            truth: &p.truth,
            metrics: &p.metrics,
            verdicts: &p.verdicts,
            light_events: &p.light_events,
            cascades: &p.cascades,
            cascade_maps: &p.cascade_maps,
            cascade_of: &p.cascade_of,
        }))
    }

    /// The frame's metrics: for one light, its own; for several, every
    /// light's summed over (pixel, light) pairs ([`Metrics::of_lights`]).
    #[must_use]
    pub fn frame_metrics(&self) -> Metrics {
        if self.more.is_empty() {
            return self.metrics;
        }
        Metrics::of_lights(&self.parts().map(|p| *p.metrics).collect::<Vec<_>>())
    }
}

/// One light's part of a [`Render`], borrowed.
#[derive(Clone, Copy)]
pub struct PartRef<'r> {
    /// The camera pass's shading against this light.
    pub image: &'r CameraImage,
    /// Its maps.
    pub maps: &'r RawMaps,
    /// The exact reference for this light.
    pub truth: &'r [Option<PixelTruth>],
    /// Its metrics.
    pub metrics: &'r Metrics,
    /// Its verdicts.
    pub verdicts: &'r [Verdict],
    /// Its light pass's events (its first cascade's).
    pub light_events: &'r Counters,
    /// Its cascades.
    pub cascades: &'r [CascadePart],
    /// The maps of its cascades after the first.
    pub cascade_maps: &'r [RawMaps],
    /// The cascade each pixel read (empty for one map).
    pub cascade_of: &'r [u8],
}
