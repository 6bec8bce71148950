//! Building the railcontact cdylib for a target.
//!
//! * Plain `cargo build --release --lib -p railcontact` (with `--target` when it is not the host):
//!   on Linux the library then needs at least the build machine's glibc.
//! * For Linux (gnu) targets, `cargo zigbuild` against an old glibc (default 2.17, the oldest
//!   Rust supports): zig links against that glibc's symbol versions and compiles fmi-sys's C
//!   logger with its headers, so the library loads on RHEL/CentOS 7 and every later
//!   distribution. `cargo-zigbuild` and zig come from PyPI (`fmu-pack/requirements.txt`; `.ci/setup`
//!   installs them into `.venv`).

use crate::platform::Platform;
use std::path::{Path, PathBuf};
use std::process::Command;

/// The glibc baseline used when none is given and cargo-zigbuild is available.
pub const DEFAULT_GLIBC: &str = "2.17";

const INSTALL_HINT: &str = "install it with `.venv/bin/pip install -r fmu-pack/requirements.txt` \
     (`bash .ci/setup` does), or pass --glibc native to link against this machine's glibc";

#[derive(Debug, Clone, PartialEq, Eq)]
pub enum Linker {
    /// `cargo build`.
    Cargo,
    /// `cargo zigbuild` against glibc `glibc` (Linux gnu targets).
    Zig {
        cargo_zigbuild: PathBuf,
        glibc: String,
    },
}

#[derive(Debug, Clone)]
pub struct Build {
    /// The Rust target triple.
    pub target: String,
    /// Whether the target is the toolchain's host (then plain cargo builds without `--target`,
    /// sharing the build of `cargo run --release -p fmu-pack`).
    pub is_host: bool,
    pub platform: Platform,
    pub linker: Linker,
}

/// `--glibc`: "native" or a version 2.N with N ≥ 17.
fn parse_glibc(v: &str) -> Result<Option<String>, String> {
    if v.eq_ignore_ascii_case("native") {
        return Ok(None);
    }
    let minor = v
        .strip_prefix("2.")
        .and_then(|m| m.parse::<u32>().ok())
        .ok_or_else(|| format!("--glibc {v:?}: expected `native` or a version such as 2.17"))?;
    if minor < 17 {
        return Err(format!(
            "--glibc {v}: Rust's standard library needs glibc 2.17 or later"
        ));
    }
    Ok(Some(format!("2.{minor}")))
}

/// `name` in `PATH`, or `None`.
fn in_path(name: &str) -> Option<PathBuf> {
    let exe = format!("{name}{}", std::env::consts::EXE_SUFFIX);
    std::env::split_paths(&std::env::var_os("PATH")?)
        .map(|dir| dir.join(&exe))
        .find(|p| p.is_file())
}

/// cargo-zigbuild in `PATH`, else in the workspace's `.venv` (where `.ci/setup` installs it).
pub fn find_cargo_zigbuild(workspace: &Path) -> Option<PathBuf> {
    in_path("cargo-zigbuild").or_else(|| {
        let exe = format!("cargo-zigbuild{}", std::env::consts::EXE_SUFFIX);
        [
            workspace.join(".venv").join("bin").join(&exe),
            workspace.join(".venv").join("Scripts").join(&exe),
        ]
        .into_iter()
        .find(|p| p.is_file())
    })
}

