use std::sync::Arc;
use stochvib::nonlinear::*;
use stochvib::response::Excitation;
use stochvib::spectrum::{Domain, RationalSpectrum};
use stochvib::system::{Attach, Drive, Mdof, Quantity};
fn main() {
    for law in [Arc::new(BumpStop::new(Some((1.0, 1e6)), Some((1.0, 1e6))).unwrap()) as Arc<dyn ForceLaw>, Arc::new(CoulombFriction::new(100.0).unwrap()), Arc::new(CubicSpring::new(0.0, -1.0).unwrap())] {
        let lin = Mdof::oscillator(1.0, 1.0, 0.2, Drive::Force).unwrap().with_output("x", Quantity::Displacement(vec![1.0])).unwrap();
        let e = NonlinearElement { name: "e".into(), law, point: vec![1.0], to: Attach::Ground };
        let model = NonlinearModel::new(&lin, vec![e]).unwrap();
        let white = Arc::new(RationalSpectrum::new(vec![0.2 / std::f64::consts::PI], vec![1.0], Domain::Temporal).unwrap());
        let exc = Excitation::single(white, 0.0).unwrap();
        match linearize(&model, &exc, &Route1Options::default()).unwrap() {
            Route1Outcome::Converged(r) => println!("converged {:?} it {}", r.moments, r.iterations),
            Route1Outcome::NotConverged { reason, .. } => println!("not: {reason}"),
        }
        if let Ok(o) = WhiteNoiseOscillator::from_model(&model, &exc) { println!("{:?}", o.stationary().map(|s| s.variance)); }
    }
}
