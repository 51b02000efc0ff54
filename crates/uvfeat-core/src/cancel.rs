//! Stopping a computation part way: a caller (the Python binding, on Ctrl-C) requests it, and the
//! long loops (per texel tile, per vertex, per chart seed) skip their remaining items once it is
//! requested and return [`UvfeatError::Cancelled`], so a stop takes effect within one item's work.
//!
//! The request is process-wide, as the signal that triggers it: every computation running stops.

use crate::error::{Result, UvfeatError};
use std::sync::atomic::{AtomicBool, Ordering};

static REQUESTED: AtomicBool = AtomicBool::new(false);

/// Asks every running computation to stop.
pub fn request() {
    REQUESTED.store(true, Ordering::Relaxed);
}

/// Withdraws the request (after the interrupted computation has returned).
pub fn clear() {
    REQUESTED.store(false, Ordering::Relaxed);
}

/// Whether a stop was requested: a loop skips its remaining items when it was.
#[inline]
pub fn requested() -> bool {
    REQUESTED.load(Ordering::Relaxed)
}

/// `Err(Cancelled)` when a stop was requested: a stage's result is not to be used then.
pub fn check() -> Result<()> {
    if requested() {
        Err(UvfeatError::Cancelled)
    } else {
        Ok(())
    }
}
