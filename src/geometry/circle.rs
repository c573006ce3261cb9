//! Circle geometry (placeholder, being written).
