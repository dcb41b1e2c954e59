//! Writes the synthetic "measured" two-track profile `data/measured-profile.csv`: ISO 8608 class C
//! (geometric mean G_d(n₀) = 256e-6 m³, w = 2) over 0.011–10 cycles/m, the two tracks 1.5 m apart with the
//! isotropic coherence (Dodds & Robson 1973), 10 000 samples at 0.05 m (500 m), from the named seed
//! [`ROAD_PROFILE_SEED`]. Elevations are written in mm to 0.001 mm, distances in m to 0.01 m.
//!
//! ```text
//! cargo run --release --example road_profile [-- OUTPUT.csv]
//! ```
//!
//! The test `measured_profile_*` in `tests/road.rs` reads the file back, regenerates it from the same
//! recipe, and checks the spatial density, the ISO class and the coherence against the model.

use std::path::PathBuf;
use stochvib::coherence::IsotropicCoherence;
use stochvib::road::{CsvWriteOptions, LengthUnit, Profile, Track, TwoTrackGenerator};
use stochvib::simulate::{stream, GENERATOR};
use stochvib::spectrum::{IsoBound, IsoClass, PowerLaw};

/// The seed of the committed file (realization 0 of this seed).
const ROAD_PROFILE_SEED: u64 = 8608;
/// Distance step, m.
const STEP_M: f64 = 0.05;
/// Samples per track (500 m).
const SAMPLES: usize = 10_000;
/// Track width B, m.
const TRACK_WIDTH_M: f64 = 1.5;
/// Band of the synthesised density, cycles/m: ISO 8608's lower limit, up to the Nyquist frequency.
const BAND: (f64, f64) = (0.011, 10.0);

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let out = std::env::args()
        .nth(1)
        .map(PathBuf::from)
        .unwrap_or_else(|| PathBuf::from("data/measured-profile.csv"));
    let spectrum = PowerLaw::iso8608(IsoClass::C, IsoBound::GeometricMean, Some(BAND))?;
    let coherence = IsotropicCoherence::new(TRACK_WIDTH_M, 2.0)?;
    let generator = TwoTrackGenerator::new(&spectrum, &coherence, STEP_M, SAMPLES)?;
    let (mut left, mut right) = (vec![0.0; SAMPLES], vec![0.0; SAMPLES]);
    generator.generate(
        &mut stream(ROAD_PROFILE_SEED, 0),
        &mut generator.scratch(),
        &mut left,
        &mut right,
    )?;
    let profile = Profile::new(
        STEP_M,
        0.0,
        vec![
            Track {
                name: "left".into(),
                elevation_m: left,
            },
            Track {
                name: "right".into(),
                elevation_m: right,
            },
        ],
    )?;
    let options = CsvWriteOptions {
        distance_unit: LengthUnit::M,
        elevation_unit: LengthUnit::Mm,
        distance_decimals: Some(2),
        elevation_decimals: Some(3),
        comments: vec![
            "Synthetic two-track road profile (not a measurement), written by".into(),
            "  cargo run --release --example road_profile   (stochvib examples/road_profile.rs)".into(),
            format!(
                "generator: stochvib::road::TwoTrackGenerator, random stream: realization 0 of seed {ROAD_PROFILE_SEED} ({GENERATOR})"
            ),
            format!(
                "density: ISO 8608 class C geometric mean, G_d(0.1 cycles/m) = 256e-6 m^3, w = 2, band {}-{} cycles/m",
                BAND.0, BAND.1
            ),
            format!(
                "coherence: isotropic surface (Dodds & Robson 1973), track width {TRACK_WIDTH_M} m, rho = x K1(x), x = 2 pi n B"
            ),
            format!(
                "{SAMPLES} samples at {STEP_M} m (one period of the FFT synthesis), elevations rounded to 0.001 mm"
            ),
        ],
    };
    profile.write_csv(&out, &options)?;
    println!(
        "wrote {} ({} samples per track, seed {ROAD_PROFILE_SEED})",
        out.display(),
        SAMPLES
    );
    Ok(())
}
