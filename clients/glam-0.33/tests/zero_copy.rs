//! ocean-fft's buffers as glam 0.33 types (the glam of Bevy 0.20, rapier, parry and avian),
//! without copying; and the conversions through mint.

#[path = "../../zero_copy.rs"]
mod zero_copy;

use glam::Vec3;
use zero_copy::{ocean, varies};

#[test]
fn buffer_elements_convert_through_mint() {
    let ocean = ocean();
    let cascade = &ocean.cascades()[0];
    for (a, d) in cascade.normal().iter().zip(cascade.displacement()) {
        // mint's vectors convert from the crate's arrays with `From`: no feature needed.
        let normal = mint::Vector3::from(*a);
        assert_eq!((normal.x, normal.y, normal.z), (a[0], a[1], a[2]));
        let horizontal: mint::Vector2<f32> = (*d).into();
        assert_eq!((horizontal.x, horizontal.y), (d[0], d[1]));
        // And any library that speaks mint takes them (glam with its `mint` feature here).
        assert_eq!(Vec3::from(normal), Vec3::from_array(*a));
        assert_eq!(<[f32; 3]>::from(normal), *a);
    }
    varies(cascade.normal().iter().map(|a| mint::Vector3::from(*a).x));
}
