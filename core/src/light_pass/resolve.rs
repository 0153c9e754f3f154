//! The tile resolve: a tile's exact bounds, worked out when it is stored.

use crate::depth::{DepthFormat, count_of, min_max, tile_rows};
use crate::raster::TileView;

/// Exact bounds of a tile at store time (the resolve).
pub(super) fn resolve<F: DepthFormat>(view: &mut TileView<'_, F::Texel>, dual: bool) {
    let (r, width) = (view.rect, view.width);
    let rows = |buf| tile_rows(buf, r, width);
    let (z1_min, z1_max) = min_max(rows(&*view.z1), F::FAR);
    let st = &mut *view.state;
    (st.z1_min, st.z1_max) = (z1_min, z1_max);
    let (culled, max): (&[F::Texel], _) = if dual {
        let (z2_min, z2_max) = min_max(rows(&*view.z2), F::FAR);
        (st.z2_min, st.z2_max) = (z2_min, z2_max);
        (&*view.z2, z2_max)
    } else {
        (&*view.z1, z1_max)
    };
    st.cull_max = max;
    st.cull_count = count_of(rows(culled), max);
}
