//! What a Lagrangian run hands out: the profiles, summary and paragraph of its report and
//! its ParaView documents (its checkpoint is the state's own serialisation, beside
//! [`super::run::state::State`]). Uses [`super::run`] and what it exposes; nothing below
//! imports this folder.

pub mod report;
pub mod vtk;
