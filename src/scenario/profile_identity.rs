//! The identity of a measured profile behind a `measured-profile` spectrum: a run records the CSV's name,
//! size and CRC-32, so that a resume after the profile changed is refused naming it.

use super::catalogue::SpectrumOrigin;
use super::scenario_file::ScenarioInput;
use crate::store::{checksum::Crc32, Provenance};
use std::path::{Path, PathBuf};

/// The profile CSV of input `inp` if its spectrum is of kind `measured-profile`: (the `file` key as
/// written, the path it resolves to — relative to the file that names it, as
/// [`spectrum_from_fields`](super::spectrum_file::spectrum_from_fields) resolves it: the spectrum file, or
/// the scenario `scenario_path` for an inline table).
pub(crate) fn measured_profile_file(inp: &ScenarioInput, scenario_path: &Path) -> Option<(String, PathBuf)> {
    let table: toml::Table = toml::from_str(&inp.spectrum_text).ok()?;
    if table.get("kind")?.as_str()? != "measured-profile" {
        return None;
    }
    let file = table.get("file")?.as_str()?.to_string();
    let naming = match &inp.origin {
        SpectrumOrigin::Catalogue { file, .. } => file.as_path(),
        SpectrumOrigin::File { path } => path.as_path(),
        SpectrumOrigin::Inline => scenario_path,
    };
    let path = match naming.parent() {
        Some(dir) => dir.join(&file),
        None => PathBuf::from(&file),
    };
    Some((file, path))
}

/// The provenance parts of the measured profile of input `inp` (none for other spectra): the identity
/// `name` = "`<file as written>` (<size> bytes, CRC-32 <8 hex digits>)" and the note `<name>_path` (the
/// resolved path, which may differ between working directories and so does not identify the run). An
/// unreadable file is recorded as such (it then differs from any readable one).
///
/// # Formula
/// CRC-32 of the file's bytes (IEEE 802.3, [`crc32`]).
pub(crate) fn profile_provenance(inp: &ScenarioInput, scenario_path: &Path, name: &str) -> Vec<Provenance> {
    let Some((file, path)) = measured_profile_file(inp, scenario_path) else {
        return Vec::new();
    };
    let identity = match file_crc32(&path) {
        Ok((len, crc)) => format!("{file} ({len} bytes, CRC-32 {crc:08x})"),
        Err(e) => format!("{file} (unreadable: {e})"),
    };
    vec![
        Provenance::identity(name, identity),
        Provenance::note(&format!("{name}_path"), path.display().to_string()),
    ]
}

/// Input `inp` of the scenario file `scenario_path` as its file names it, for reports: a measured profile by
/// its CSV file and track (`measured-profile.csv (measured profile, track left)`), a catalogue spectrum or
/// spectrum file by its name as written with the spectrum's description, an inline table by its `name` (if
/// any) with the description.
///
/// # Examples
/// ```
/// use std::path::Path;
/// let sc = stochvib::scenario::load_scenario(Path::new("data/quarter-car.toml"), Path::new("spectra")).unwrap();
/// let s = stochvib::scenario::input_as_written(&sc.input, &sc.path);
/// assert!(s.starts_with("iso8608-c ("), "{s}");
/// ```
pub fn input_as_written(inp: &ScenarioInput, scenario_path: &Path) -> String {
    if let Some((file, _)) = measured_profile_file(inp, scenario_path) {
        let table: toml::Table = toml::from_str(&inp.spectrum_text).unwrap_or_default();
        let track = table.get("track").and_then(|t| t.as_str());
        return match track {
            Some(t) => format!("{file} (measured profile, track {t})"),
            None => format!("{file} (measured profile, first track)"),
        };
    }
    let inline_name = match inp.origin {
        SpectrumOrigin::Inline => toml::from_str::<toml::Table>(&inp.spectrum_text)
            .ok()
            .and_then(|t| t.get("name").and_then(|n| n.as_str()).map(str::to_string)),
        _ => None,
    };
    let name = inline_name.unwrap_or_else(|| inp.reference.clone());
    format!("{name} ({})", inp.spectrum.describe())
}

/// The size and CRC-32 of a file read under the input rule ([`crate::io_rules::open_input`], CSV limit),
/// 64 KiB at a time.
fn file_crc32(path: &Path) -> crate::Result<(u64, u32)> {
    use std::io::Read;
    let (mut f, _) = crate::io_rules::open_input(path, crate::io_rules::CSV_INPUT)?;
    let mut c = Crc32::default();
    let mut buf = vec![0u8; 1 << 16];
    let mut len = 0u64;
    loop {
        let n = f.read(&mut buf).map_err(|source| crate::Error::Io {
            path: path.to_path_buf(),
            source,
        })?;
        if n == 0 {
            return Ok((len, c.finish()));
        }
        c.update(&buf[..n]);
        len += n as u64;
    }
}
