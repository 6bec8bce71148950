//! Writes an `.fmu`: a deflate zip (FMI 2.0 requires deflate; forward slashes) holding
//! `modelDescription.xml`, `binaries/linux64/<modelIdentifier>.so` and
//! `documentation/index.html`.

use railcontact::fmi::model::ModelInfo;
use std::io::Write;
use std::path::Path;
use zip::write::SimpleFileOptions;
use zip::CompressionMethod;

pub fn write_fmu(info: &ModelInfo, library: &Path, fmu: &Path) -> Result<(), String> {
    let binary = std::fs::read(library).map_err(|e| format!("{}: {e}", library.display()))?;
    let file = std::fs::File::create(fmu).map_err(|e| format!("{}: {e}", fmu.display()))?;
    let html = crate::docs::index_html(info);
    let mut zip = zip::ZipWriter::new(file);
    let options = SimpleFileOptions::default()
        .compression_method(CompressionMethod::Deflated)
        .unix_permissions(0o644);
    let entries: [(String, &[u8]); 3] = [
        (
            "modelDescription.xml".to_string(),
            info.model_description_xml.as_bytes(),
        ),
        (
            format!("binaries/linux64/{}.so", info.model_identifier),
            &binary,
        ),
        ("documentation/index.html".to_string(), html.as_bytes()),
    ];
    for (name, bytes) in entries {
        let opts = if name.ends_with(".so") {
            options.unix_permissions(0o755)
        } else {
            options
        };
        zip.start_file(name.as_str(), opts)
            .map_err(|e| format!("{}: {name}: {e}", fmu.display()))?;
        zip.write_all(bytes)
            .map_err(|e| format!("{}: {name}: {e}", fmu.display()))?;
    }
    zip.finish()
        .map_err(|e| format!("{}: {e}", fmu.display()))?;
    Ok(())
}
