//! Compiles the host's variadic logger callback (`src/logger.c`).

fn main() {
    println!("cargo:rerun-if-changed=src/logger.c");
    cc::Build::new()
        .file("src/logger.c")
        .warnings(true)
        .compile("fmi_host_logger");
}
