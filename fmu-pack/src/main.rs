//! `fmu-pack`: builds the railcontact cdylib in release mode for a target (by default this
//! machine's; Linux libraries against glibc 2.17 when cargo-zigbuild is available), packs one
//! `.fmu` per model into `<target dir>/fmu/` with the library under the target's platform folder
//! (`binaries/linux64`, `win64`, `darwin64`, …) and any bundled files under `resources/`, then —
//! when the library runs on this machine — loads each packed FMU through its C API (a small Rust
//! host) and runs its default experiment, printing a table.
//!
//! Usage: `cargo run --release -p fmu-pack [-- OPTIONS]`; `--help` lists the options.

mod cdylib;
mod docs;
mod host;
mod pack;
mod platform;

use clap::Parser;
use std::path::PathBuf;
use std::process::ExitCode;

/// Builds the railcontact FMUs (FMI 2.0 Co-Simulation) and runs their default experiments.
#[derive(Parser, Debug)]
#[command(name = "fmu-pack", version)]
struct Args {
    /// Pack the library already built; do not run cargo.
    #[arg(long)]
    no_build: bool,
    /// Do not run the default experiments.
    #[arg(long)]
    no_run: bool,
    /// Write the .fmu files into DIR [default: <cargo target dir>/fmu].
    #[arg(long, value_name = "DIR")]
    out: Option<PathBuf>,
    /// Bundle FILE in every FMU's resources/ (repeatable). A profile parameter such as
    /// wheelProfile then names it by its bare file name.
    #[arg(long = "resource", value_name = "FILE")]
    resources: Vec<PathBuf>,
    /// Rust target to build for [default: this machine's]. It decides the platform folder:
    /// x86_64 Linux (gnu) → linux64, x86_64 Windows → win64, macOS → darwin64, 32-bit x86 →
    /// linux32 / win32. Other targets need their Rust standard library installed (rustup target
    /// add) and, for Linux, are usually built with --glibc.
    #[arg(long, value_name = "TRIPLE")]
    target: Option<String>,
    /// Linux targets: the oldest glibc the library must load on, e.g. 2.17 (needs
    /// cargo-zigbuild), or `native` to link against this machine's glibc. [default: 2.17 when
    /// cargo-zigbuild is in PATH or .venv, else native]
    #[arg(long, value_name = "VERSION|native")]
    glibc: Option<String>,
}

/// The workspace root (this crate lives in `<root>/fmu-pack`).
fn workspace_root() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
        .parent()
        .expect("fmu-pack is inside the workspace")
        .to_path_buf()
}

/// Cargo's target directory: `CARGO_TARGET_DIR` (relative to the current directory, as Cargo
/// reads it) or `<root>/target`.
fn target_dir() -> Result<PathBuf, String> {
    let dir = std::env::var_os("CARGO_TARGET_DIR")
        .map(PathBuf::from)
        .unwrap_or_else(|| workspace_root().join("target"));
    std::path::absolute(&dir).map_err(|e| format!("{}: {e}", dir.display()))
}

fn run(args: Args) -> Result<(), String> {
    let resources = pack::Resources::new(&args.resources)?;
    let host = platform::host_triple()?;
    let root = workspace_root();
    let target_dir = target_dir()?;
    let (build, note) = cdylib::Build::plan(
        args.target.as_deref(),
        args.glibc.as_deref(),
        &host,
        cdylib::find_cargo_zigbuild(&root),
    )?;
    if let Some(note) = note {
        eprintln!("fmu-pack: {note}");
    }
    println!("{}", build.describe());
    if !args.no_build {
        build.run(&root, &target_dir)?;
    }
    let library = build.library(&target_dir);
    if !library.is_file() {
        return Err(format!(
            "{} not found: build it (run fmu-pack without --no-build)",
            library.display()
        ));
    }
    let runs_here = platform::Platform::of_target(&host).ok() == Some(build.platform);
    let out_dir = args.out.unwrap_or_else(|| target_dir.join("fmu"));
    std::fs::create_dir_all(&out_dir).map_err(|e| format!("{}: {e}", out_dir.display()))?;
    for info in railcontact::models::MODELS {
        let fmu = out_dir.join(format!("{}.fmu", info.model_identifier));
        pack::write_fmu(info, &library, &build.platform, &resources, &fmu)?;
        println!("packed {}", fmu.display());
        if args.no_run {
            continue;
        }
        if runs_here {
            host::run_default_experiment(info, &fmu, &build.platform, &out_dir.join("run"))?;
        } else {
            println!(
                "{}: a {} library does not run on this {host} machine: default experiment skipped",
                info.model_identifier, build.platform.folder
            );
        }
    }
    let bundled: Vec<&str> = resources.names().collect();
    if !bundled.is_empty() {
        println!(
            "resources/ of every FMU: {} (name them by the bare file name, e.g. wheelProfile = {:?})",
            bundled.join(", "),
            bundled[0]
        );
    }
    println!("FMUs in {}", out_dir.display());
    Ok(())
}

fn main() -> ExitCode {
    match run(Args::parse()) {
        Ok(()) => ExitCode::SUCCESS,
        Err(e) => {
            eprintln!("fmu-pack: {e}");
            ExitCode::FAILURE
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use clap::CommandFactory;

    #[test]
    fn arguments() {
        Args::command().debug_assert();
        let a = Args::try_parse_from([
            "fmu-pack",
            "--resource",
            "a.prw",
            "--resource",
            "b.prr",
            "--out",
            "dir",
            "--glibc",
            "2.17",
            "--no-run",
        ])
        .unwrap();
        assert_eq!(
            a.resources,
            [PathBuf::from("a.prw"), PathBuf::from("b.prr")]
        );
        assert_eq!(a.out, Some(PathBuf::from("dir")));
        assert_eq!(a.glibc.as_deref(), Some("2.17"));
        assert!(a.no_run && !a.no_build && a.target.is_none());
        assert!(Args::try_parse_from(["fmu-pack", "--bogus"]).is_err());
    }
}
