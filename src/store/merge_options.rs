//! How the shard files of a cluster run are merged into one run file: options shared by the merge of a
//! stationary run ([`crate::study::merge_runs`]) and of a transient run ([`crate::study::merge_transient`]).
//! They say how the merged file is stored (where its raw realizations are, whether an existing file is
//! replaced, the confidence of its intervals), so they live with the store both merges write to.

use super::{CreateOptions, RawStorage};

/// Options of a merge of shard files ([`crate::study::merge_runs`], [`crate::study::merge_transient`]).
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct MergeOptions {
    /// Copy the raw realizations into the merged file instead of referencing the shard files.
    pub copy: bool,
    /// Replace an existing finished run file at `out` (at the final rename).
    pub overwrite: bool,
    /// Confidence of the intervals; default: that of the shard files (which must then agree).
    pub confidence: Option<f64>,
}

impl MergeOptions {
    /// Where the merged file keeps the raw realizations of a run that stored them (`store_raw`): copied
    /// with [`MergeOptions::copy`], otherwise virtual datasets over the shard files; none if the run
    /// stored none.
    pub fn raw_storage(&self, store_raw: bool) -> RawStorage {
        match (store_raw, self.copy) {
            (false, _) => RawStorage::None,
            (true, true) => RawStorage::Copied,
            (true, false) => RawStorage::Virtual,
        }
    }

    /// How the merged file's writer treats what is already at `out`: replaced with
    /// [`MergeOptions::overwrite`]; an interrupted merge of the same shards resumed (no `restart`).
    pub fn create_options(&self) -> CreateOptions {
        CreateOptions {
            overwrite: self.overwrite,
            ..CreateOptions::default()
        }
    }
}
