//! The textbook's scraper road spectrum (8.66), as printed and in its dimensionally consistent form.

use super::{Asymptote, Domain, RationalSpectrum, Spectrum};
use crate::error::{require_non_negative, require_positive, Result};
use std::f64::consts::PI;

/// Which reading of the textbook's formula (8.66).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Form {
    /// Ŝ = 2D_q(α+β)αβ / ((α²+ω²)(α²+β²)), as printed: a one-pole (type 1) shape whose variance is
    /// D_q β(α+β)/(α²+β²), not D_q.
    AsPrinted,
    /// Ŝ = 2D_q αβ(α+β) / ((α²+ω²)(β²+ω²)): two poles, variance exactly D_q.
    Consistent,
}

/// The road spectrum of the textbook's scraper example (8.66), spatial (Ω in rad/m).
///
/// # Formula
/// Engineering convention Ŝ = 2πS as printed in the book; canonical S = Ŝ/(2π):
/// ```text
/// consistent:  S(Ω) = D_q αβ(α+β) / (π (α²+Ω²)(β²+Ω²)),
///              K(x) = D_q (β e^{−α|x|} − α e^{−β|x|}) / (β − α),      D = D_q
///              (α = β: K = D_q (1 + α|x|) e^{−α|x|})
/// as printed:  S(Ω) = D_q (α+β)αβ / (π (α²+β²)(α²+Ω²)),
///              K(x) = D_q β(α+β)/(α²+β²) · e^{−α|x|},                D = D_q β(α+β)/(α²+β²)
/// ```
/// The book's values are √D_q = 3.5 cm, α = 0.3, β = 12; units of α, β are not printed. The speed
/// dependence of Table 8.1 means the spectrum is spatial; this crate reads α, β in 1/m (an assumption,
/// stated wherever the spectrum is used). With those values the printed form's variance is 1.0244 D_q.
///
/// # Errors
/// [`TwoPoleRoad::build`] rejects D_q < 0, α ≤ 0, β ≤ 0 and non-finite values.
///
/// # Examples
/// ```
/// use stochvib::spectrum::{TwoPoleRoad, two_pole_road::Form, Spectrum};
/// let c = TwoPoleRoad { dq: 0.035f64.powi(2), alpha: 0.3, beta: 12.0, form: Form::Consistent }.build().unwrap();
/// assert!((c.variance().unwrap() - 0.035f64.powi(2)).abs() < 1e-18);
/// let p = TwoPoleRoad { dq: 0.035f64.powi(2), alpha: 0.3, beta: 12.0, form: Form::AsPrinted }.build().unwrap();
/// let ratio = 12.0 * 12.3 / (0.09 + 144.0);
/// assert!((p.variance().unwrap() / 0.035f64.powi(2) - ratio).abs() < 1e-14);
/// ```
#[derive(Debug, Clone, PartialEq)]
pub struct TwoPoleRoad {
    /// D_q, the profile's variance, m².
    pub dq: f64,
    /// α > 0, 1/m.
    pub alpha: f64,
    /// β > 0, 1/m.
    pub beta: f64,
    /// The formula as printed or in its dimensionally consistent form.
    pub form: Form,
}

impl TwoPoleRoad {
    /// The (8.66) road of these fields, checked: D_q (m²), α and β (1/m).
    ///
    /// # Errors
    /// See the type's `# Errors`.
    pub fn build(self) -> Result<Self> {
        let TwoPoleRoad { dq, alpha, beta, form } = self;
        Ok(TwoPoleRoad {
            dq: require_non_negative("dq", dq)?,
            alpha: require_positive("alpha", alpha)?,
            beta: require_positive("beta", beta)?,
            form,
        })
    }

    fn printed_variance(&self) -> f64 {
        let (a, b) = (self.alpha, self.beta);
        self.dq * b * (a + b) / (a * a + b * b)
    }
}

impl Spectrum for TwoPoleRoad {
    fn describe(&self) -> String {
        format!(
            "textbook (8.66) road, {}: D_q = {} m^2, alpha = {} 1/m, beta = {} 1/m (units assumed)",
            match self.form {
                Form::AsPrinted => "as printed (one pole)",
                Form::Consistent => "consistent form (two poles)",
            },
            crate::numbers::num(self.dq),
            crate::numbers::num(self.alpha),
            crate::numbers::num(self.beta)
        )
    }
    fn domain(&self) -> Domain {
        Domain::Spatial
    }
    fn density(&self, omega: f64) -> f64 {
        let (a, b, w2) = (self.alpha, self.beta, omega * omega);
        match self.form {
            Form::Consistent => self.dq * a * b * (a + b) / (PI * (a * a + w2) * (b * b + w2)),
            Form::AsPrinted => self.printed_variance() * a / (PI * (a * a + w2)),
        }
    }
    fn high_frequency(&self) -> Asymptote {
        let (a, b) = (self.alpha, self.beta);
        match self.form {
            Form::Consistent => Asymptote::Power {
                exponent: -4.0,
                coefficient: self.dq * a * b * (a + b) / PI,
            },
            Form::AsPrinted => Asymptote::Power {
                exponent: -2.0,
                coefficient: self.printed_variance() * a / PI,
            },
        }
    }
    fn low_frequency(&self) -> Asymptote {
        Asymptote::Power {
            exponent: 0.0,
            coefficient: self.density(0.0),
        }
    }
    fn breakpoints(&self) -> Vec<f64> {
        vec![self.alpha, self.beta]
    }
    fn variance(&self) -> Result<f64> {
        Ok(match self.form {
            Form::Consistent => self.dq,
            Form::AsPrinted => self.printed_variance(),
        })
    }
    fn correlation(&self, tau: f64) -> Result<f64> {
        let x = tau.abs();
        let (a, b) = (self.alpha, self.beta);
        Ok(match self.form {
            Form::AsPrinted => self.printed_variance() * (-a * x).exp(),
            Form::Consistent => {
                // (β e^{−αx} − α e^{−βx})/(β−α) = e^{−αx} [1 + α (1 − e^{−(β−α)x})/(β−α)], stable as β → α;
                // symmetric in α and β, so taken with α ≤ β (else e^{−(β−α)x} overflows for a large α)
                let (a, b) = (a.min(b), a.max(b));
                let d = b - a;
                let ratio = if d == 0.0 { x } else { -(-d * x).exp_m1() / d };
                self.dq * (-a * x).exp() * (1.0 + a * ratio)
            }
        })
    }
    fn rational(&self) -> Option<RationalSpectrum> {
        let (a, b) = (self.alpha, self.beta);
        let (num, den) = match self.form {
            Form::Consistent => (
                vec![self.dq * a * b * (a + b) / PI],
                vec![a * a * b * b, a * a + b * b, 1.0],
            ),
            Form::AsPrinted => (vec![self.printed_variance() * a / PI], vec![a * a, 1.0]),
        };
        RationalSpectrum::new(num, den, Domain::Spatial).ok()
    }
}
