//! The memory system below the renderer: the CLI's global allocator
//! ([`Recycling`]: large freed blocks handed to the next large allocation)
//! and a cache prefetch for the walk ([`prefetch`]). The workspace forbids
//! unsafe code; both need it, so they live here, alone, each unsafe block
//! with its reason.

mod prefetch;
mod recycling;

pub use prefetch::prefetch;
pub use recycling::{LARGE, Recycling, SLOTS};
