//! The bearing an instance simulates: `<fmuResourceLocation>/bearing.json`, written by the
//! packager, or the compiled-in default preset when no usable location or file is given; and
//! how it was packaged, `<fmuResourceLocation>/packaging.json` (`crate::packaging`: start
//! values chosen at packaging, Enumerations declared as Integers), none when that file is
//! missing.

use crate::bearing::{Bearing, DEFAULT_PRESET};
use crate::packaging::{self, Packaging};
use std::path::{Path, PathBuf};

/// The bearing, how it was packaged, and a warning to log when it is the fallback preset.
pub struct Loaded {
    pub bearing: Bearing,
    pub packaging: Packaging,
    pub warning: Option<String>,
}

/// The local directory a resource location names. Accepts `file:///abs`, `file:/abs`,
/// `file://localhost/abs` (with or without trailing slash, percent-escapes decoded) and,
/// leniently, a plain absolute path.
pub fn resource_dir(location: &str) -> Result<PathBuf, String> {
    let is_file_uri = location.get(..5).is_some_and(|s| s.eq_ignore_ascii_case("file:"));
    if is_file_uri {
        let url = url::Url::parse(location).map_err(|e| format!("fmuResourceLocation \"{location}\" is not a valid URI: {e}"))?;
        url.to_file_path()
            .map_err(|()| format!("fmuResourceLocation \"{location}\" does not name a local directory"))
    } else if Path::new(location).is_absolute() {
        Ok(PathBuf::from(location))
    } else {
        Err(format!(
            "fmuResourceLocation \"{location}\" is not a file URI (file:///path/to/resources)"
        ))
    }
}

/// Load the bearing for resource location `location` (None or empty: the default preset).
/// A malformed bearing file or an unusable location is an error; a missing file is not.
pub fn load(location: Option<&str>) -> Result<Loaded, String> {
    let location = location.unwrap_or("");
    if location.is_empty() {
        return Ok(Loaded {
            bearing: Bearing::default_preset(),
            packaging: Packaging::default(),
            warning: Some(format!(
                "no fmuResourceLocation given; using the compiled-in bearing {DEFAULT_PRESET}"
            )),
        });
    }
    let dir = resource_dir(location)?;
    let path = dir.join("bearing.json");
    let (bearing, warning) = match std::fs::read_to_string(&path) {
        Ok(text) => (Bearing::from_json(&text).map_err(|e| format!("{}: {e}", path.display()))?, None),
        Err(e) if e.kind() == std::io::ErrorKind::NotFound => (
            Bearing::default_preset(),
            Some(format!(
                "{} not found; using the compiled-in bearing {DEFAULT_PRESET}",
                path.display()
            )),
        ),
        Err(e) => return Err(format!("cannot read {}: {e}", path.display())),
    };
    let path = dir.join(packaging::RESOURCE);
    let packaging = match std::fs::read_to_string(&path) {
        Ok(text) => Packaging::from_json(&text, bearing.roller_count).map_err(|e| format!("{}: {e}", path.display()))?,
        Err(e) if e.kind() == std::io::ErrorKind::NotFound => Packaging::default(),
        Err(e) => return Err(format!("cannot read {}: {e}", path.display())),
    };
    Ok(Loaded {
        bearing,
        packaging,
        warning,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn uri_variants() {
        for (loc, want) in [
            ("file:///a/b/resources", "/a/b/resources"),
            ("file:///a/b/resources/", "/a/b/resources/"),
            ("file:/a/b/resources", "/a/b/resources"),
            ("file://localhost/a/b/resources", "/a/b/resources"),
            ("FILE:///a/with%20space/r%25s", "/a/with space/r%s"),
            ("/a/b/resources", "/a/b/resources"),
        ] {
            assert_eq!(resource_dir(loc).unwrap(), PathBuf::from(want), "{loc}");
        }
        assert!(resource_dir("file://otherhost/a").is_err());
        assert!(resource_dir("http://example.com/resources").is_err());
        assert!(resource_dir("relative/path").is_err());
    }
}
