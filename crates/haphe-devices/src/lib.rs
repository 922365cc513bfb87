//! Stage 7 — real haptic devices for haphe's servo loop, each a
//! [`haphe::servo::Device`]:
//!
//! - [`DhdDevice`]: Force Dimension devices through the SDK's C API (`libdhd.so`);
//! - [`HdDevice`]: 3D Systems Touch and Phantom devices through OpenHaptics' HD API
//!   (`libHD.so`), clocked by the HD scheduler ([`HdClock`], a
//!   [`DeviceClock`](haphe::servo::DeviceClock));
//! - [`UdpDevice`]: a device driven by another process or machine over UDP, one small
//!   datagram each way ([`udp::datagram`]).
//!
//! The vendor libraries are loaded at run time (`libloading`), from the file named by
//! `HAPHE_DHD_LIBRARY` / `HAPHE_HD_LIBRARY` or else from the system's library search
//! path, and every symbol is resolved once when the library is loaded: haphe builds,
//! installs and tests on machines without the SDKs. [`open_device`] turns a device
//! specification (`dhd`, `dhd:N`, `openhaptics`, `openhaptics:NAME`, `udp:HOST:PORT`,
//! `hand`) into an opened device, for every front end; [`open_devices`] opens several
//! for one servo (two hands), refusing a device named twice before any is opened.
//!
//! # Frames and units
//! SI units. The device frame of every device here is Force Dimension's: x towards the
//! user, y to the right, z up (OpenHaptics' millimetres and y-up frame are converted).
//!
//! # Real-time
//! `read` and `write_force` make a few C calls or non-blocking socket calls with fixed
//! buffers: no allocation, no lock (tests/alloc.rs counts them over 10^5 ticks each).
//!
//! # Safety
//! This crate calls C: every `unsafe` block says why it is sound.

mod dhd;
mod library;
mod list;
mod mapping;
mod openhaptics;
mod spec;
pub mod udp;

pub use dhd::{DHD_WORKSPACE_HALF_M, DhdDevice, DhdInfo};
pub use library::{DHD_LIBRARY, HD_LIBRARY, LoadError, VendorLibrary};
pub use list::{Found, list_devices};
pub use mapping::workspace_mapping;
pub use openhaptics::{HD_STALL_TIMEOUT_S, HdClock, HdDevice, HdInfo};
pub use spec::{
    DEFAULT_OVERRUN_BUDGET, DeviceKind, MAX_DHD_INDEX, OpenedDevice, SpecError, open_device,
    open_devices, parse_devices,
};
pub use udp::{UDP_FIRST_TIMEOUT_S, UDP_TIMEOUT_S, UdpCounters, UdpDevice, UdpOptions};
