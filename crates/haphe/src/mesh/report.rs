//! Validation report (stub).
/// Report.
#[derive(Debug)]
pub struct MeshReport;
/// Component.
#[derive(Debug)]
pub struct ComponentReport;
/// Edge.
#[derive(Debug)]
pub struct EdgeUse;
/// Usability.
#[derive(Debug)]
pub enum Usability {}
