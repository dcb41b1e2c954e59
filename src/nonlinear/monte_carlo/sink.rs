//! What route 2 keeps of the recorded samples of L realizations stepped in lockstep: the running
//! statistics of every output and element regime (arrays over the lanes, see [`OutputRecords`]), and per
//! lane the block of samples for the Welch estimate and, if asked, the raw samples. At the end the lanes
//! part into the records of lone realizations ([`Sink::close`]).

use super::plan::{NlPlan, HISTOGRAM_BINS};
use super::record::{OutputRecord, OutputRecords, RegimeRecord, RegimeRecords};
use crate::error::{Error, Result};
use crate::estimate::{WelchScratch, WelchStream, WelchSums};
use crate::nonlinear::integrator::{Lanes, Prepared};

/// Samples per block fed to the Welch estimate.
const BLOCK: usize = 4096;

/// The records of L realizations (see the module docs).
pub(super) struct Sink<'a, const L: usize> {
    plan: &'a NlPlan,
    /// The element laws (for their regimes).
    regime: Prepared<'a>,
    records: Vec<OutputRecords<L>>,
    regimes: Vec<RegimeRecords<L>>,
    lanes: Vec<LaneBlock>,
    /// The block of centred samples of every output, lane-major (one [`Lanes`] value per sample: a
    /// recorded sample is one store per output); a lane's column is copied out at a flush.
    block: Vec<Vec<Lanes<L>>>,
    column: Vec<f64>,
    filled: usize,
    /// Whether the lanes keep their raw samples (tested once per output and sample, not once per lane).
    keep_raw: bool,
}

/// One lane's Welch blocks and raw samples.
struct LaneBlock {
    streams: Vec<WelchStream>,
    welch: Vec<WelchSums>,
    raw: Option<Vec<Vec<f64>>>,
    err: Option<Error>,
}

/// The records of one realization, closed.
pub(super) struct LoneRecords {
    pub records: Vec<OutputRecord>,
    pub regimes: Vec<RegimeRecord>,
    pub welch: Vec<WelchSums>,
    pub raw: Option<Vec<Vec<f64>>>,
}

/// The running statistics of every output of `plan` for L lanes.
pub(super) fn records<const L: usize>(plan: &NlPlan) -> Vec<OutputRecords<L>> {
    plan.outputs
        .iter()
        .map(|o| OutputRecords::new(o.centre, &o.levels, o.hist_lo, o.hist_width, HISTOGRAM_BINS))
        .collect()
}

impl<'a, const L: usize> Sink<'a, L> {
    pub(super) fn new(plan: &'a NlPlan, keep_raw: bool) -> Self {
        let p = plan.outputs.len();
        Sink {
            plan,
            regime: plan.kicks.prepared(0.5 * plan.h),
            records: records(plan),
            regimes: vec![RegimeRecords::default(); plan.kicks.len()],
            lanes: (0..L)
                .map(|_| LaneBlock {
                    streams: (0..p).map(|_| plan.welch.stream()).collect(),
                    welch: (0..p).map(|_| plan.welch.sums()).collect(),
                    raw: keep_raw.then(|| vec![Vec::with_capacity(plan.n); p]),
                    err: None,
                })
                .collect(),
            block: vec![vec![[0.0; L]; BLOCK]; p],
            column: vec![0.0; BLOCK],
            filled: 0,
            keep_raw,
        }
    }

    /// The outputs y and the element deflections x of every lane.
    #[inline(always)]
    pub(super) fn push(&mut self, y: &[Lanes<L>], x: &[Lanes<L>], scratch: &mut WelchScratch) {
        for ((r, v), rec) in y.iter().enumerate().zip(self.records.iter_mut()) {
            self.block[r][self.filled] = rec.push(v);
            if self.keep_raw {
                for (lane, v) in self.lanes.iter_mut().zip(v) {
                    if let Some(raw) = &mut lane.raw {
                        raw[r].push(*v);
                    }
                }
            }
        }
        for ((e, rg), x) in self.regimes.iter_mut().enumerate().zip(x) {
            rg.push(&self.regime.engaged(e, x));
        }
        self.filled += 1;
        if self.filled == BLOCK {
            self.flush(scratch);
        }
    }

    fn flush(&mut self, scratch: &mut WelchScratch) {
        let welch = &self.plan.welch;
        let column = &mut self.column[..self.filled];
        for (l, lane) in self.lanes.iter_mut().enumerate() {
            for ((st, block), ws) in lane.streams.iter_mut().zip(&self.block).zip(lane.welch.iter_mut()) {
                for (c, b) in column.iter_mut().zip(block) {
                    *c = b[l];
                }
                if let Err(e) = welch.push(st, column, ws, scratch) {
                    lane.err.get_or_insert(e);
                }
            }
        }
        self.filled = 0;
    }

    /// The records closed (the last Welch block, the end of every record), lane by lane.
    ///
    /// # Errors
    /// A Welch failure, the first of each lane.
    pub(super) fn close(mut self, scratch: &mut WelchScratch) -> Vec<Result<LoneRecords>> {
        self.flush(scratch);
        let (records, regimes) = (&self.records, &self.regimes);
        let welch = &self.plan.welch;
        self.lanes
            .into_iter()
            .enumerate()
            .map(|(l, mut lane)| {
                for (st, ws) in lane.streams.iter_mut().zip(lane.welch.iter_mut()) {
                    welch.end_record(st, ws)?;
                }
                if let Some(e) = lane.err {
                    return Err(e);
                }
                Ok(LoneRecords {
                    records: records.iter().map(|r| r.lane(l)).collect(),
                    regimes: regimes.iter().map(|r| r.lane(l)).collect(),
                    welch: lane.welch,
                    raw: lane.raw,
                })
            })
            .collect()
    }
}
