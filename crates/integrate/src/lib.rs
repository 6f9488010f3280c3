//! The volume rendering integral along one ray segment.
//!
//! API CONTRACT (skeleton): the ray casters use `ScalarIntegrator`:
//! `ScalarIntegrator::new(method, &transfer_function, &options)` and
//! `integrate(s_front, s_back, length) -> SegmentLight { emitted, transmittance }`
//! (front = nearer the eye). It splits the segment at transfer-function
//! control points and applies the chosen per-segment method.