impl Build {
    /// What to build for `target` (default: `host`) with the `--glibc` option `glibc`. The
    /// returned note, if any, tells why a Linux library is not built against a baseline.
    pub fn plan(
        target: Option<&str>,
        glibc: Option<&str>,
        host: &str,
        cargo_zigbuild: Option<PathBuf>,
    ) -> Result<(Build, Option<String>), String> {
        let target = target.unwrap_or(host).to_string();
        let platform = Platform::of_target(&target)?;
        let is_host = target == host;
        let requested = glibc.map(parse_glibc).transpose()?;
        let mut note = None;
        let linker = match (platform.is_linux(), requested) {
            (false, Some(Some(_))) => {
                return Err(format!(
                    "--glibc applies to Linux targets only, not to {target}"
                ))
            }
            (false, _) | (true, Some(None)) => Linker::Cargo,
            (true, Some(Some(version))) => Linker::Zig {
                cargo_zigbuild: cargo_zigbuild.ok_or_else(|| {
                    format!("--glibc {version} needs cargo-zigbuild: {INSTALL_HINT}")
                })?,
                glibc: version,
            },
            (true, None) => match cargo_zigbuild {
                Some(exe) => Linker::Zig {
                    cargo_zigbuild: exe,
                    glibc: DEFAULT_GLIBC.to_string(),
                },
                None => {
                    note = Some(format!(
                        "note: cargo-zigbuild not found, so the library is linked against this \
                         machine's glibc and will not load on older Linux distributions; \
                         {INSTALL_HINT}"
                    ));
                    Linker::Cargo
                }
            },
        };
        Ok((
            Build {
                target,
                is_host,
                platform,
                linker,
            },
            note,
        ))
    }

    /// Where the build leaves the library.
    pub fn library(&self, target_dir: &Path) -> PathBuf {
        let dir = match self.linker {
            Linker::Cargo if self.is_host => target_dir.join("release"),
            _ => target_dir.join(&self.target).join("release"),
        };
        dir.join(self.platform.cargo_library("railcontact"))
    }

    /// One line for the user: target, platform and how it is linked.
    pub fn describe(&self) -> String {
        let how = match &self.linker {
            Linker::Cargo if self.platform.is_linux() => {
                "cargo build, linked against this machine's glibc".to_string()
            }
            Linker::Cargo => "cargo build".to_string(),
            Linker::Zig { glibc, .. } => format!("cargo zigbuild, glibc {glibc} or later"),
        };
        format!(
            "railcontact cdylib for {} (binaries/{}; {how})",
            self.target, self.platform.folder
        )
    }

