//! The FMI 2.0 platform of a Rust target: the `binaries/<folder>` an FMU keeps its library in,
//! the library's suffix, and the file name Cargo gives the cdylib.
//!
//! FMI 2.0 names five folders: `linux32`, `linux64`, `win32`, `win64` and `darwin64` (32-bit x86
//! and x86-64 Linux and Windows; 64-bit macOS, which hosts also use on Apple silicon). Targets
//! without one of these folders (ARM Linux or Windows, musl, BSDs) are refused with a message
//! rather than packed under a folder no host looks in.

use std::process::Command;

#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Platform {
    /// The FMI 2.0 platform folder under `binaries/`.
    pub folder: &'static str,
    /// The shared library's suffix, dot included.
    pub suffix: &'static str,
    /// Cargo's prefix of a cdylib's file name (`lib` except on Windows).
    prefix: &'static str,
}

const LINUX64: Platform = Platform::new("linux64", ".so", "lib");
const LINUX32: Platform = Platform::new("linux32", ".so", "lib");
const WIN64: Platform = Platform::new("win64", ".dll", "");
const WIN32: Platform = Platform::new("win32", ".dll", "");
const DARWIN64: Platform = Platform::new("darwin64", ".dylib", "lib");

impl Platform {
    /// The platform of `folder` whose libraries are named `<prefix><name><suffix>`.
    const fn new(folder: &'static str, suffix: &'static str, prefix: &'static str) -> Platform {
        Platform {
            folder,
            suffix,
            prefix,
        }
    }

    /// The platform of a target triple such as `x86_64-unknown-linux-gnu`,
    /// `x86_64-pc-windows-msvc` or `aarch64-apple-darwin`.
    pub fn of_target(triple: &str) -> Result<Platform, String> {
        let arch = triple.split('-').next().unwrap_or("");
        let x86_64 = arch == "x86_64";
        let x86 = matches!(arch, "i686" | "i586" | "i386");
        let platform = if triple.ends_with("-linux-gnu") {
            (x86_64, x86, LINUX64, LINUX32)
        } else if triple.contains("-windows-") {
            (x86_64, x86, WIN64, WIN32)
        } else if triple.ends_with("-apple-darwin") {
            // FMI 2.0 has no folder for Apple silicon: hosts look in darwin64 there too.
            (x86_64 || arch == "aarch64", false, DARWIN64, DARWIN64)
        } else {
            (false, false, LINUX64, LINUX32)
        };
        match platform {
            (true, _, p64, _) => Ok(p64),
            (_, true, _, p32) => Ok(p32),
            _ => Err(format!(
                "target {triple:?} has no FMI 2.0 platform folder: supported are x86-64 and \
                 32-bit x86 Linux (gnu) and Windows (linux64, linux32, win64, win32) and macOS \
                 (darwin64)"
            )),
        }
    }

    /// The file name Cargo gives the cdylib of crate `crate_name` on this platform.
    pub fn cargo_library(&self, crate_name: &str) -> String {
        format!("{}{crate_name}{}", self.prefix, self.suffix)
    }

    /// The path of a model's library inside the FMU.
    pub fn fmu_library(&self, model_identifier: &str) -> String {
        format!("binaries/{}/{model_identifier}{}", self.folder, self.suffix)
    }

    /// Whether glibc symbol versions apply (Linux gnu targets).
    pub fn is_linux(&self) -> bool {
        self.folder.starts_with("linux")
    }
}

/// The host triple of the Rust toolchain (`rustc -vV`), i.e. the default target.
pub fn host_triple() -> Result<String, String> {
    let rustc = std::env::var_os("RUSTC").unwrap_or_else(|| "rustc".into());
    let out = Command::new(&rustc)
        .arg("-vV")
        .output()
        .map_err(|e| format!("cannot run rustc -vV: {e}"))?;
    let text = String::from_utf8_lossy(&out.stdout);
    text.lines()
        .find_map(|l| l.strip_prefix("host: "))
        .map(|h| h.trim().to_string())
        .ok_or_else(|| format!("rustc -vV printed no host line:\n{text}"))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn folders_and_file_names_from_targets() {
        for (triple, folder, cargo_name, fmu_name) in [
            (
                "x86_64-unknown-linux-gnu",
                "linux64",
                "librailcontact.so",
                "binaries/linux64/M.so",
            ),
            (
                "i686-unknown-linux-gnu",
                "linux32",
                "librailcontact.so",
                "binaries/linux32/M.so",
            ),
            (
                "x86_64-pc-windows-msvc",
                "win64",
                "railcontact.dll",
                "binaries/win64/M.dll",
            ),
            (
                "x86_64-pc-windows-gnu",
                "win64",
                "railcontact.dll",
                "binaries/win64/M.dll",
            ),
            (
                "i686-pc-windows-msvc",
                "win32",
                "railcontact.dll",
                "binaries/win32/M.dll",
            ),
            (
                "x86_64-apple-darwin",
                "darwin64",
                "librailcontact.dylib",
                "binaries/darwin64/M.dylib",
            ),
            (
                "aarch64-apple-darwin",
                "darwin64",
                "librailcontact.dylib",
                "binaries/darwin64/M.dylib",
            ),
        ] {
            let p = Platform::of_target(triple).unwrap();
            assert_eq!(p.folder, folder, "{triple}");
            assert_eq!(p.cargo_library("railcontact"), cargo_name, "{triple}");
            assert_eq!(p.fmu_library("M"), fmu_name, "{triple}");
            assert_eq!(p.is_linux(), folder.starts_with("linux"));
        }
    }

    #[test]
    fn targets_without_a_folder_are_refused() {
        for triple in [
            "aarch64-unknown-linux-gnu",
            "x86_64-unknown-linux-musl",
            "aarch64-pc-windows-msvc",
            "x86_64-unknown-freebsd",
            "wasm32-unknown-unknown",
        ] {
            let e = Platform::of_target(triple).unwrap_err();
            assert!(e.contains(triple) && e.contains("darwin64"), "{e}");
        }
    }

    #[test]
    fn the_host_triple_is_known() {
        let host = host_triple().unwrap();
        assert!(host.contains('-'), "{host}");
    }
}
