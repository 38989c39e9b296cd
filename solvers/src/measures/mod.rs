//! Measures taken of a run's profiles, one definition each for the solvers' summaries, the
//! tests and the command-line tables: the transport scales of the dimensionless numbers
//! ([`transport_scales`]), the levels of a flux profile and Cheng's flux layer
//! ([`flux_levels`]), the bed-aligned comparison with measured profiles ([`bed_aligned`]),
//! the Rouse number of a suspension ([`rouse`]), and the classic bedload laws a study of
//! qs* holds its runs against ([`bedload`]).

pub mod bed_aligned;
pub mod bedload;
pub mod flux_levels;
pub mod rouse;
pub mod transport_scales;
