//! The exact route's realizations stepped 8 at a time in lockstep (`simulate::GaussMarkovLanes`): every
//! realization's time sums, Welch sums and verdict values keep the bits of the realization run alone.

use crate::common;
use common::root;
use stochvib::scenario::load_scenario;
use stochvib::simulate::{Route, RunOptions};
use stochvib::store::RunFile;

/// Runs of 2 (the fewest a run takes), 3, 8 and 11 realizations (one shard: 11 is a lockstep group of 8
/// and a short group of 3 run one at a time) of the operator seat with its comfort and fatigue channels
/// (more than 8 states: the lanes' general step) and of the conveyor idler (at most 8 states: the
/// fixed-size step), statistics only in blocks of 7 steps (not dividing the record) and of 1000 (dividing
/// it): every statistic (the verdict statistics among them), every density estimate and every rainflow
/// count is bit-identical to the same run keeping its raw records, whose realizations are whole records
/// generated one at a time by the scalar recursion (`GaussMarkov::advance`) and reduced by a different
/// code path.
#[test]
fn lockstep_realizations_have_the_bits_of_one_at_a_time() {
    let _serial = common::hdf5_serial(); // see its docs: no fork while a file is open
    let d = common::scratch_dir("lockstep", "runs");
    for (name, realizations) in ["operator-seat-verdicts", "conveyor-idler"]
        .into_iter()
        .flat_map(|name| [2usize, 3, 8, 11].map(|r| (name, r)))
    {
        let sc = load_scenario(&root().join(format!("data/{name}.toml")), &root().join("spectra")).unwrap();
        let mut all = Vec::new();
        for (k, (block, raw)) in [(7usize, false), (1000, false), (1 << 14, true)]
            .into_iter()
            .enumerate()
        {
            let mut o = RunOptions {
                realizations,
                duration_s: 20.0,
                dt_s: 0.005,
                seed: 9,
                ..RunOptions::default()
            };
            o.shard_size = 16;
            o.block_steps = block;
            o.store_raw = raw;
            let out = d.join(format!("{name}-{realizations}-{k}.h5"));
            let s = sc.simulate(&o, &out, &|_, _| {}).unwrap();
            assert_eq!((s.route, s.n_samples), (Route::Exact, 4000), "{name}");
            let mut v = common::statistic_bits(&s);
            v.extend(common::psd_bits(&out));
            for h in RunFile::open(&out).unwrap().rainflow().unwrap() {
                v.extend(h.counts.iter().chain([&h.overflow]).map(|x| x.to_bits()));
            }
            all.push(v);
        }
        assert!(
            all.windows(2).all(|w| w[0] == w[1]),
            "{name}: {realizations} realizations"
        );
    }
    let _ = std::fs::remove_dir_all(&d);
}
