//! Records as WAV files (as some data loggers write them): PCM integer or IEEE float samples, interleaved
//! channels, the sample rate in the header; read with the `hound` crate (pure Rust, PCM 8–32 bit and float,
//! `WAVE_FORMAT_EXTENSIBLE`; no system library), a block of frames at a time.
//!
//! A WAV file stores no unit and no scale: the physical value of full scale must be stated
//! ([`RecordOptions::full_scale`], e.g. `50 m/s^2`), else the file is refused. A float sample v is
//! v·full scale; an integer sample i of b bits is i/2^(b−1)·full scale (the most negative integer is −full
//! scale). Channel names are stated ([`RecordOptions::channel_names`]) or `ch1`, `ch2`, ….

use super::hdf5::not_finite;
use super::source::{channel, RecordInfo, RecordOptions, RecordReader, TimeBase};
use crate::error::{Error, Result};
use crate::io_rules::{open_input, InputKind};
use std::io::BufReader;
use std::path::Path;

/// WAV records: at most 4 GiB (the format's own limit).
pub const WAV_INPUT: InputKind = InputKind {
    what: "WAV file",
    max_bytes: Some(4 << 30),
    too_large_hint: "a WAV file cannot be larger; store long records as HDF5",
};

/// A WAV record being read (see the [module docs](self)).
pub struct WavRecord {
    info: RecordInfo,
    reader: hound::WavReader<BufReader<std::fs::File>>,
    /// factor from the stored sample to SI (full scale in SI over the format's full scale)
    scale: f64,
    float: bool,
    frame: usize,
    frames: usize,
}

impl WavRecord {
    /// Opens `path` and reads its header.
    ///
    /// # Errors
    /// The refusals of [`open_input`]; a file that is not a WAV file hound can read; no full scale stated
    /// (or one with an unknown unit); channel names whose number differs from the file's channels.
    pub fn open(path: &Path, options: &RecordOptions) -> Result<Self> {
        let (file, _) = open_input(path, WAV_INPUT)?;
        let reader = hound::WavReader::new(BufReader::with_capacity(1 << 16, file))
            .map_err(|e| Error::in_file(path, "header", "<WAV header>", format!("not a readable WAV file: {e}")))?;
        let spec = reader.spec();
        let n_ch = spec.channels as usize;
        let names: Vec<String> = if options.channel_names.is_empty() {
            (1..=n_ch).map(|i| format!("ch{i}")).collect()
        } else if options.channel_names.len() == n_ch {
            options.channel_names.clone()
        } else {
            return Err(Error::invalid(
                "--channels",
                options.channel_names.join(","),
                format!(
                    "{} names for a WAV file of {n_ch} channels",
                    options.channel_names.len()
                ),
            ));
        };
        let full = options.full_scale.as_deref().ok_or_else(|| {
            Error::in_file(
                path,
                "full scale",
                "<missing>",
                "a WAV file stores no unit or scale: state the physical value of full scale with --full-scale, e.g. \
                 `--full-scale \"50 m/s^2\"`; a unit is never guessed",
            )
        })?;
        let (value, unit) = split_value_unit(full)
            .ok_or_else(|| Error::invalid("--full-scale", full, "expected a number and a unit, e.g. `50 m/s^2`"))?;
        let mut channels = Vec::with_capacity(n_ch);
        for name in &names {
            channels.push(channel(path, "--full-scale", name, unit)?);
        }
        let float = spec.sample_format == hound::SampleFormat::Float;
        let format_full = if float {
            1.0
        } else {
            2f64.powi(i32::from(spec.bits_per_sample) - 1)
        };
        let scale = value * channels[0].to_si / format_full;
        for c in &mut channels {
            c.unit = format!("{unit} (full scale {value})");
        }
        let frames = reader.duration() as usize;
        if frames == 0 {
            return Err(Error::in_file(path, "data", "0 frames", "the record is empty"));
        }
        Ok(WavRecord {
            info: RecordInfo {
                source: path.to_path_buf(),
                format: "WAV",
                sample_rate_hz: f64::from(spec.sample_rate),
                time_base: TimeBase::WavHeader,
                channels,
                samples_hint: Some(frames),
            },
            reader,
            scale,
            float,
            frame: 0,
            frames,
        })
    }
}

/// `"50 m/s^2"` (or `"50m/s^2"`) → (50, "m/s^2").
fn split_value_unit(text: &str) -> Option<(f64, &str)> {
    let (number, unit) = crate::units::split_number(text.trim())?;
    let v: f64 = number.parse().ok()?;
    (v.is_finite() && v > 0.0 && !unit.trim().is_empty()).then_some((v, unit.trim()))
}

impl RecordReader for WavRecord {
    fn info(&self) -> &RecordInfo {
        &self.info
    }

    fn read_block(&mut self, out: &mut [Vec<f64>], max: usize) -> Result<usize> {
        for o in out.iter_mut() {
            o.clear();
        }
        let n = max.min(self.frames - self.frame);
        let n_ch = out.len();
        let path = self.info.source.clone();
        let truncated = |frame: usize, e: hound::Error| {
            Error::in_file(
                &path,
                format!("frame {frame}"),
                "<samples>",
                format!("truncated or unreadable: {e}"),
            )
        };
        if self.float {
            let mut it = self.reader.samples::<f32>();
            for k in 0..n {
                for (c, o) in out.iter_mut().enumerate().take(n_ch) {
                    let v = it
                        .next()
                        .ok_or_else(|| truncated(self.frame + k, hound::Error::UnfinishedSample))?;
                    let v = f64::from(v.map_err(|e| truncated(self.frame + k, e))?);
                    if !v.is_finite() {
                        return Err(not_finite(&path, &format!("channel {}", c + 1), self.frame + k, v));
                    }
                    o.push(v * self.scale);
                }
            }
        } else {
            let mut it = self.reader.samples::<i32>();
            for k in 0..n {
                for o in out.iter_mut().take(n_ch) {
                    let v = it
                        .next()
                        .ok_or_else(|| truncated(self.frame + k, hound::Error::UnfinishedSample))?;
                    o.push(f64::from(v.map_err(|e| truncated(self.frame + k, e))?) * self.scale);
                }
            }
        }
        self.frame += n;
        Ok(n)
    }
}
