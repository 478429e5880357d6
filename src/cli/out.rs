//! Printing to stdout that ends quietly when the reader has gone (`contrail check S | head -1`):
//! a closed pipe stops the output, like other Unix tools, instead of a panic.

use std::fmt::Arguments;
use std::io::{ErrorKind, Write};

/// Write formatted text to stdout. A closed pipe is not an error (the rest is dropped);
/// any other write error is returned.
pub fn print(args: Arguments) -> std::io::Result<()> {
    let mut out = std::io::stdout().lock();
    match out.write_fmt(args).and_then(|_| out.flush()) {
        Err(e) if e.kind() == ErrorKind::BrokenPipe => Ok(()),
        r => r,
    }
}

/// `println!` through [`print`]; evaluates to `std::io::Result<()>`.
macro_rules! outln {
    ($($arg:tt)*) => {
        $crate::cli::out::print(format_args!("{}\n", format_args!($($arg)*)))
    };
}

/// `print!` through [`print`]; evaluates to `std::io::Result<()>`.
macro_rules! out {
    ($($arg:tt)*) => {
        $crate::cli::out::print(format_args!($($arg)*))
    };
}

pub(crate) use {out, outln};
