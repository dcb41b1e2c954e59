use std::sync::Arc;
use stochvib::nonlinear::*;
use stochvib::nonlinear::monte_carlo::*;
use stochvib::response::{Excitation, analyze_output};
use stochvib::spectrum::{Domain, RationalSpectrum};
use stochvib::system::{Attach, Drive, Mdof, Quantity, FrequencyResponse};
use stochvib::simulate::RunOptions;

fn main() {
    let lin = Mdof::oscillator(1.0, 1.0, 0.2, Drive::Force).unwrap().with_output("x", Quantity::Displacement(vec![1.0])).unwrap()
        .with_output("v", Quantity::Velocity(vec![1.0])).unwrap();
    let e = NonlinearElement { name: "cubic".into(), law: Arc::new(CubicSpring::new(0.0, 1.0).unwrap()), point: vec![1.0], to: Attach::Ground };
    let model = NonlinearModel::new(&lin, vec![e]).unwrap();
    let white = Arc::new(RationalSpectrum::new(vec![0.2 / std::f64::consts::PI], vec![1.0], Domain::Temporal).unwrap());
    let exc = Excitation::single(white, 0.0).unwrap();
    let r1 = linearize(&model, &exc, &Route1Options::default()).unwrap();
    let r1 = r1.converged().unwrap();
    println!("route1 sigma2 {} iters {} method {}", r1.moments[0].sigma_x.powi(2), r1.iterations, r1.method);
    let osc = WhiteNoiseOscillator::from_model(&model, &exc).unwrap();
    let st = osc.stationary().unwrap();
    println!("route3 var {} kurt {} nu(1) {}", st.variance, st.kurtosis, st.upcrossing_rate(1.0));
    let stats1 = r1.output_statistics(&exc, &Default::default()).unwrap();
    let lin_stats: Vec<_> = (0..2).map(|i| analyze_output(model.linear(), &exc, i).unwrap()).collect();
    let input = NonlinearRunInput { model: &model, excitation: &exc, outputs: vec![0, 1], input_signals: vec![stochvib::store::Signal::new("force", "N")],
        scenario_text: "scratch".into(), provenance: vec![], source_files: vec![], kurtosis: vec![], levels: vec![(0, vec![1.0, 2.0])],
        route1: Some(r1), route1_statistics: Some(&stats1), linear_statistics: Some(&lin_stats), route3: Some(&st) };
    let out = std::path::Path::new("/tmp/nlscratch/duffing.h5");
    let _ = std::fs::remove_file(out);
    let t = std::time::Instant::now();
    let opts = NonlinearRunOptions { run: RunOptions { shard_size: 16, ..RunOptions::new(64, 2000.0, 0.05, 7) }, burn_in_s: None, halving_checks: None };
    let s = run_nonlinear(&input, &opts, out, &|_, _| {}).unwrap();
    println!("elapsed {:?}, burn {}", t.elapsed(), s.burn_in_s);
    for n in &s.run.notes { println!("note {n}"); }
    for o in &s.run.outputs { for st in &o.statistics { println!("{} {} {:.6} [{:.6}, {:.6}] analytic {:?}", o.output, st.name, st.interval.estimate, st.interval.lower, st.interval.upper, st.analytic); } }
}
