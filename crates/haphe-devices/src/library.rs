//! Loading a vendor's C library at run time: from the file an environment variable names,
//! else by its name on the system's search path; every symbol resolved once, at load.

use std::ffi::{CStr, c_char};

use libloading::Library;

/// A vendor library haphe can load, and how to tell haphe where it is.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct VendorLibrary {
    /// The file name looked up on the system search path, e.g. `libdhd.so`.
    pub file: &'static str,
    /// The environment variable that names the library file instead.
    pub variable: &'static str,
    /// The vendor SDK that provides it.
    pub sdk: &'static str,
}

/// The Force Dimension SDK's C library.
pub const DHD_LIBRARY: VendorLibrary = VendorLibrary {
    file: "libdhd.so",
    variable: "HAPHE_DHD_LIBRARY",
    sdk: "the Force Dimension SDK (sdk-3.x, from forcedimension.com)",
};

/// The OpenHaptics HD API library.
pub const HD_LIBRARY: VendorLibrary = VendorLibrary {
    file: "libHD.so",
    variable: "HAPHE_HD_LIBRARY",
    sdk: "the OpenHaptics Developer Edition from 3D Systems (with the Touch device drivers)",
};

/// Why a vendor library could not be used.
#[derive(Debug, Clone, PartialEq, Eq, thiserror::Error)]
#[error(
    "cannot load {} from {}: {reason}; install {} or set {} to the library file (see docs/devices.md)",
    library.file, where_from, library.sdk, library.variable
)]
pub struct LoadError {
    /// The library.
    pub library: VendorLibrary,
    /// Where it was looked for: the variable's file, or the system search path.
    pub where_from: String,
    /// What the loader said.
    pub reason: String,
}

/// A loaded library and where it came from.
pub(crate) struct Loaded {
    pub(crate) library: Library,
    pub(crate) path: String,
}

impl VendorLibrary {
    /// Loads the library from `$variable` when set, else by file name.
    ///
    /// # Errors
    /// A [`LoadError`] naming the library, the variable and the SDK.
    pub(crate) fn load(&self) -> Result<Loaded, LoadError> {
        let (path, where_from) = match std::env::var_os(self.variable) {
            Some(p) if !p.is_empty() => {
                let shown = p.to_string_lossy().into_owned();
                (p, format!("{shown} (named by {})", self.variable))
            }
            _ => (
                self.file.into(),
                "the system library search path".to_string(),
            ),
        };
        // SAFETY: loading a library runs its initialisers; the vendor SDKs' libraries (and
        // the file the user named in the variable for them) are meant to be loaded by
        // applications, which is what this is.
        let library = unsafe { Library::new(&path) }.map_err(|e| LoadError {
            library: *self,
            where_from: where_from.clone(),
            reason: with_source(&e),
        })?;
        Ok(Loaded {
            library,
            path: path.to_string_lossy().into_owned(),
        })
    }

    /// A [`LoadError`] for a symbol the library lacks.
    pub(crate) fn missing(&self, path: &str, symbol: &str, why: &libloading::Error) -> LoadError {
        LoadError {
            library: *self,
            where_from: path.to_string(),
            reason: format!(
                "it has no symbol {symbol} ({}): not the vendor's library, or too old",
                with_source(why)
            ),
        }
    }
}

/// An error with its source (libloading keeps the loader's message there).
fn with_source(e: &libloading::Error) -> String {
    match std::error::Error::source(e) {
        Some(s) => format!("{e}: {s}"),
        None => e.to_string(),
    }
}

/// Resolves `name` in `loaded` as a value of type `T` (a C function pointer type).
///
/// # Safety
/// `T` must be the symbol's true C type, and the value must not be used after `loaded`'s
/// library is dropped.
pub(crate) unsafe fn symbol<T: Copy>(
    lib: &VendorLibrary,
    loaded: &Loaded,
    name: &str,
) -> Result<T, LoadError> {
    // SAFETY: the caller vouches for the type and the lifetime (see above).
    unsafe { loaded.library.get::<T>(name.as_bytes()) }
        .map(|s| *s)
        .map_err(|e| lib.missing(&loaded.path, name, &e))
}

/// Copies a C string owned by a library (off the servo path); `None` for a null pointer.
pub(crate) fn c_text(p: *const c_char) -> Option<String> {
    if p.is_null() {
        return None;
    }
    // SAFETY: the vendor functions that return strings return null or a nul-terminated
    // string that stays valid at least until the next call into the library, and it is
    // copied here at once.
    Some(unsafe { CStr::from_ptr(p) }.to_string_lossy().into_owned())
}
