//! Pictures: spectra, frequency responses, output densities with their cumulative variance, and the
//! Monte Carlo and catalogue-model checks, written as SVG and PNG with `plotters` (pure-Rust back ends and
//! a bundled font: no system font library is needed).
//!
//! * [`chart`]: the generic layer — [`LineChart`] (log or linear axes, bands, markers, a secondary axis),
//!   [`BarChart`] (values against limits), [`Histogram`] (with overlaid density curves and markers). Each
//!   renders to `<stem>.svg` and `<stem>.png` (800 × 500) in a directory.
//! * [`scenario_plots`](mod@scenario_plots): input density, |H(iω)|² and output densities of a loaded
//!   [`Scenario`](crate::scenario::Scenario).
//! * [`mc_plots`]: Monte Carlo checks from plain data (realizations, histogram against N(M, σ), Welch
//!   estimate against the analytic density, correlation estimate against the model).
//! * [`model_plots`]: catalogue-model pictures from plain data (octave-band RMS against limits, mine-hoist
//!   frequencies and modes over ξ, balancer D_y/D_x over r, scraper σ over speed).
//!
//! * [`record_plots`]: the pictures of `stochvib exposure` and `stochvib fatigue` (weighted time history,
//!   band spectrum against the comfort scale, rainflow ranges against Dirlik, the rainflow matrix).
//! * [`road_plots`](mod@road_plots): the pictures of `stochvib road PROFILE.csv --plots DIR` (measured density
//!   with its χ² band, the ISO 8608 fits and class limits, the two-track coherence).
//! * [`run_plots`](mod@run_plots): the pictures of a Monte Carlo run file (`stochvib plot run.h5`).
//! * [`book_plots`](mod@book_plots): the pictures of `stochvib book --plots DIR`, every catalogue model's data
//!   computed with the library.
//! * [`pareto_plots`]: the Pareto front of `stochvib optimize --pareto Q --plots DIR`.
//!
//! * [`style`](mod@style): the look every chart shares (Okabe–Ito palette, marker shapes, fonts, tick labels
//!   in engineering notation at the decades of a logarithmic axis); [`legend`](mod@legend): the legend placed
//!   where the data are not. The drawing itself is in the private module `draw`.
//!
//! Axis labels carry the quantity and its unit; titles name the scenario or model. `docs/gallery.md` shows
//! one picture of each kind.

pub mod book_plots;
pub mod chart;
pub mod comfort_plots;
mod draw;
pub mod legend;
pub mod mc_plots;
pub mod model_plots;
pub mod nonlinear_plots;
pub mod pareto_plots;
pub mod record_plots;
pub mod road_plots;
pub mod run_plots;
pub mod scenario_plots;
pub mod transient_plots;

pub mod style;

pub use book_plots::book_plots;
pub use chart::{
    Band, BarChart, Histogram, Legend, LineChart, LineStyle, Marker, Role, SecondaryAxis, Series, HEIGHT, WIDTH,
};
pub use road_plots::road_plots;
pub use run_plots::{rainflow_charts, run_plots};
pub use scenario_plots::{scenario_plots, scenario_plots_with, ScenarioPlotOptions};
