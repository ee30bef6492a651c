//! Enums a scene names by a string (`scheme = "ts2"`, `kernel = "wendland_c2"`, `limiter`,
//! `riemann`, `muscl_time`): with the feature `serde` each reads from its name through its
//! `from_name` and writes its name, and an unknown name is refused with the one-line
//! reason the scene check gives (`unknown scheme `rk4` (known: av, pm, ts1, ts2, tkc)`;
//! the value shown is an excerpt: at most 40 characters, control characters escaped).

use core::fmt;

/// At most 40 characters of a value, control characters escaped, `…` when cut.
pub struct Excerpt<'a>(pub &'a str);

impl fmt::Display for Excerpt<'_> {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        use fmt::Write;
        for (shown, c) in self.0.chars().enumerate() {
            if shown == 40 {
                return f.write_char('…');
            }
            if c.is_control() {
                for e in c.escape_default() {
                    f.write_char(e)?;
                }
            } else {
                f.write_char(c)?;
            }
        }
        Ok(())
    }
}

/// `impl Deserialize` (from the name, by `from_name`; else `unknown WHAT `NAME` (known:
/// KNOWN)`) and `impl Serialize` (the name, by `Display`) for a named enum.
#[cfg(feature = "serde")]
macro_rules! serde_by_name {
    ($t:ty, $what:literal, $known:expr) => {
        impl<'de> serde::Deserialize<'de> for $t {
            fn deserialize<De: serde::Deserializer<'de>>(d: De) -> Result<Self, De::Error> {
                struct V;
                impl serde::de::Visitor<'_> for V {
                    type Value = $t;
                    fn expecting(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
                        f.write_str(concat!("a ", $what, " name"))
                    }
                    fn visit_str<E: serde::de::Error>(self, v: &str) -> Result<$t, E> {
                        <$t>::from_name(v).ok_or_else(|| {
                            E::custom(format_args!(
                                concat!("unknown ", $what, " `{}` (known: {})"),
                                $crate::named::Excerpt(v),
                                $known
                            ))
                        })
                    }
                }
                d.deserialize_str(V)
            }
        }

        impl serde::Serialize for $t {
            fn serialize<S: serde::Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
                s.collect_str(self)
            }
        }
    };
}

#[cfg(feature = "serde")]
mod impls {
    use crate::kernel::Kernel;
    use crate::limiter::Limiter;
    use crate::riemann::Dissipation;
    use crate::schemes::options::{
        EnergyEquation, Integrator, MusclTime, RiemannSolver, SpecificVolume,
    };
    use crate::schemes::scheme::Scheme;

    serde_by_name!(Scheme, "scheme", "av, pm, ts1, ts2, tkc");
    serde_by_name!(Kernel, "kernel", "cubic_spline, wendland_c2, gaussian");
    serde_by_name!(
        Limiter,
        "limiter",
        "minmod, superbee, mc, vanleer, sweby:BETA"
    );
    serde_by_name!(RiemannSolver, "Riemann solver", RiemannSolver::KNOWN);
    serde_by_name!(Dissipation, "dissipation", "compression, full");
    serde_by_name!(MusclTime, "value", "predictor, courant, none");
    serde_by_name!(Integrator, "integrator", Integrator::KNOWN);
    serde_by_name!(SpecificVolume, "specific volume", SpecificVolume::KNOWN);
    serde_by_name!(EnergyEquation, "energy equation", EnergyEquation::KNOWN);
}