    /// Runs the build; `workspace` is the workspace root, `target_dir` Cargo's target directory.
    pub fn run(&self, workspace: &Path, target_dir: &Path) -> Result<(), String> {
        let cargo = std::env::var_os("CARGO").unwrap_or_else(|| "cargo".into());
        let common = ["--release", "--lib", "-p", "railcontact"];
        let mut cmd = match &self.linker {
            Linker::Cargo => {
                let mut c = Command::new(cargo);
                c.arg("build").args(common).current_dir(workspace);
                if !self.is_host {
                    c.args(["--target", &self.target]);
                }
                c
            }
            Linker::Zig {
                cargo_zigbuild,
                glibc,
            } => {
                let mut c = Command::new(cargo_zigbuild);
                c.arg("zigbuild")
                    .args(common)
                    .arg("--target")
                    .arg(format!("{}.{glibc}", self.target))
                    .arg("--manifest-path")
                    .arg(workspace.join("Cargo.toml"));
                // cargo-zigbuild finds zig as `zig` or `python3 -m ziglang`: put the directory
                // it was installed in (a venv's bin) first in PATH.
                if let Some(dir) = cargo_zigbuild.parent() {
                    let path = std::env::var_os("PATH").unwrap_or_default();
                    let dirs = std::iter::once(dir.to_path_buf())
                        .chain(std::env::split_paths(&path))
                        .collect::<Vec<_>>();
                    c.env(
                        "PATH",
                        std::env::join_paths(dirs).map_err(|e| format!("PATH: {e}"))?,
                    );
                }
                // cargo-zigbuild writes zig's include directories for bindgen (fmi-sys) relative
                // to its working directory when they lie below it, and bindgen runs in another
                // directory, so a zig inside the workspace (.venv) would not be found from the
                // workspace root: run it from a directory of its own.
                let cwd = target_dir.join("zigbuild");
                std::fs::create_dir_all(&cwd).map_err(|e| format!("{}: {e}", cwd.display()))?;
                c.current_dir(cwd);
                c
            }
        };
        cmd.arg("--target-dir").arg(target_dir);
        let status = cmd
            .status()
            .map_err(|e| format!("cannot run {:?}: {e}", cmd.get_program()))?;
        match (&self.linker, status.success()) {
            (_, true) => Ok(()),
            (Linker::Cargo, false) => Err(format!("the build of the cdylib failed ({status})")),
            (Linker::Zig { cargo_zigbuild, .. }, false) => Err(format!(
                "the build of the cdylib with {} failed ({status}); --glibc native builds with \
                 plain cargo against this machine's glibc",
                cargo_zigbuild.display()
            )),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    const HOST: &str = "x86_64-unknown-linux-gnu";

    fn zig() -> Option<PathBuf> {
        Some(PathBuf::from("/opt/venv/bin/cargo-zigbuild"))
    }

    #[test]
    fn linux_uses_zig_with_the_default_baseline_when_available() {
        let (b, note) = Build::plan(None, None, HOST, zig()).unwrap();
        assert!(note.is_none());
        assert_eq!(
            b.linker,
            Linker::Zig {
                cargo_zigbuild: zig().unwrap(),
                glibc: "2.17".into()
            }
        );
        assert_eq!(
            b.library(Path::new("/t")),
            Path::new("/t/x86_64-unknown-linux-gnu/release/librailcontact.so")
        );
        assert!(b.describe().contains("glibc 2.17 or later"));
    }

    #[test]
    fn without_zig_linux_falls_back_to_cargo_with_a_note() {
        let (b, note) = Build::plan(None, None, HOST, None).unwrap();
        assert_eq!(b.linker, Linker::Cargo);
        assert!(note.unwrap().contains("fmu-pack/requirements.txt"));
        assert_eq!(
            b.library(Path::new("/t")),
            Path::new("/t/release/librailcontact.so")
        );
        // Asked for explicitly, a baseline without cargo-zigbuild is an error.
        let e = Build::plan(None, Some("2.17"), HOST, None).unwrap_err();
        assert!(e.contains("cargo-zigbuild"), "{e}");
    }

    #[test]
    fn glibc_option() {
        let (b, _) = Build::plan(None, Some("native"), HOST, zig()).unwrap();
        assert_eq!(b.linker, Linker::Cargo);
        let (b, _) = Build::plan(None, Some("2.28"), HOST, zig()).unwrap();
        assert!(matches!(b.linker, Linker::Zig { ref glibc, .. } if glibc == "2.28"));
        for bad in ["2.16", "3.1", "2.x", ""] {
            assert!(Build::plan(None, Some(bad), HOST, zig()).is_err(), "{bad}");
        }
        let e = Build::plan(Some("x86_64-pc-windows-msvc"), Some("2.17"), HOST, zig()).unwrap_err();
        assert!(e.contains("Linux targets only"), "{e}");
    }

    #[test]
    fn other_targets_build_with_cargo_into_their_target_folder() {
        for (target, lib) in [
            (
                "x86_64-pc-windows-msvc",
                "/t/x86_64-pc-windows-msvc/release/railcontact.dll",
            ),
            (
                "aarch64-apple-darwin",
                "/t/aarch64-apple-darwin/release/librailcontact.dylib",
            ),
        ] {
            let (b, note) = Build::plan(Some(target), None, HOST, zig()).unwrap();
            assert!(note.is_none());
            assert_eq!(b.linker, Linker::Cargo);
            assert!(!b.is_host);
            assert_eq!(b.library(Path::new("/t")), Path::new(lib));
        }
        // On a Windows host the host build needs no --target.
        let (b, _) = Build::plan(None, None, "x86_64-pc-windows-msvc", None).unwrap();
        assert_eq!(
            b.library(Path::new("/t")),
            Path::new("/t/release/railcontact.dll")
        );
    }
}
