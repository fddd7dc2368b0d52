//! Logging through the importer's `fmi2CallbackLogger`.
//!
//! Messages are formatted in Rust only when their category is enabled and a logger exists,
//! so the hot path (doStep, get/set) never formats or allocates with logging off. The
//! message is passed as the printf format string with no variadic arguments, escaped:
//! `%` -> `%%` (printf) and `#` -> `##` (FMI value-reference syntax); interior NULs dropped.

use super::types::*;
use std::ffi::{CStr, CString};
use std::fmt;

/// The log categories of `model_description::LOG_CATEGORIES`, in the same order (a test
/// checks that they agree).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Category {
    StatusWarning = 0,
    StatusDiscard = 1,
    StatusError = 2,
    StatusFatal = 3,
    Events = 4,
    Solver = 5,
}

impl Category {
    pub const ALL: [Category; 6] = [
        Category::StatusWarning,
        Category::StatusDiscard,
        Category::StatusError,
        Category::StatusFatal,
        Category::Events,
        Category::Solver,
    ];

    pub fn c_name(self) -> &'static CStr {
        match self {
            Category::StatusWarning => c"logStatusWarning",
            Category::StatusDiscard => c"logStatusDiscard",
            Category::StatusError => c"logStatusError",
            Category::StatusFatal => c"logStatusFatal",
            Category::Events => c"logEvents",
            Category::Solver => c"logSolver",
        }
    }

    pub fn name(self) -> &'static str {
        self.c_name().to_str().expect("ASCII category name")
    }

    pub fn from_name(name: &[u8]) -> Option<Category> {
        Category::ALL.into_iter().find(|c| c.c_name().to_bytes() == name)
    }
}

/// Escape a message for use as a printf format string in an FMI logger.
pub fn escape(message: &str) -> CString {
    let mut out = Vec::with_capacity(message.len() + 8);
    for &b in message.as_bytes() {
        match b {
            0 => {}
            b'%' => out.extend_from_slice(b"%%"),
            b'#' => out.extend_from_slice(b"##"),
            _ => out.push(b),
        }
    }
    CString::new(out).expect("NULs removed")
}

/// The importer's logger, its environment pointer, the instance name and the enabled
/// categories. Without a logger nothing is ever logged.
pub struct Logger {
    callback: Option<Fmi2CallbackLogger>,
    environment: Fmi2ComponentEnvironment,
    instance_name: CString,
    enabled: [bool; 6],
}

impl Logger {
    /// Status categories (warning, discard, error, fatal) are on from the start, like the
    /// Reference FMUs log errors unless told otherwise; `logging_on` enables all.
    pub fn new(
        callback: Option<Fmi2CallbackLogger>,
        environment: Fmi2ComponentEnvironment,
        instance_name: CString,
        logging_on: bool,
    ) -> Logger {
        let mut enabled = [logging_on; 6];
        for c in [
            Category::StatusWarning,
            Category::StatusDiscard,
            Category::StatusError,
            Category::StatusFatal,
        ] {
            enabled[c as usize] = true;
        }
        Logger {
            callback,
            environment,
            instance_name,
            enabled,
        }
    }

    pub fn instance_name(&self) -> &CStr {
        &self.instance_name
    }

    /// Would a message of this category reach the logger?
    #[inline]
    pub fn enabled(&self, category: Category) -> bool {
        self.callback.is_some() && self.enabled[category as usize]
    }

    pub fn set_enabled(&mut self, category: Category, on: bool) {
        self.enabled[category as usize] = on;
    }

    pub fn set_all(&mut self, on: bool) {
        self.enabled = [on; 6];
    }

    /// Log `args` with `status` in `category` if that category is enabled.
    pub fn log(&self, status: Fmi2Status, category: Category, args: fmt::Arguments<'_>) {
        if !self.enabled(category) {
            return;
        }
        let Some(callback) = self.callback else { return };
        let message = escape(&fmt::format(args));
        // SAFETY: the importer gave us this logger and environment for exactly this use;
        // every string is NUL-terminated and outlives the call; the message contains no
        // unescaped conversion specifications, so no variadic arguments are read.
        unsafe {
            callback(
                self.environment,
                self.instance_name.as_ptr(),
                status,
                category.c_name().as_ptr(),
                message.as_ptr(),
            )
        }
    }

    pub fn error(&self, args: fmt::Arguments<'_>) {
        self.log(FMI2_ERROR, Category::StatusError, args)
    }

    pub fn warning(&self, args: fmt::Arguments<'_>) {
        self.log(FMI2_WARNING, Category::StatusWarning, args)
    }

    pub fn discard(&self, args: fmt::Arguments<'_>) {
        self.log(FMI2_DISCARD, Category::StatusDiscard, args)
    }

    pub fn fatal(&self, args: fmt::Arguments<'_>) {
        self.log(FMI2_FATAL, Category::StatusFatal, args)
    }

    pub fn event(&self, args: fmt::Arguments<'_>) {
        self.log(FMI2_OK, Category::Events, args)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::model_description::LOG_CATEGORIES;

    #[test]
    fn categories_match_the_model_description() {
        let ours: Vec<&str> = Category::ALL.iter().map(|c| c.name()).collect();
        let declared: Vec<&str> = LOG_CATEGORIES.iter().map(|(n, _)| *n).collect();
        assert_eq!(ours, declared);
        for (i, c) in Category::ALL.iter().enumerate() {
            assert_eq!(*c as usize, i);
            assert_eq!(Category::from_name(c.name().as_bytes()), Some(*c));
        }
        assert_eq!(Category::from_name(b"logAll"), None);
    }

    #[test]
    fn escaping() {
        assert_eq!(escape("5 % of #3\0x").as_bytes(), b"5 %% of ##3x");
        assert_eq!(escape("plain").as_bytes(), b"plain");
    }
}
