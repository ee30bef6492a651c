//! What every equation of state shares (the parent module's documentation explains the
//! sound-speed floor and the compression guard): one state's pressure and sound speed, the
//! floor and the guard. A leaf of the folder, so that the models and their dispatch
//! ([`super::Eos`]) both import it without a cycle.

use crate::math::{real, Real};

/// Pressure and squared bulk sound speed at one state.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct EosState {
    /// Pressure, Pa, positive in compression.
    pub p: Real,
    /// Squared isentropic bulk sound speed `dP/drho|_s = dP/drho|_e + P/rho² dP/de|_rho`,
    /// m²/s² (floored where documented in the module doc).
    pub c2: Real,
}

/// Lower bound of `c²` as a fraction of the model's reference `c0²` (dimensionless), used
/// only in states where the model itself gives `c² <= 0` (module doc, "Sound-speed
/// floor"): the floored sound speed is 1 % of `c0`.
pub const C2_FLOOR_FRACTION: Real = 1e-4;

/// Value of `1 - s y` (dimensionless; `= c0/Us` on the Hugoniot) at which the linear
/// `Us`–`up` reference curves stop and are continued linearly in `rho` (module doc,
/// "Compression guard").
pub const HUGONIOT_GUARD: Real = 0.1;

/// Guard density (kg/m³) of a linear `Us = c0 + s up` Hugoniot: the density where
/// `1 - s y = HUGONIOT_GUARD`, `y = 1 - rho0/rho`, i.e. `rho0 / (1 - (1 - HUGONIOT_GUARD)/s)`.
/// Infinite when the curve has no pole at finite density (`s <= 1 - HUGONIOT_GUARD`).
#[inline]
pub fn guard_density(rho0: Real, s: Real) -> Real {
    let y_g = (1.0 - HUGONIOT_GUARD) / s;
    if s > 0.0 && y_g < 1.0 {
        rho0 / (1.0 - y_g)
    } else {
        Real::INFINITY
    }
}

/// `max(c2, C2_FLOOR_FRACTION c_ref2)` (m²/s²), see the module doc.
#[inline(always)]
pub(crate) fn floor_c2(c2: Real, c_ref2: Real) -> Real {
    real::max(c2, C2_FLOOR_FRACTION * c_ref2)
}
