//! `fmu-pack`: builds the railcontact cdylib in release mode, packs one `.fmu` per model into
//! `target/fmu/`, then loads each packed FMU through its C API (a small Rust host) and runs its
//! default experiment, printing a table.
//!
//! Usage: `cargo run --release -p fmu-pack [-- --no-build] [--no-run] [--out DIR]`

mod docs;
mod host;
mod pack;

use std::path::PathBuf;
use std::process::{Command, ExitCode};

struct Options {
    build: bool,
    run: bool,
    out_dir: Option<PathBuf>,
}

fn parse_args() -> Result<Options, String> {
    let mut o = Options {
        build: true,
        run: true,
        out_dir: None,
    };
    let mut args = std::env::args().skip(1);
    while let Some(a) = args.next() {
        match a.as_str() {
            "--no-build" => o.build = false,
            "--no-run" => o.run = false,
            "--out" => o.out_dir = Some(args.next().ok_or("--out needs a directory")?.into()),
            "-h" | "--help" => {
                println!("usage: fmu-pack [--no-build] [--no-run] [--out DIR]\n  packs target/fmu/<Model>.fmu for every model and runs its default experiment");
                std::process::exit(0);
            }
            other => return Err(format!("unknown argument {other:?} (see --help)")),
        }
    }
    Ok(o)
}

/// The workspace root (this crate lives in `<root>/fmu-pack`).
fn workspace_root() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
        .parent()
        .expect("fmu-pack is inside the workspace")
        .to_path_buf()
}

fn target_dir() -> PathBuf {
    std::env::var_os("CARGO_TARGET_DIR")
        .map(PathBuf::from)
        .unwrap_or_else(|| workspace_root().join("target"))
}

fn build_cdylib() -> Result<(), String> {
    let cargo = std::env::var_os("CARGO").unwrap_or_else(|| "cargo".into());
    let status = Command::new(cargo)
        .args(["build", "--release", "--lib", "-p", "railcontact"])
        .current_dir(workspace_root())
        .status()
        .map_err(|e| format!("cannot run cargo: {e}"))?;
    if status.success() {
        Ok(())
    } else {
        Err(format!("cargo build of the cdylib failed ({status})"))
    }
}

fn run() -> Result<(), String> {
    let options = parse_args()?;
    if options.build {
        build_cdylib()?;
    }
    let library = target_dir().join("release").join("librailcontact.so");
    if !library.is_file() {
        return Err(format!(
            "{} not found: build it with `cargo build --release --lib`",
            library.display()
        ));
    }
    let out_dir = options.out_dir.unwrap_or_else(|| target_dir().join("fmu"));
    std::fs::create_dir_all(&out_dir).map_err(|e| format!("{}: {e}", out_dir.display()))?;
    for info in railcontact::models::MODELS {
        let fmu = out_dir.join(format!("{}.fmu", info.model_identifier));
        pack::write_fmu(info, &library, &fmu)?;
        println!("packed {}", fmu.display());
        if options.run {
            host::run_default_experiment(info, &fmu, &out_dir.join("run"))?;
        }
    }
    Ok(())
}

fn main() -> ExitCode {
    match run() {
        Ok(()) => ExitCode::SUCCESS,
        Err(e) => {
            eprintln!("fmu-pack: {e}");
            ExitCode::FAILURE
        }
    }
}
