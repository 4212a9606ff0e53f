//! The robust response at 8 bits (the lab's precision dial), where the
//! detection's touching tolerance `touch_ulps * u * s` is wider than the
//! padding, so a resting body's contact is met by a sweep at `t = 0`
//! rather than among the resting contacts. Found by a review in the
//! twenty-fourth session (R24c): such a touch was taken as a gap of zero
//! and the body pushed a whole padding out of wherever it was; on a floor
//! it rose by the padding frame after frame (jitter `9.3e-3` of the push),
//! in the obtuse corner it jittered (0.27), in the crease too (0.025). The
//! gap of a touch at the start is now measured.

use std::sync::Arc;
use sweepslide::lab::scenes::build;
use sweepslide::lab::{Precision, RunConfig, run};
use sweepslide::respond::Response;

#[test]
fn robust_rests_and_slides_without_jitter_at_8_bits() {
    for spec in ["floor", "tessellated-floor", "corner", "crease"] {
        let mut scene = build(spec, 1).unwrap();
        scene.frames = 150;
        let config = RunConfig {
            scene: Arc::new(scene),
            response: Response::Robust,
            detection: None,
            precision: Precision::Mpfr(8),
            seed: 1,
        };
        let r = run(&config).unwrap().result;
        assert_eq!(r.penetrating_frames, 0, "{spec}: {r:?}");
        assert!(r.jitter <= 1e-3, "{spec}: jitter {}: {r:?}", r.jitter);
    }
}
