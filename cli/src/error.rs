//! The tool's errors and their exit codes (listed in `--help`, see [`crate::args::EXIT_CODES`]).

use std::fmt;

/// What went wrong, by exit code.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Kind {
    /// 1: a bug.
    Internal,
    /// 2: the command line.
    Usage,
    /// 3: the sea configuration (file or parameters).
    Config,
    /// 4: writing the output.
    Output,
    /// 5: the output directory holds another bake.
    Conflict,
}

impl Kind {
    /// The process exit code.
    pub fn exit_code(self) -> i32 {
        match self {
            Kind::Internal => 1,
            Kind::Usage => 2,
            Kind::Config => 3,
            Kind::Output => 4,
            Kind::Conflict => 5,
        }
    }
}

/// An error with its exit code and a message that names the argument or file at fault.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct CliError {
    /// Which exit code.
    pub kind: Kind,
    /// The message, printed after `error: `.
    pub message: String,
}

impl CliError {
    /// A new error.
    pub fn new(kind: Kind, message: impl Into<String>) -> CliError {
        CliError {
            kind,
            message: message.into(),
        }
    }

    /// A bad command-line argument.
    pub fn usage(message: impl Into<String>) -> CliError {
        CliError::new(Kind::Usage, message)
    }

    /// A bad sea configuration.
    pub fn config(message: impl Into<String>) -> CliError {
        CliError::new(Kind::Config, message)
    }

    /// An output failure.
    pub fn output(message: impl Into<String>) -> CliError {
        CliError::new(Kind::Output, message)
    }
}

impl fmt::Display for CliError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(&self.message)
    }
}

impl std::error::Error for CliError {}
