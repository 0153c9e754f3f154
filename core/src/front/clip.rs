//! Homogeneous clipping: near plane, far plane and the guard band.
//!
//! Vertices arrive in light clip space (`x, y, z, w` in f32, from the
//! transform) and are clipped in f64, where no f32 input can overflow: the
//! differences and products below stay far inside f64's range. Planes, as
//! distances that are `≥ 0` inside:
//!
//! * near `z ≥ 0` and far `z ≤ w` (depth `z/w` in `[0, 1]`);
//! * the guard band `|x| ≤ g_x·w`, `|y| ≤ g_y·w`, wide enough that almost no
//!   triangle is clipped by it, narrow enough that snapped coordinates stay
//!   inside the integer budget of [`crate::front::snap`](mod@crate::front::snap).
//!
//! Sutherland–Hodgman: a triangle becomes a convex polygon of at most
//! [`MAX_POLYGON`] vertices, which the light pass draws as a fan. A new
//! vertex is always interpolated from the inside endpoint towards the
//! outside one, so two triangles sharing an edge get the same point.

use heapless::Vec;

/// A vertex in homogeneous light clip space.
pub type ClipVertex = [f64; 4];

/// Three vertices, plus one per clip plane.
pub const MAX_POLYGON: usize = 3 + PLANES;

const PLANES: usize = 6;

/// A clipped convex polygon.
pub type Polygon = Vec<ClipVertex, MAX_POLYGON>;

/// The result of clipping one triangle.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Clipped {
    /// Every vertex inside every plane: the triangle as it was.
    Inside,
    /// Part of the triangle is inside: the polygon written to the caller's buffer.
    Polygon,
    /// Nothing is inside.
    Outside,
}

/// Which depth planes clip.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum DepthClip {
    /// Near and far (the light and camera passes).
    NearFar,
    /// Near only: depth beyond the far plane is clamped to it by the
    /// format's saturation (the depth clamp that depth-fail shadow volumes
    /// need, so their far caps are not cut away).
    Near,
}

#[inline]
fn distance(v: &ClipVertex, plane: usize, guard: [f64; 2]) -> f64 {
    let [x, y, z, w] = *v;
    match plane {
        0 => z,
        1 => w - z,
        2 => guard[0] * w + x,
        3 => guard[0] * w - x,
        4 => guard[1] * w + y,
        _ => guard[1] * w - y,
    }
}

/// Whether a vertex is inside every plane.
#[inline]
#[must_use]
pub fn inside_all(v: &ClipVertex, guard: [f64; 2]) -> bool {
    (0..PLANES).all(|p| distance(v, p, guard) >= 0.0)
}

/// Clip a triangle whose vertices are finite. `guard` is `[g_x, g_y]`. The
/// polygon, when there is one, goes to `poly`.
#[must_use]
pub fn clip_triangle(tri: &[ClipVertex; 3], guard: [f64; 2], poly: &mut Polygon) -> Clipped {
    clip_triangle_with(tri, guard, DepthClip::NearFar, poly)
}

/// [`clip_triangle`] with a choice of depth planes.
#[must_use]
pub fn clip_triangle_with(tri: &[ClipVertex; 3], guard: [f64; 2], depth: DepthClip, poly: &mut Polygon) -> Clipped {
    let active = |p: usize| p != 1 || depth == DepthClip::NearFar;
    let inside = |v: &ClipVertex| (0..PLANES).filter(|&p| active(p)).all(|p| distance(v, p, guard) >= 0.0);
    if tri.iter().all(inside) {
        return Clipped::Inside;
    }
    let mut outside_all = [true; PLANES];
    for v in tri {
        for (p, out) in outside_all.iter_mut().enumerate() {
            *out &= active(p) && distance(v, p, guard) < 0.0;
        }
    }
    if outside_all.iter().any(|&o| o) {
        return Clipped::Outside;
    }
    poly.clear();
    for v in tri {
        // Capacity is MAX_POLYGON ≥ 3.
        let _ = poly.push(*v);
    }
    for plane in (0..PLANES).filter(|&p| active(p)) {
        let mut next: Polygon = Vec::new();
        let n = poly.len();
        for i in 0..n {
            let cur = poly[i];
            let nxt = poly[(i + 1) % n];
            let dc = distance(&cur, plane, guard);
            let dn = distance(&nxt, plane, guard);
            if dc >= 0.0 && next.push(cur).is_err() {
                return Clipped::Outside;
            }
            if (dc >= 0.0) != (dn >= 0.0) {
                let (inside, outside, d_in, d_out) = if dc >= 0.0 { (cur, nxt, dc, dn) } else { (nxt, cur, dn, dc) };
                let t = d_in / (d_in - d_out);
                let mut p = [0.0; 4];
                for k in 0..4 {
                    p[k] = inside[k] + t * (outside[k] - inside[k]);
                }
                if next.push(p).is_err() {
                    // A convex polygon gains at most one vertex per plane, so
                    // this is unreachable for finite input; drop rather than panic.
                    return Clipped::Outside;
                }
            }
        }
        if next.len() < 3 {
            return Clipped::Outside;
        }
        *poly = next;
    }
    Clipped::Polygon
}

#[cfg(test)]
mod tests {
    use super::*;

    const G: [f64; 2] = [4.0, 4.0];

    #[test]
    fn inside_and_outside() {
        let tri = [[0.0, 0.0, 0.5, 1.0], [0.5, 0.0, 0.5, 1.0], [0.0, 0.5, 0.5, 1.0]];
        let mut p = Polygon::new();
        assert_eq!(clip_triangle(&tri, G, &mut p), Clipped::Inside);
        let behind = [[0.0, 0.0, -0.5, 1.0], [0.5, 0.0, -0.5, 1.0], [0.0, 0.5, -0.1, 1.0]];
        assert_eq!(clip_triangle(&behind, G, &mut p), Clipped::Outside);
    }

    #[test]
    fn near_plane_cut_gives_a_quad_on_the_plane() {
        let tri = [[0.0, 0.0, -1.0, 1.0], [1.0, 0.0, 1.0, 1.0], [0.0, 1.0, 1.0, 1.0]];
        let mut p = Polygon::new();
        assert_eq!(clip_triangle(&tri, G, &mut p), Clipped::Polygon);
        assert_eq!(p.len(), 4);
        assert!(p.iter().all(|v| v[2] >= 0.0));
        assert_eq!(p.iter().filter(|v| v[2] == 0.0).count(), 2);
        // The cut points sit halfway along the two crossing edges.
        assert!(p.iter().any(|v| v[0] == 0.5 && v[1] == 0.0));
        assert!(p.iter().any(|v| v[0] == 0.0 && v[1] == 0.5));
    }
}
