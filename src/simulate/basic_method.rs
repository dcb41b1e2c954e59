//! ISO 2631-1's test of whether the basic (r.m.s.) method suffices, on the Monte Carlo results of a weighted
//! output: the crest factor, MTVV/a_w and VDV/(a_w T^(1/4)) of the simulated records against 9, 1.5 and 1.75,
//! and the metric that governs ([`Governing`]).
//!
//! # Formula
//! From the statistics of a comfort channel ([`super::verdicts`]) over records of duration T = NΔt:
//! ```text
//! a_w  = MC σ of the weighted output (`sigma` estimate),        CF = mean over realizations of max|a_k|/a_w,i
//! MTVV/a_w = mean MTVV_i / a_w,                                  VDV/(a_w T^(1/4)) = VDV / (a_w T^(1/4))
//! ```
//! with VDV the run's estimate ((mean of VDV_i⁴)^(1/4)). The check is [`BasicMethodInputs::check`] with
//! peak = CF·a_w. The crest factor and the MTVV ratio grow with the record length (a longer record reaches
//! higher maxima), so they hold for records of the simulated duration T, not for the daily exposure; the
//! VDV ratio of a stationary Gaussian output is 3^(1/4) ≈ 1.32 for any T.

use crate::comfort::{BasicMethodCheck, BasicMethodInputs, Governing};
use crate::store::OutputStatistics;
use serde::Serialize;

/// The basic-method check of one weighted output of a run.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct RunBasicMethod {
    /// The weighted output.
    pub output: String,
    /// Record duration T = NΔt the ratios refer to, s.
    pub duration_s: f64,
    /// The ISO 2631-1 criteria (crest factor, MTVV ratio, VDV ratio, which are exceeded) and the metric
    /// that governs.
    pub check: BasicMethodCheck,
}

impl RunBasicMethod {
    /// A line of text: the three ratios against their thresholds and the governing metric.
    pub fn describe(&self) -> String {
        let c = &self.check;
        let r = |v: Option<f64>, lim: f64, over: bool| match v {
            Some(v) => format!("{v:.3} ({} {lim})", if over { ">" } else { "≤" }),
            None => "—".into(),
        };
        format!(
            "crest factor {}, MTVV/a_w {}, VDV/(a_w T^¼) {} over records of T = {} s: {}; {} governs",
            r(c.crest_factor, 9.0, c.crest_factor_exceeded),
            r(c.mtvv_ratio, 1.5, c.mtvv_ratio_exceeded),
            r(c.vdv_ratio, 1.75, c.vdv_ratio_exceeded),
            self.duration_s,
            if c.basic_method_sufficient {
                "the basic method suffices"
            } else {
                "the basic method is NOT sufficient (ISO 2631-1 6.3.3)"
            },
            c.governing.label()
        )
    }

    /// The governing metric.
    pub fn governing(&self) -> Governing {
        self.check.governing
    }
}

/// The basic-method check of every output that has the comfort statistics `vdv`, `crest_factor` (and
/// `mtvv` when the records are at least 1 s long), records of `duration_s` seconds.
///
/// # Formula
/// See the module docs.
pub fn basic_method_rows(outputs: &[OutputStatistics], duration_s: f64) -> Vec<RunBasicMethod> {
    outputs
        .iter()
        .filter_map(|o| {
            let a_w = o.get("sigma")?.interval.estimate;
            let vdv = o.get("vdv")?.interval.estimate;
            let cf = o.get("crest_factor")?.interval.estimate;
            let mtvv = o.get("mtvv").map(|m| m.interval.estimate);
            let check = BasicMethodInputs {
                a_w,
                peak: cf * a_w,
                mtvv,
                vdv,
                duration_s,
            }
            .check()
            .ok()?;
            Some(RunBasicMethod {
                output: o.output.clone(),
                duration_s,
                check,
            })
        })
        .collect()
}
