//! Shared 1D column fluid solver.
