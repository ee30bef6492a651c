//! What a column of `final.csv` or a dataset of `snapshots.h5` is ([`Quantity`]): a leaf
//! that the particle table (`table.rs`) and the files' self-description (`meta.rs`) both
//! name, so that neither imports the other's.

/// A column of `final.csv` or a dataset of `snapshots.h5`: name, SI unit, meaning.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Quantity {
    /// Column or dataset name.
    pub name: &'static str,
    /// SI unit (`1`: dimensionless; empty: a label, not a quantity); see `meta::unit` for `m`.
    pub unit: &'static str,
    /// What it is.
    pub description: &'static str,
}
