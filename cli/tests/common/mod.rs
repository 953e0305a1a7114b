//! Helpers the test files share: scratch directories, parsed command lines, the binary.

#![allow(dead_code)] // each test file uses its own part

use std::path::PathBuf;
use std::process::Command;

use clap::Parser;
use ocean_fft_cli::args::{BakeArgs, Cli, Command as Sub, SeaArgs};

/// A fresh directory under the system's temporary space, unique to this process.
pub fn scratch(name: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("ocean-fft-cli-{}-{name}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

/// `ocean-fft bake ARGS`, parsed.
pub fn bake_args(args: &[&str]) -> BakeArgs {
    let mut full = vec!["ocean-fft", "bake"];
    full.extend_from_slice(args);
    match Cli::try_parse_from(full).unwrap().command {
        Sub::Bake(b) => b,
        Sub::Info(_) => unreachable!(),
    }
}

/// The sea of `ocean-fft info ARGS`, parsed.
pub fn sea_args(args: &[&str]) -> SeaArgs {
    let mut full = vec!["ocean-fft", "info"];
    full.extend_from_slice(args);
    match Cli::try_parse_from(full).unwrap().command {
        Sub::Info(i) => i.sea,
        Sub::Bake(_) => unreachable!(),
    }
}

/// Runs the binary; its exit code and stderr.
pub fn binary(args: &[&str]) -> (i32, String) {
    let out = Command::new(env!("CARGO_BIN_EXE_ocean-fft"))
        .args(args)
        .output()
        .unwrap();
    (
        out.status.code().unwrap(),
        String::from_utf8_lossy(&out.stderr).into_owned(),
    )
}
