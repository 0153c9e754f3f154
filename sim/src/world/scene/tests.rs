//! The scene's views and lights, worked by hand.

use glam::{DVec3, Vec3};

use super::{Light, Perspective};

/// A spot light's cone, worked by hand: at the origin looking down −y
/// with a 90° field of view, its cone is 45° about the axis. A point
/// 1 below it and (0.9, 0.9) aside lies inside the square frustum
/// (each of x/y under tan 45° = 1) but √(0.9² + 0.9²) = 1.27 > 1 off
/// the axis: outside the cone, not reached. (0.6, 0.6) aside,
/// 0.85 < 1: reached.
#[test]
fn a_spot_lights_its_cone_not_its_frustums_corners() {
    let view =
        Perspective { position: Vec3::ZERO, target: Vec3::NEG_Y, fov_degrees: 90.0, near: 0.1, far: 10.0, up: Vec3::Z };
    let cone = Light::Cone(view).source();
    assert!(!cone.reaches(DVec3::new(0.9, -1.0, 0.9)), "a corner of the frustum");
    assert!(cone.reaches(DVec3::new(0.6, -1.0, 0.6)));
    assert!(cone.reaches(DVec3::new(0.0, -1.0, 0.99)), "just inside the cone's edge");
    assert!(!cone.reaches(DVec3::new(0.0, -1.0, 1.01)), "just outside it");
    assert!(!cone.reaches(DVec3::new(0.0, -11.0, 0.0)), "past the far plane");
}
