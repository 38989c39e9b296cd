//! What a Lagrangian run hands out: the profiles, summary and paragraph of its report, its
//! checkpoint (the state's own serialisation) and its ParaView documents. Uses
//! [`super::run`] and what it exposes; nothing below imports this folder.

pub mod checkpoint;
pub mod report;
pub mod vtk;
