//! Writes an `.fmu`: a deflate zip (FMI 2.0 requires deflate; forward slashes) holding
//! `modelDescription.xml`, `binaries/<platform>/<modelIdentifier><suffix>`,
//! `documentation/index.html` and the bundled files under `resources/`.

use crate::platform::Platform;
use railcontact::fmi::model::ModelInfo;
use std::collections::BTreeMap;
use std::io::Write;
use std::path::{Path, PathBuf};
use zip::write::SimpleFileOptions;
use zip::CompressionMethod;

/// Files to bundle under `resources/`, by their name there.
#[derive(Debug, Default)]
pub struct Resources(BTreeMap<String, PathBuf>);

impl Resources {
    /// Checks the `--resource` files: readable regular files with distinct UTF-8 names (a
    /// model parameter names a bundled file by its bare name).
    pub fn new(files: &[PathBuf]) -> Result<Resources, String> {
        let mut map = BTreeMap::new();
        for file in files {
            if !file.is_file() {
                return Err(format!(
                    "--resource {}: not a file ({})",
                    file.display(),
                    if file.exists() {
                        "a directory or special file"
                    } else {
                        "no such file"
                    }
                ));
            }
            let name = file
                .file_name()
                .and_then(|n| n.to_str())
                .ok_or_else(|| format!("--resource {}: the name is not UTF-8", file.display()))?
                .to_string();
            if let Some(other) = map.insert(name.clone(), file.clone()) {
                return Err(format!(
                    "--resource: {} and {} would both be resources/{name}",
                    other.display(),
                    file.display()
                ));
            }
        }
        Ok(Resources(map))
    }

    pub fn names(&self) -> impl Iterator<Item = &str> {
        self.0.keys().map(String::as_str)
    }
}

pub fn write_fmu(
    info: &ModelInfo,
    library: &Path,
    platform: &Platform,
    resources: &Resources,
    fmu: &Path,
) -> Result<(), String> {
    let read = |p: &Path| std::fs::read(p).map_err(|e| format!("{}: {e}", p.display()));
    let binary = read(library)?;
    let html = crate::docs::index_html(info);
    let mut entries: Vec<(String, Vec<u8>, u32)> = vec![
        (
            "modelDescription.xml".to_string(),
            info.model_description_xml.as_bytes().to_vec(),
            0o644,
        ),
        (platform.fmu_library(info.model_identifier), binary, 0o755),
        (
            "documentation/index.html".to_string(),
            html.into_bytes(),
            0o644,
        ),
    ];
    for (name, path) in &resources.0 {
        entries.push((format!("resources/{name}"), read(path)?, 0o644));
    }

    let file = std::fs::File::create(fmu).map_err(|e| format!("{}: {e}", fmu.display()))?;
    let mut zip = zip::ZipWriter::new(file);
    let options = SimpleFileOptions::default().compression_method(CompressionMethod::Deflated);
    for (name, bytes, mode) in entries {
        zip.start_file(name.as_str(), options.unix_permissions(mode))
            .map_err(|e| format!("{}: {name}: {e}", fmu.display()))?;
        zip.write_all(&bytes)
            .map_err(|e| format!("{}: {name}: {e}", fmu.display()))?;
    }
    zip.finish()
        .map_err(|e| format!("{}: {e}", fmu.display()))?;
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::platform::Platform;
    use railcontact::models::wheel_rail_contact::INFO;

    fn scratch(name: &str) -> PathBuf {
        let dir = std::env::temp_dir().join(format!("fmu-pack-{name}-{}", std::process::id()));
        let _ = std::fs::remove_dir_all(&dir);
        std::fs::create_dir_all(&dir).unwrap();
        dir
    }

    fn entry_names(fmu: &Path) -> Vec<String> {
        let archive = zip::ZipArchive::new(std::fs::File::open(fmu).unwrap()).unwrap();
        let mut names: Vec<String> = archive.file_names().map(String::from).collect();
        names.sort();
        names
    }

    #[test]
    fn platform_folder_library_name_and_resources_in_the_archive() {
        let dir = scratch("entries");
        let library = dir.join("lib.bin");
        std::fs::write(&library, b"not a library").unwrap();
        let a = dir.join("a.prw");
        std::fs::write(&a, b"wheel").unwrap();
        let sub = dir.join("sub");
        std::fs::create_dir_all(&sub).unwrap();
        let b = sub.join("b.prr");
        std::fs::write(&b, b"rail").unwrap();
        let resources = Resources::new(&[b.clone(), a.clone()]).unwrap();
        assert_eq!(resources.names().collect::<Vec<_>>(), ["a.prw", "b.prr"]);
        for (triple, binary) in [
            (
                "x86_64-unknown-linux-gnu",
                "binaries/linux64/WheelRailContact.so",
            ),
            (
                "x86_64-pc-windows-msvc",
                "binaries/win64/WheelRailContact.dll",
            ),
            (
                "x86_64-apple-darwin",
                "binaries/darwin64/WheelRailContact.dylib",
            ),
        ] {
            let platform = Platform::of_target(triple).unwrap();
            let fmu = dir.join("x.fmu");
            write_fmu(&INFO, &library, &platform, &resources, &fmu).unwrap();
            assert_eq!(
                entry_names(&fmu),
                [
                    binary,
                    "documentation/index.html",
                    "modelDescription.xml",
                    "resources/a.prw",
                    "resources/b.prr",
                ]
            );
            let mut archive = zip::ZipArchive::new(std::fs::File::open(&fmu).unwrap()).unwrap();
            let mut text = String::new();
            std::io::Read::read_to_string(
                &mut archive.by_name("resources/b.prr").unwrap(),
                &mut text,
            )
            .unwrap();
            assert_eq!(text, "rail");
            for i in 0..archive.len() {
                let e = archive.by_index(i).unwrap();
                assert_eq!(e.compression(), CompressionMethod::Deflated, "{}", e.name());
            }
        }
        let _ = std::fs::remove_dir_all(&dir);
    }

    #[test]
    fn bad_resources_are_refused() {
        let dir = scratch("bad");
        let e = Resources::new(&[dir.join("missing.prw")]).unwrap_err();
        assert!(
            e.contains("missing.prw") && e.contains("no such file"),
            "{e}"
        );
        let e = Resources::new(std::slice::from_ref(&dir)).unwrap_err();
        assert!(e.contains("a directory"), "{e}");
        let (x, y) = (dir.join("p.prw"), dir.join("q").join("p.prw"));
        std::fs::create_dir_all(y.parent().unwrap()).unwrap();
        std::fs::write(&x, b"1").unwrap();
        std::fs::write(&y, b"2").unwrap();
        let e = Resources::new(&[x, y]).unwrap_err();
        assert!(e.contains("both be resources/p.prw"), "{e}");
        let _ = std::fs::remove_dir_all(&dir);
    }
}
