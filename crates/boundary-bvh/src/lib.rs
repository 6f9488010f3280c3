//! A BVH (obvhs) over the boundary faces of a tetrahedral mesh, answering
//! "which boundary face does this ray enter the mesh through first, after t".
//!
//! API CONTRACT (skeleton, filled in by the BVH work): `BoundaryBvh::build`,
//! `first_entry`, and `brute_force_first_entry` with the same contract.

pub mod watertight;
