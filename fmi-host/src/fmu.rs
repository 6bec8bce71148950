//! An FMU a host can instantiate: its functions (linked or from a loaded library), its model
//! description and the resource location its instances get.

use crate::description::ModelDescription;
use crate::functions::Functions;
use crate::instance::Instance;
use crate::Error;
use libloading::Library;
use std::ffi::CStr;
use std::path::{Path, PathBuf};
use std::sync::Arc;

/// One FMU: shared by its instances (each holds an `Arc`), so a loaded library stays loaded
/// until the last instance is freed.
pub struct Fmu {
    functions: Functions,
    description: ModelDescription,
    resource_uri: Option<String>,
    /// The library the functions live in (None: linked into this program). Declared last, so
    /// it is unloaded after everything else is dropped.
    _library: Option<Library>,
}

impl Fmu {
    /// An FMU linked into this program (see [`linked_functions!`](crate::linked_functions)),
    /// described by `model_description_xml`; its instances get `resource_uri`.
    pub fn linked(
        functions: Functions,
        model_description_xml: &str,
        resource_uri: Option<String>,
    ) -> Result<Arc<Self>, Error> {
        Ok(Arc::new(Self {
            functions,
            description: ModelDescription::parse(model_description_xml)?,
            resource_uri,
            _library: None,
        }))
    }

    /// The unzipped FMU in `dir`: reads `modelDescription.xml`, loads
    /// `binaries/<platform_folder>/<modelIdentifier><this system's library suffix>`, checks that
    /// it exports all 34 FMI 2.0 Co-Simulation functions; its instances get the `file:` URI of
    /// `dir/resources`.
    pub fn load(dir: &Path, platform_folder: &str) -> Result<Arc<Self>, Error> {
        let xml_path = dir.join("modelDescription.xml");
        let xml = std::fs::read_to_string(&xml_path).map_err(|e| io(&xml_path, e))?;
        let description = ModelDescription::parse(&xml)?;
        let library_path = dir.join("binaries").join(platform_folder).join(format!(
            "{}{}",
            description.model_identifier,
            std::env::consts::DLL_SUFFIX
        ));
        let library = load_library(&library_path)?;
        // SAFETY: an FMU's exports have the signatures of the FMI 2.0 headers.
        let functions =
            unsafe { Functions::resolve(&library) }.map_err(|names| Error::MissingExports {
                path: library_path.clone(),
                names,
            })?;
        let resources = std::path::absolute(dir.join("resources")).map_err(|e| io(dir, e))?;
        Ok(Arc::new(Self {
            functions,
            description,
            resource_uri: Some(file_uri(&resources)),
            _library: Some(library),
        }))
    }

    pub fn description(&self) -> &ModelDescription {
        &self.description
    }

    pub fn functions(&self) -> &Functions {
        &self.functions
    }

    /// The `fmuResourceLocation` its instances get.
    pub fn resource_uri(&self) -> Option<&str> {
        self.resource_uri.as_deref()
    }

    /// `fmi2GetTypesPlatform`.
    pub fn types_platform(&self) -> String {
        // SAFETY: takes no argument; returns a static string.
        unsafe { static_text((self.functions.fmi2GetTypesPlatform)()) }
    }

    /// `fmi2GetVersion`.
    pub fn version(&self) -> String {
        // SAFETY: takes no argument; returns a static string.
        unsafe { static_text((self.functions.fmi2GetVersion)()) }
    }

    /// An instance `name` with the model's GUID and this FMU's resource location.
    pub fn instantiate(self: &Arc<Self>, name: &str) -> Result<Instance, Error> {
        let guid = self.description.guid.clone();
        self.instantiate_as(name, &guid, self.resource_uri.as_deref())
    }

    /// An instance `name` with the given GUID and resource location (None: NULL), for hosts
    /// that test how an FMU refuses them.
    pub fn instantiate_as(
        self: &Arc<Self>,
        name: &str,
        guid: &str,
        resource_uri: Option<&str>,
    ) -> Result<Instance, Error> {
        Instance::new(Arc::clone(self), name, guid, resource_uri)
    }
}

fn load_library(path: &Path) -> Result<Library, Error> {
    // SAFETY: loading an FMU's library runs its initialisers; that is what hosting it means.
    unsafe { Library::new(path) }.map_err(|e| Error::Library {
        path: path.to_path_buf(),
        reason: e.to_string(),
    })
}

/// Copies a static C string an FMU returned (NULL reads as "").
///
/// # Safety
/// `s` is NULL or NUL-terminated.
unsafe fn static_text(s: *const std::ffi::c_char) -> String {
    if s.is_null() {
        return String::new();
    }
    // SAFETY: the caller's contract.
    unsafe { CStr::from_ptr(s) }.to_string_lossy().into_owned()
}

pub(crate) fn io(path: &Path, e: std::io::Error) -> Error {
    Error::Io {
        path: path.to_path_buf(),
        reason: e.to_string(),
    }
}

/// A `file:` URI of an absolute path as hosts give `fmuResourceLocation`: `file:///abs/path`
/// with forward slashes (`file:///C:/dir` on Windows) and bytes other than unreserved
/// characters, `/` and `:` percent-encoded.
pub fn file_uri(path: &Path) -> String {
    let mut text = path.to_string_lossy().into_owned();
    if cfg!(windows) {
        text = text.replace('\\', "/");
    }
    let mut uri = String::from("file://");
    if !text.starts_with('/') {
        uri.push('/');
    }
    for b in text.bytes() {
        if b.is_ascii_alphanumeric() || b"-._~/:".contains(&b) {
            uri.push(b as char);
        } else {
            uri.push_str(&format!("%{b:02X}"));
        }
    }
    uri
}

/// Extracts the FMU archive `fmu` into `dir`, refusing entries whose names would leave it.
pub fn unzip(fmu: &Path, dir: &Path) -> Result<(), Error> {
    let archive_error = |reason: String| Error::Archive {
        path: fmu.to_path_buf(),
        reason,
    };
    let file = std::fs::File::open(fmu).map_err(|e| io(fmu, e))?;
    let mut archive = zip::ZipArchive::new(file).map_err(|e| archive_error(e.to_string()))?;
    for i in 0..archive.len() {
        let mut entry = archive
            .by_index(i)
            .map_err(|e| archive_error(format!("entry {i}: {e}")))?;
        let Some(relative) = entry.enclosed_name() else {
            return Err(archive_error(format!(
                "entry {:?} would be extracted outside {}",
                entry.name(),
                dir.display()
            )));
        };
        let path: PathBuf = dir.join(relative);
        if entry.is_dir() {
            std::fs::create_dir_all(&path).map_err(|e| io(&path, e))?;
            continue;
        }
        if let Some(parent) = path.parent() {
            std::fs::create_dir_all(parent).map_err(|e| io(parent, e))?;
        }
        let mut out = std::fs::File::create(&path).map_err(|e| io(&path, e))?;
        std::io::copy(&mut entry, &mut out).map_err(|e| io(&path, e))?;
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn file_uris_of_paths() {
        assert_eq!(
            file_uri(Path::new("/tmp/a b/résources")),
            "file:///tmp/a%20b/r%C3%A9sources"
        );
        assert_eq!(
            file_uri(Path::new(r"C:\x\resources")),
            if cfg!(windows) {
                "file:///C:/x/resources"
            } else {
                "file:///C:%5Cx%5Cresources"
            }
        );
    }
}
