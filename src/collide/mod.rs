//! Narrow phase: contact manifolds for each pair of shapes (being written).
